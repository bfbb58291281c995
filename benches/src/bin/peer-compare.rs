//! Times our fit and evaluation on the peers' workloads and prints records that
//! `../shared/peers/compare.py --rust` lines up with scipy's (same ids).
//!
//! `cargo run --release -p rbf-benches --bin peer-compare -- [--fit 2000,8000] [--eval 2000] [--grid 100] [--all-methods] [--mesh]`
//! (`--fit 0 --eval 0 --mesh` times only the meshing workloads).

use std::time::Instant;

use rbf_benches::{grid, sphere_constraints};
use rbf_core::{FitSettings, System};
use rbf_solve::{SolveOptions, Strategy};

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn sizes(args: &[String], flag: &str, default: &[usize]) -> Vec<usize> {
    match args.iter().position(|a| a == flag) {
        Some(i) => args
            .get(i + 1)
            .map(|s| {
                s.split(',')
                    .filter_map(|x| x.parse().ok())
                    .filter(|&x| x > 0)
                    .collect()
            })
            .unwrap_or_default(),
        None => default.to_vec(),
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let fits = sizes(&args, "--fit", &[2000, 8000]);
    let evals = sizes(&args, "--eval", &[2000]);
    let grid_n = sizes(&args, "--grid", &[100])
        .first()
        .copied()
        .unwrap_or(100);
    let repeats = sizes(&args, "--repeats", &[3])
        .first()
        .copied()
        .unwrap_or(3);
    let threads = rayon::current_num_threads();
    let mut records = Vec::new();
    let settings = FitSettings::default();

    for &k in &fits {
        let cs = sphere_constraints(k, 0);
        for (label, strategy) in [
            ("rbf_scipy_fit", Strategy::Auto),
            ("rbf_lu_fit", Strategy::Lu),
            ("rbf_lblt_fit", Strategy::Lblt),
        ] {
            if strategy != Strategy::Auto && !args.iter().any(|a| a == "--all-methods") {
                continue;
            }
            let options = SolveOptions {
                strategy,
                ..Default::default()
            };
            let mut times = Vec::new();
            let mut last = None;
            for _ in 0..repeats {
                let t = Instant::now();
                let system = System::new(&cs, &settings).expect("valid workload");
                let fit = rbf_solve::solve(&system, &settings, &options).expect("fit");
                times.push(t.elapsed().as_secs_f64());
                last = Some(fit.report);
            }
            let report = last.expect("at least one run");
            eprintln!(
                "{label}[K={k}] {:.3} s  {:?} residual {:.1e} condition {:.1e} refinements {}",
                median(times.clone()),
                report.method,
                report.residual,
                report.condition,
                report.refinements
            );
            records.push(format!(
                "{{\"id\": \"{label}[K={k}]\", \"median_s\": {}, \"threads\": {threads}}}",
                median(times)
            ));
        }
    }

    for &k in &evals {
        let cs = sphere_constraints(k, 0);
        let fit = rbf_solve::fit(&cs, &settings).expect("fit");
        let points = grid(grid_n);
        let mut out = vec![0.0; points.len()];
        let view = fit.interpolant.view();
        view.par_values(&points, &mut out).expect("lengths");
        let mut times = Vec::new();
        for _ in 0..repeats {
            let t = Instant::now();
            view.par_values(&points, &mut out).expect("lengths");
            times.push(t.elapsed().as_secs_f64());
        }
        let s = median(times);
        let q = points.len();
        eprintln!(
            "rbf_scipy_eval[K={k},Q={q}] {s:.3} s  {:.2} G kernel evaluations/s",
            (k * q) as f64 / s / 1e9
        );
        records.push(format!(
            "{{\"id\": \"rbf_scipy_eval[K={k},Q={q}]\", \"median_s\": {s}, \"threads\": {threads}}}"
        ));
    }
    if args.iter().any(|a| a == "--mesh") {
        mesh_workloads(repeats, threads, &mut records);
    }
    println!("{{\"records\": [\n  {}\n]}}", records.join(",\n  "));
}

/// Times `f` `repeats` times after one warm-up run and records the median under `id`.
fn record(
    id: String,
    repeats: usize,
    threads: usize,
    records: &mut Vec<String>,
    mut f: impl FnMut(),
) -> f64 {
    f();
    let mut times = Vec::new();
    for _ in 0..repeats {
        let t = Instant::now();
        f();
        times.push(t.elapsed().as_secs_f64());
    }
    let s = median(times);
    eprintln!("{id} {s:.3} s");
    records.push(format!(
        "{{\"id\": \"{id}\", \"median_s\": {s}, \"threads\": {threads}}}"
    ));
    s
}

/// The workloads of `peer_voxel.py`, `peer_edt.py` and the polygonizer's goal.
fn mesh_workloads(repeats: usize, threads: usize, records: &mut Vec<String>) {
    use rbf_mesh::{
        PolygonizeSettings, Resolution, VoxelMethod, VoxelSettings, polygonize_continuation,
        polygonize_grid, signed_distance, surface_seeds, voxelize, winding_numbers,
    };
    let sphere = rbf_benches::icosphere(5);
    for res in [128_usize, 256] {
        // The peers' pitch is 2.4 / res over the sphere's diameter of 2.
        let across = (2.0 * res as f64 / 2.4).round() as usize;
        for s in [1_usize, 4] {
            let settings = VoxelSettings {
                resolution: across,
                supersampling: s,
                method: VoxelMethod::Rays,
                margin: 2,
                memory_limit: None,
            };
            record(
                format!("vox_rbf_rays_s{s}[mesh=icosphere,res={res}]"),
                repeats,
                threads,
                records,
                || {
                    voxelize(&sphere, &settings).expect("voxelize");
                },
            );
        }
        let pitch = 2.4 / res as f64;
        let centres: Vec<[f64; 3]> = (0..res * res * res)
            .map(|p| {
                let (i, j, k) = (p / (res * res), (p / res) % res, p % res);
                [
                    -1.2 + (i as f64 + 0.5) * pitch,
                    -1.2 + (j as f64 + 0.5) * pitch,
                    -1.2 + (k as f64 + 0.5) * pitch,
                ]
            })
            .collect();
        record(
            format!("vox_rbf_winding[mesh=icosphere,res={res}]"),
            repeats.min(2),
            threads,
            records,
            || {
                winding_numbers(&sphere, &centres);
            },
        );
    }
    for m in [128_usize, 256] {
        let mask = rbf_benches::torus_and_ball(m);
        record(
            format!("edt_rbf_signed[n={m}]"),
            repeats,
            threads,
            records,
            || {
                signed_distance(&mask);
            },
        );
    }
    // A model of 3000 constraint points: 1500 oriented points on a torus.
    let cs = rbf_core::shapes::torus(1500, 0.35);
    let settings = FitSettings::default();
    let fit = rbf_solve::fit(&cs, &settings).expect("fit");
    let model = rbf_core::Model {
        constraints: cs,
        settings,
        interpolant: fit.interpolant,
        report: None,
    };
    let f = model.interpolant.view();
    let s = PolygonizeSettings {
        resolution: Resolution::Cells(256),
        ..Default::default()
    };
    let seeds = surface_seeds(&model);
    record(
        "mc_rbf_continuation[K=3000,n=256]".into(),
        repeats,
        threads,
        records,
        || {
            polygonize_continuation(&f, &seeds, &s).expect("mesh");
        },
    );
    record(
        "mc_rbf_grid[K=3000,n=256]".into(),
        repeats.min(2),
        threads,
        records,
        || {
            polygonize_grid(&f, &s).expect("mesh");
        },
    );
    let (mesh, stats) = polygonize_continuation(&f, &seeds, &s).expect("mesh");
    eprintln!(
        "  {} triangles over {:?} cubes",
        mesh.triangles().len(),
        stats.cells
    );
    // For benches/peers/sample_and_march.py: the model and the lattice it was polygonized on.
    let dir = std::env::temp_dir();
    let _ = std::fs::write(dir.join("rbf-torus3000.json"), model.to_json());
    let _ = std::fs::write(
        dir.join("rbf-torus3000-lattice.json"),
        format!(
            "{{\"cells\": {:?}, \"origin\": {:?}, \"cell_size\": {:?}}}",
            stats.cells, stats.origin, stats.cell_size
        ),
    );
}
