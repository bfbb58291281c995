//! `rbf compare`: how far a model's surface lies from a mesh, both ways, in the mesh's units
//! and in voxels.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use rbf_convert::{CompareSettings, DistanceStats, surface_distance};

use crate::common::{read_mesh, read_model_3d};
use crate::failure::{BAD_INPUT, Failure, USAGE};

pub(crate) const HELP: &str = "\
Spreads points by area over the mesh and measures each to the model's surface, then spreads
points over the model's surface (polygonized finely) and measures each to the mesh: the mean,
RMS and largest distance each way, and the larger maximum (a sampled Hausdorff distance).
Unlike the errors `rbf convert` prints, which compare sets of boundary voxels and so move in
whole voxels, these are distances between the surfaces themselves.

Examples:
  rbf convert bunny.obj -o bunny.json --resolution 220
  rbf compare bunny.json bunny.obj --voxels 220
  rbf compare model.json scan.ply --samples 100000 --json";

#[derive(Args, Debug)]
pub(crate) struct CompareArgs {
    /// Model file (3D).
    model: PathBuf,
    /// Mesh to compare with (.obj, .ply, .stl).
    mesh: PathBuf,
    /// Points spread over each surface.
    #[arg(long, value_name = "N", default_value_t = 20_000)]
    samples: usize,
    /// Cubes across the mesh's longest side for polygonizing the model.
    #[arg(long, value_name = "N", default_value_t = 256)]
    resolution: usize,
    /// Also give distances in voxels of a grid of N along the mesh's longest side (as `rbf
    /// convert --resolution N`).
    #[arg(long, value_name = "N")]
    voxels: Option<usize>,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

pub(crate) fn run(args: &CompareArgs, quiet: bool) -> Result<(), Failure> {
    let source = args.model.display().to_string();
    let model = read_model_3d(&args.model, "compare")?;
    if args.samples == 0 || args.resolution == 0 || args.voxels == Some(0) {
        return Err(Failure::new(
            USAGE,
            "--samples, --resolution and --voxels must be at least 1".to_string(),
        ));
    }
    let mesh = read_mesh(&args.mesh)?;
    let settings = CompareSettings {
        samples: args.samples,
        resolution: args.resolution,
        ..Default::default()
    };
    let start = Instant::now();
    let spinner = crate::common::spinner(quiet || args.json, "measuring".into());
    let result = surface_distance(&model.interpolant.view(), &mesh, &settings);
    spinner.finish_and_clear();
    let d = result.map_err(|e| Failure::new(BAD_INPUT, format!("{source}: {e}")))?;
    let (lo, hi) = mesh.bounding_box();
    let longest = (0..3).map(|i| hi[i] - lo[i]).fold(0.0, f64::max);
    let voxel = args.voxels.map(|n| longest / n as f64);

    if args.json {
        let stats = |s: DistanceStats| {
            let mut v = serde_json::json!({"mean": s.mean, "rms": s.rms, "max": s.max});
            if let Some(h) = voxel {
                v["voxels"] =
                    serde_json::json!({"mean": s.mean / h, "rms": s.rms / h, "max": s.max / h});
            }
            v
        };
        let json = serde_json::json!({
            "model": source,
            "mesh": args.mesh.display().to_string(),
            "samples": d.samples,
            "cell_size": d.cell_size,
            "voxel_size": voxel,
            "mesh_to_surface": stats(d.mesh_to_surface),
            "surface_to_mesh": stats(d.surface_to_mesh),
            "hausdorff": d.hausdorff(),
        });
        println!("{json}");
        return Ok(());
    }
    let line = |name: &str, s: DistanceStats| {
        let mut text = format!(
            "{name}: mean {:.4e}, RMS {:.4e}, max {:.4e}",
            s.mean, s.rms, s.max
        );
        if let Some(h) = voxel {
            text += &format!(
                " ({:.3} / {:.3} / {:.3} voxels)",
                s.mean / h,
                s.rms / h,
                s.max / h
            );
        }
        println!("{text}");
    };
    line("mesh → surface", d.mesh_to_surface);
    line("surface → mesh", d.surface_to_mesh);
    let h = voxel.map_or(String::new(), |h| {
        format!(" ({:.3} voxels)", d.hausdorff() / h)
    });
    println!("Hausdorff (sampled): {:.4e}{h}", d.hausdorff());
    if !quiet {
        eprintln!(
            "{} points each way; the model polygonized in cubes of {:.4}; {:.2} s",
            d.samples,
            d.cell_size,
            start.elapsed().as_secs_f64()
        );
    }
    Ok(())
}
