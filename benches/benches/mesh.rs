//! Meshing: polygonizing 3000-row models (a Fibonacci torus and the peers' random sphere),
//! voxelizing, winding numbers (of oriented points: through the cluster hierarchy against direct
//! sums), distance transforms.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use rbf_benches::{random_sphere_model, torus_model};
use rbf_mesh::{
    PolygonizeSettings, Resolution, VoxelMethod, VoxelSettings, dipole_winding_numbers,
    polygonize_continuation, polygonize_grid, signed_distance, surface_seeds, voxelize,
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
    // 10⁴ oriented points on a sphere, each with its share of the area, and two probes per
    // point a twentieth of the radius inside and outside (as a scan's normals are judged).
    let n = 10_000;
    let points = rbf_core::shapes::fibonacci_sphere(n);
    let share = 4.0 * std::f64::consts::PI / n as f64;
    let moments: Vec<[f64; 3]> = points.iter().map(|p| p.map(|c| share * c)).collect();
    let probes: Vec<[f64; 3]> = points
        .iter()
        .flat_map(|p| [p.map(|c| 0.95 * c), p.map(|c| 1.05 * c)])
        .collect();
    group.bench_function(BenchmarkId::new("winding-dipoles-tree", n), |b| {
        b.iter(|| dipole_winding_numbers(&points, &moments, &probes))
    });
    group.bench_function(BenchmarkId::new("winding-dipoles-direct", n), |b| {
        b.iter(|| direct_dipole_sums(&points, &moments, &probes))
    });
    let mask = rbf_benches::torus_and_ball(256);
    group.bench_function(BenchmarkId::new("signed-distance", 256), |b| {
        b.iter(|| signed_distance(&mask))
    });
    group.finish();
}

/// The winding number of dipoles at `points` with `moments` at each probe, summed over every
/// dipole (what the scan pipeline did before the cluster hierarchy).
fn direct_dipole_sums(points: &[[f64; 3]], moments: &[[f64; 3]], probes: &[[f64; 3]]) -> Vec<f64> {
    use rayon::prelude::*;
    probes
        .par_iter()
        .map(|q| {
            let mut sum = 0.0;
            for (p, m) in points.iter().zip(moments) {
                let r = [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
                let r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
                if r2 > 0.0 {
                    sum += (m[0] * r[0] + m[1] * r[1] + m[2] * r[2]) / (r2 * r2.sqrt());
                }
            }
            sum / (4.0 * std::f64::consts::PI)
        })
        .collect()
}

criterion_group!(benches, mesh);
criterion_main!(benches);
