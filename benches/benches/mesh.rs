//! Meshing: polygonizing a 3000-point model, voxelizing, winding numbers, distance transforms.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use rbf_core::{Constraint, FitSettings, Model};
use rbf_mesh::{
    PolygonizeSettings, Resolution, VoxelMethod, VoxelSettings, polygonize_continuation,
    polygonize_grid, signed_distance, surface_seeds, voxelize,
};

fn torus_model(n: usize) -> Model<3> {
    let golden = (5f64.sqrt() - 1.0) / 2.0;
    let cs: Vec<Constraint<3>> = (0..n)
        .map(|i| {
            let u = std::f64::consts::TAU * (i as f64 + 0.5) / n as f64;
            let v = std::f64::consts::TAU * (i as f64 * golden).fract();
            let normal = [v.cos() * u.cos(), v.cos() * u.sin(), v.sin()];
            let p = [
                (1.0 + 0.35 * v.cos()) * u.cos(),
                (1.0 + 0.35 * v.cos()) * u.sin(),
                0.35 * v.sin(),
            ];
            Constraint::normal(p, normal)
        })
        .collect();
    let settings = FitSettings::default();
    let fit = rbf_solve::fit(&cs, &settings).expect("fit");
    Model {
        constraints: cs,
        settings,
        interpolant: fit.interpolant,
        report: None,
    }
}

fn mesh(c: &mut Criterion) {
    let mut group = c.benchmark_group("mesh");
    group.sample_size(10);
    let model = torus_model(1500);
    let f = model.interpolant.view();
    let seeds = surface_seeds(&model);
    for n in [128_usize, 256] {
        let s = PolygonizeSettings {
            resolution: Resolution::Cells(n),
            ..Default::default()
        };
        group.bench_function(BenchmarkId::new("polygonize-continuation-K3000", n), |b| {
            b.iter(|| polygonize_continuation(&f, &seeds, &s).expect("mesh"))
        });
        group.bench_function(BenchmarkId::new("polygonize-grid-K3000", n), |b| {
            b.iter(|| polygonize_grid(&f, &s).expect("mesh"))
        });
    }
    let sphere = rbf_benches::icosphere(5);
    for res in [107_usize, 213] {
        let s = VoxelSettings {
            resolution: res,
            method: VoxelMethod::Rays,
            ..Default::default()
        };
        group.bench_function(BenchmarkId::new("voxelize-rays-s4-icosphere", res), |b| {
            b.iter(|| voxelize(&sphere, &s).expect("voxelize"))
        });
    }
    let mask = rbf_benches::torus_and_ball(256);
    group.bench_function(BenchmarkId::new("signed-distance", 256), |b| {
        b.iter(|| signed_distance(&mask))
    });
    group.finish();
}

criterion_group!(benches, mesh);
criterion_main!(benches);
