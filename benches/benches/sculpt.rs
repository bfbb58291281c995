//! Sculpting: one edit re-solved by updating the factorization, against a fresh fit, at 2000
//! constraints.

use criterion::{Criterion, criterion_group, criterion_main};
use rbf_benches::Rng;
use rbf_core::{Constraint, FitSettings, Kernel};
use rbf_sculpt::{IncrementalFit, Row};

/// 1999 points on a bumpy sphere and an interior point.
fn rows(n: usize) -> Vec<Row<3>> {
    let mut rng = Rng::new(7);
    let mut rows: Vec<Row<3>> = (0..n - 1)
        .map(|_| {
            let v = [rng.normal(), rng.normal(), rng.normal()];
            let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-9);
            let r: f64 = 1.0 + 0.1 * (3.0 * v[0] / len).sin();
            Row {
                position: v.map(|x| r * x / len),
                value: 0.0,
            }
        })
        .collect();
    rows.push(Row {
        position: [0.0; 3],
        value: 1.0,
    });
    rows
}

fn sculpt(c: &mut Criterion) {
    let mut group = c.benchmark_group("sculpt");
    group.sample_size(10);
    let rows = rows(2000);
    let constraints: Vec<Constraint<3>> = rows
        .iter()
        .map(|r| {
            if r.value > 0.0 {
                Constraint::interior(r.position, r.value)
            } else {
                Constraint::boundary(r.position)
            }
        })
        .collect();
    let settings = FitSettings {
        kernel: Some(Kernel::Cubic),
        ..Default::default()
    };
    group.bench_function("fresh fit, 2000 constraints (rbf_solve::fit)", |b| {
        b.iter(|| rbf_solve::fit(&constraints, &settings).expect("fit"))
    });
    let mut fit = IncrementalFit::new(Kernel::Cubic, &rows).expect("factor");
    let mut k = 0usize;
    group.bench_function(
        "edit: move one constraint and re-solve, 2000 constraints",
        |b| {
            b.iter(|| {
                // Move a row near the end of the factor out and back (delete + bordered append).
                k = (k + 1) % 8;
                let id = 1990 - k;
                let mut row = fit.row(id).expect("row");
                row.position[0] += 1e-3;
                fit.replace(id, row).expect("replace");
                fit.interpolant().expect("solve")
            })
        },
    );
    group.bench_function("edit: add a constraint and re-solve, then remove it", |b| {
        b.iter(|| {
            let id = fit
                .push(Row {
                    position: [0.0, 0.0, 1.5],
                    value: 0.0,
                })
                .expect("push");
            let f = fit.interpolant().expect("solve");
            fit.remove(id).expect("remove");
            f
        })
    });
    group.finish();
}

criterion_group!(benches, sculpt);
criterion_main!(benches);
