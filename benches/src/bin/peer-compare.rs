//! Times our fit and evaluation on the peers' workloads and prints records that
//! `../shared/peers/compare.py --rust` lines up with scipy's (same ids).
//!
//! `cargo run --release -p rbf-benches --bin peer-compare -- [--fit 2000,8000] [--eval 2000] [--grid 100]`

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
            .map(|s| s.split(',').filter_map(|x| x.parse().ok()).collect())
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
        rbf_solve::par_values(&view, &points, &mut out).expect("lengths");
        let mut times = Vec::new();
        for _ in 0..repeats {
            let t = Instant::now();
            rbf_solve::par_values(&view, &points, &mut out).expect("lengths");
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
    println!("{{\"records\": [\n  {}\n]}}", records.join(",\n  "));
}
