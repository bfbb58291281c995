//! Meshing: polygonizing 3000-row models (a Fibonacci torus and the peers' random sphere),
//! voxelizing, winding numbers, distance transforms.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use rbf_benches::{random_sphere_model, torus_model};
use rbf_mesh::{
    PolygonizeSettings, Resolution, VoxelMethod, VoxelSettings, polygonize_continuation,
    polygonize_grid, signed_distance, surface_seeds, voxelize,
};

fn mesh(c: &mut Criterion) {
    let mut group = c.benchmark_group("mesh");
    group.sample_size(10);
    for (name, model) in [
        ("torus", torus_model(1500)),
        ("random-sphere", random_sphere_model(3000)),
    ] {
        let f = model.interpolant.view();
        let seeds = surface_seeds(&model);
        for n in [128_usize, 256] {
            let s = PolygonizeSettings {
                resolution: Resolution::Cells(n),
                ..Default::default()
            };
            let id =
                |method: &str| BenchmarkId::new(format!("polygonize-{method}-{name}-K3000"), n);
            group.bench_function(id("continuation"), |b| {
                b.iter(|| polygonize_continuation(&f, &seeds, &s).expect("mesh"))
            });
            group.bench_function(id("grid"), |b| {
                b.iter(|| polygonize_grid(&f, &s).expect("mesh"))
            });
        }
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
