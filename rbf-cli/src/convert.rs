//! `rbf convert`: a polygon mesh to an implicit surface.

use std::path::PathBuf;
use std::time::Instant;

use crate::fit_progress::FitMessages;
use clap::{Args, ValueEnum};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rbf_convert::{
    ConvertError, IterativeReport, IterativeSettings, NormalSettings, TopologyReport,
    convert_iterative, convert_normals,
};
use rbf_core::NormalOffset;

use crate::common::{read_mesh, write_atomically};
use crate::failure::{BAD_INPUT, Failure, USAGE};

pub(crate) const HELP: &str = "\
--method iterative (Yngve & Turk): voxelize the mesh (--resolution voxels along its longest side,
winding numbers if it is not watertight), then fit, measure the two-way error between the goal's
and the surface's boundary voxels, and add constraints where it is largest, until the error is
at most a voxel with an RMS of at most 0.3 voxel, 4 iterations bring no improvement,
--max-iterations pass or --max-constraints are placed. The best model seen is written; --report writes every iteration's figures as JSON.
For a closed mesh its topology is then kept: the voxel error cannot see gaps or parts thinner
than a voxel, so the middle of every gap and part narrower than two voxels is probed, probes on
the wrong side of the surface become exterior or interior constraints, and the surface is
fitted again; the summary line ends with the genus and components of the result against the
mesh's (--keep-topology false skips this). Where the loop falls short (a topology other than
the mesh's, or a surface more than two voxels off: a shell a couple of voxels thick, such as a
skull's), its rival is fitted too: normal constraints at an even spread of the vertices, 98 % of
the rows of --max-constraints, each inside point kept within thin walls. It is measured the same way
and written instead if it ranks better (the summary line says so).

