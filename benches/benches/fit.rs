//! Fitting time against K, on the peers' workload (`peer_rbf.py`): K/2 points on the unit
//! sphere with value 0 and K/2 moved 0.01 inward with value 1, r³ kernel; the iterative solver
//! against the dense one where both run, and beyond; a refit of 1 % more constraints from zero
//! and from the earlier fit; greedy fits of 10⁴–10⁵ oriented points.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use rbf_benches::sphere_constraints;
use rbf_core::{FitSettings, System};
use rbf_solve::{SolveOptions, Strategy};

fn fit(c: &mut Criterion) {
    let settings = FitSettings::default();
    let mut group = c.benchmark_group("fit");
    group.sample_size(10);
    for k in [500_usize, 1000, 2000, 4000, 8000] {
        let cs = sphere_constraints(k, 0);
        // Up to 4000 the dense solver, at 8000 the iterative one (`rbf_solve::DENSE_LIMIT`).
        group.bench_with_input(BenchmarkId::new("auto", k), &cs, |b, cs| {
            b.iter(|| rbf_solve::fit(cs, &settings).expect("fit"))
        });
    }
    // The alternatives the default chooses between, at one size.
    let cs = sphere_constraints(2000, 0);
    let system = System::new(&cs, &settings).expect("valid");
    for (name, strategy) in [("lblt", Strategy::Lblt), ("lu", Strategy::Lu)] {
        let options = SolveOptions {
            strategy,
            ..Default::default()
        };
        group.bench_function(BenchmarkId::new(name, 2000), |b| {
            b.iter(|| rbf_solve::solve(&system, &settings, &options).expect("fit"))
        });
    }
    group.bench_function(BenchmarkId::new("core-dense-lu", 2000), |b| {
        b.iter(|| rbf_core::solve_dense(&system, &settings).expect("fit"))
    });
    group.finish();
}

/// Greedy fits of large oriented point sets to 1e-4 of the box (a dense fit of 10⁵ points
/// would need 200 000 rows: 320 GB).
fn greedy(c: &mut Criterion) {
    let settings = FitSettings::default();
    let greedy = rbf_solve::GreedySettings::default();
    let mut group = c.benchmark_group("greedy");
    group.sample_size(10);
    for n in [20_000_usize, 100_000] {
        let cs = rbf_core::shapes::torus(n, 0.35);
        group.bench_with_input(BenchmarkId::new("torus", n), &cs, |b, cs| {
            b.iter(|| rbf_solve::fit_greedy(cs, &settings, &greedy, |_| {}).expect("fit"))
        });
    }
    group.finish();
}

/// The same workload through both solvers at 8000 rows, and the iterative one at 2·10⁴ and
/// 5·10⁴ rows (dense: 3.2 and 20 GB), random points included (the workload's are random).
fn iterative(c: &mut Criterion) {
    let settings = FitSettings::default();
    let mut group = c.benchmark_group("iterative");
    group.sample_size(10);
    for k in [8000_usize, 20_000, 50_000] {
        let cs = sphere_constraints(k, 0);
        let system = System::new(&cs, &settings).expect("valid");
        group.bench_with_input(BenchmarkId::new("fgmres", k), &system, |b, system| {
            b.iter(|| {
                rbf_solve::solve_iterative(system, &settings, &Default::default(), |_| {})
                    .expect("fit")
            })
        });
        if k <= 8000 {
            group.bench_with_input(BenchmarkId::new("dense", k), &system, |b, system| {
                b.iter(|| {
                    rbf_solve::solve(system, &settings, &SolveOptions::default()).expect("fit")
                })
            });
        }
    }
    // One percent more constraints than an earlier fit took, as in a greedy round: solved from
    // zero, and from that fit (`rbf_solve::fit_from`).
    let cs = sphere_constraints(20_000, 0);
    let earlier = rbf_solve::fit(&cs[..19_800], &settings).expect("fit");
    group.bench_function(BenchmarkId::new("refit-from-zero", 20_000), |b| {
        b.iter(|| rbf_solve::fit(&cs, &settings).expect("fit"))
    });
    group.bench_function(BenchmarkId::new("refit-from-earlier", 20_000), |b| {
        b.iter(|| rbf_solve::fit_from(&cs, &settings, &earlier.interpolant).expect("fit"))
    });
    // And with the earlier fit's preconditioner kept (`rbf_solve::fit_from_keeping`): the 200
    // added rows get small subdomains of their own. The first 19 800 are fitted once more with
    // a preconditioner kept; each iteration then starts from it (a solve with a kept
    // preconditioner keeps it as it was).
    let mut kept = rbf_solve::KeptPreconditioner::default();
    rbf_solve::fit_from_keeping(&cs[..19_800], &settings, &earlier.interpolant, &mut kept)
        .expect("fit");
    group.bench_function(BenchmarkId::new("refit-kept-preconditioner", 20_000), |b| {
        b.iter(|| {
            rbf_solve::fit_from_keeping(&cs, &settings, &earlier.interpolant, &mut kept)
                .expect("fit")
        })
    });
    group.finish();
}

criterion_group!(benches, fit, iterative, greedy);
criterion_main!(benches);