--method normals (Turk & O'Brien, §4.3): every vertex becomes a boundary constraint with a normal
constraint a small distance inside, against the vertex normal; meshes with more vertices than
--max-constraints are thinned to an evenly spread subset first, or with --tolerance T the
vertices are chosen greedily until the surface meets every vertex within T of the box.

Examples:
  rbf convert bunny.obj -o bunny.json
  rbf convert bunny.obj -o bunny.json --resolution 220 --report bunny-report.json
  rbf convert scan.ply -o scan.json --method normals --max-constraints 2000
  rbf convert scan.ply -o scan.json --method normals --tolerance 1e-4
  rbf mesh bunny.json -o smooth_bunny.obj";

#[derive(Args, Debug)]
pub(crate) struct ConvertArgs {
    /// Mesh file (.obj, .ply, .stl).
    mesh: PathBuf,
    /// Model file to write.
    #[arg(short, long, value_name = "MODEL.json")]
    output: PathBuf,
    /// Conversion method.
    #[arg(long, value_enum, default_value_t = Method::Iterative)]
    method: Method,
    /// Most constraints placed [default: 4000 iterative; every vertex (two rows each) normals,
    /// or 5000 with --tolerance]; fewer vertices than the mesh has are spread evenly.
    #[arg(long, value_name = "N")]
    max_constraints: Option<usize>,
    /// Voxels along the longest side of the mesh's bounding box (iterative).
    #[arg(long, value_name = "N", default_value_t = 128)]
    resolution: usize,
    /// Most iterations (iterative).
    #[arg(long, value_name = "N", default_value_t = 30)]
    max_iterations: usize,
    /// Write every iteration's figures here as JSON (iterative).
    #[arg(long, value_name = "REPORT.json")]
    report: Option<PathBuf>,
    /// Keep a closed mesh's genus and components where its parts come closer than a voxel
    /// (iterative).
    #[arg(long, value_name = "BOOL", default_value_t = true, action = clap::ArgAction::Set)]
    keep_topology: bool,
    /// Regularization λ of the fit.
    #[arg(long, value_name = "L", default_value_t = 0.0)]
    lambda: f64,
    /// Normal constraint offset as a fraction of the bounding box's longest side (normals).
    #[arg(long, value_name = "F", default_value_t = 0.01)]
    offset: f64,
    /// Choose the vertices greedily until the surface meets every one within this fraction of
    /// the bounding box's longest side (normals).
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    tolerance: Option<f64>,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum Method {
    /// Voxelize, then add constraints where the error is largest, iteration by iteration.
    Iterative,
    /// A boundary and a normal constraint at each vertex.
    Normals,
}

pub(crate) fn run(args: &ConvertArgs, quiet: bool, verbose: bool) -> Result<(), Failure> {
    let mesh = read_mesh(&args.mesh)?;
    let source = args.mesh.display().to_string();
    let failure = |e: ConvertError| match e {
        ConvertError::Fit(f) => Failure::fit(&source, &f),
        other => Failure::new(BAD_INPUT, format!("{source}: {other}")),
    };
    let start = Instant::now();
    match args.method {
        Method::Normals => {
            let settings = NormalSettings {
                offset: NormalOffset::Relative(args.offset),
                max_vertices: args.max_constraints.unwrap_or(usize::MAX),
                lambda: args.lambda,
                tolerance: args.tolerance,
            };
            if let Some(t) = args.tolerance
                && !(t >= 0.0 && t.is_finite())
            {
                return Err(Failure::new(
                    USAGE,
                    format!("--tolerance must be a finite number ≥ 0, not {t}"),
                ));
            }
            let spinner = crate::common::spinner(quiet, "fitting normal constraints".into());
            let mut messages = FitMessages::new(rbf_core::FitSettings::default().max_residual);
            let result = convert_normals(&mesh, &settings, |p| {
                spinner.set_message(messages.message(p));
            });
            spinner.finish_and_clear();
            let (model, report) = result.map_err(failure)?;
            write_atomically(&args.output, model.to_json().as_bytes())?;
            if let Some((worst, false)) = report.greedy {
                eprintln!(
                    "rbf: warning: {} vertices still miss by up to {worst:.2e} of the box; raise --max-constraints or --tolerance",
                    report.vertices_used
                );
            }
            if !quiet {
                let thinned = match report.greedy {
                    Some((worst, _)) => {
                        format!(" (chosen greedily: every vertex within {worst:.1e} of the box)")
                    }
                    None if report.thinned => " (thinned evenly)".into(),
                    None => String::new(),
                };
                let how = match report.fit.method {
                    rbf_core::SolveMethod::Iterative => {
                        format!("{} iterations", report.fit.iterations)
                    }
                    _ => format!("condition ≈ {:.1e}", report.fit.condition),
                };
                eprintln!(
                    "{} of {} vertices used{thinned}, {} without a normal; {} rows, residual {:.1e}, {how}; {:.2} s; wrote {}",
                    report.vertices_used,
                    report.vertices,
                    report.without_normal,
                    report.fit.rows,
                    report.fit.residual,
                    start.elapsed().as_secs_f64(),
                    args.output.display()
                );
            }
        }
        Method::Iterative => {
            let settings = IterativeSettings {
                resolution: args.resolution,
                max_iterations: args.max_iterations,
                max_constraints: args
                    .max_constraints
                    .unwrap_or(IterativeSettings::default().max_constraints),
                lambda: args.lambda,
                keep_topology: args.keep_topology,
                ..Default::default()
            };
            let bar = ProgressBar::new(settings.max_iterations as u64);
            if quiet {
                bar.set_draw_target(ProgressDrawTarget::hidden());
            }
            bar.set_style(
                ProgressStyle::with_template("{bar:30} {pos}/{len} iterations {msg}")
                    .unwrap_or_else(|_| ProgressStyle::default_bar()),
            );
            bar.set_message("voxelizing");
            let result = convert_iterative(&mesh, &settings, |it, _| {
                if verbose {
                    bar.suspend(|| {
                        eprintln!(
                            "iteration {:2}: {} boundary / {} interior / {} exterior, max {:.2} / RMS {:.3} voxels; fit {:.2} s, evaluate {:.2} s, distances {:.2} s, select {:.3} s",
                            it.iteration, it.boundary, it.interior, it.exterior, it.max_error, it.rms_error,
                            it.fit_seconds, it.evaluate_seconds, it.distance_seconds, it.select_seconds
                        )
                    });
                }
                bar.set_position(it.iteration as u64);
                bar.set_message(format!(
                    "max {:.2} / RMS {:.2} voxels, {} constraints",
                    it.max_error,
                    it.rms_error,
                    it.boundary + it.interior + it.exterior
                ));
            });
            bar.finish_and_clear();
            let (model, report) = result.map_err(failure)?;
            write_atomically(&args.output, model.to_json().as_bytes())?;
            if let Some(path) = &args.report {
                write_atomically(path, report_json(&report).as_bytes())?;
            }
            if !quiet {
                let best = report.iterations[report
                    .best
                    .saturating_sub(1)
                    .min(report.iterations.len() - 1)];
                let the_loop = format!(
                    "best of {} iterations: {}: max error {:.2} voxels, RMS {:.2}, {} boundary / {} interior / {} exterior constraints",
                    report.iterations.len(),
                    best.iteration,
                    best.max_error,
                    best.rms_error,
                    best.boundary,
                    best.interior,
                    best.exterior,
                );
                let kept = match report.rival {
                    Some(r) if r.kept => format!(
                        "the loop fell short ({the_loop}); kept its rival, normal constraints at {} vertices: max error {:.2} voxels, RMS {:.2}",
                        r.vertices, r.max_error, r.rms_error
                    ),
                    Some(r) => format!(
                        "{the_loop} (its rival, normal constraints at {} vertices, ranked lower: max error {:.2} voxels, RMS {:.2}, {})",
                        r.vertices,
                        r.max_error,
                        r.rms_error,
                        match r.topology {
                            Some((Some(g), c)) => format!("genus {g}, {c} component(s)"),
                            Some((None, _)) => "not closed".to_string(),
                            None => "its topology not measured".to_string(),
                        }
                    ),
                    None => the_loop,
                };
                eprintln!(
                    "{} × {} × {} voxels{}; {kept}{}; {:.1} s; wrote {}",
                    report.shape[0],
                    report.shape[1],
                    report.shape[2],
                    if report.watertight {
                        ""
                    } else {
                        " (not watertight: winding numbers)"
                    },
                    report
                        .topology
                        .map_or(String::new(), |t| topology_summary(&t)),
                    start.elapsed().as_secs_f64(),
                    args.output.display()
                );
            }
        }
    }
    Ok(())
}

/// The topology check for the summary line.
fn topology_summary(t: &TopologyReport) -> String {
    let genus = t.genus.map_or("open".to_string(), |g| format!("genus {g}"));
    let added = match (t.added, t.polished) {
        (0, 0) => String::new(),
        (a, 0) => format!(" (of which {a} in thin gaps and parts)"),
        (a, p) => {
            format!(" (+{p} where the surface strayed from the mesh; {a} in thin gaps and parts)")
        }
    };
    if t.agrees() {
        format!(
            "{added}; topology kept: {genus}, {} component(s)",
            t.components
        )
    } else {
        format!(
            "{added}; TOPOLOGY DIFFERS: {genus}, {} component(s), the mesh has genus {}, {}",
            t.components, t.goal_genus, t.goal_components
        )
    }
}

/// The report as JSON: the grid, and every iteration's figures.
fn report_json(report: &IterativeReport) -> String {
    let iterations: Vec<serde_json::Value> = report
        .iterations
        .iter()
        .map(|it| {
            serde_json::json!({
                "iteration": it.iteration,
                "boundary": it.boundary,
                "interior": it.interior,
                "exterior": it.exterior,
                "violated_probes": it.violated_probes,
                "max_error_voxels": it.max_error,
                "rms_error_voxels": it.rms_error,
                "fit_seconds": it.fit_seconds,
                "evaluate_seconds": it.evaluate_seconds,
                "distance_seconds": it.distance_seconds,
                "select_seconds": it.select_seconds,
            })
        })
        .collect();
    serde_json::json!({
        "shape": report.shape,
        "voxel_size": report.voxel_size,
        "watertight": report.watertight,
        "best_iteration": report.best,
        "iterations": iterations,
        "topology": report.topology.map(|t| serde_json::json!({
            "mesh_genus": t.goal_genus,
            "mesh_components": t.goal_components,
            "genus": t.genus,
            "components": t.components,
            "agrees": t.agrees(),
            "cell": t.cell,
            "probes": t.probes,
            "added": t.added,
            "polished": t.polished,
            "seconds": t.seconds,
        })),
        "rival": report.rival.map(|r| serde_json::json!({
            "vertices": r.vertices,
            "max_error_voxels": r.max_error,
            "rms_error_voxels": r.rms_error,
            "genus": r.topology.and_then(|t| t.0),
            "components": r.topology.map(|t| t.1),
            "kept": r.kept,
        })),
    })
    .to_string()
}
