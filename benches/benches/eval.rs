//! Evaluation throughput: f at a grid of points, K = 2000 centres (`peer_rbf.py`'s workload).
//! Throughput is reported in points per second; multiply by K for kernel evaluations.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use rbf_benches::{grid, sphere_constraints};
use rbf_core::FitSettings;

fn eval(c: &mut Criterion) {
    let k = 2000;
    let fit = rbf_solve::fit(&sphere_constraints(k, 0), &FitSettings::default()).expect("fit");
    let f64_model = fit.interpolant;
    let f32_model = f64_model.cast::<f32>();
    let points = grid(50); // 125 000 points
    let points32: Vec<[f32; 3]> = points.iter().map(|p| p.map(|v| v as f32)).collect();
    let mut out = vec![0.0; points.len()];
    let mut out32 = vec![0.0_f32; points.len()];

    let mut group = c.benchmark_group("eval-K2000");
    group.sample_size(10);
    group.throughput(Throughput::Elements(points.len() as u64));
    group.bench_function(BenchmarkId::new("parallel-f64", points.len()), |b| {
        b.iter(|| {
            f64_model
                .view()
                .par_values(&points, &mut out)
                .expect("lengths")
        })
    });
    group.bench_function(BenchmarkId::new("parallel-f32", points.len()), |b| {
        b.iter(|| {
            f32_model
                .view()
                .par_values(&points32, &mut out32)
                .expect("lengths")
        })
    });
    let few = &points[..8192];
    group.throughput(Throughput::Elements(few.len() as u64));
    group.bench_function(BenchmarkId::new("core-serial-f64", few.len()), |b| {
        b.iter(|| {
            f64_model
                .values(few, &mut out[..few.len()])
                .expect("lengths")
        })
    });
    group.bench_function(
        BenchmarkId::new("core-serial-gradients-f64", few.len()),
        |b| {
            let (mut values, mut gradients) = (vec![0.0; few.len()], vec![[0.0; 3]; few.len()]);
            b.iter(|| {
                f64_model
                    .view()
                    .values_and_gradients(few, &mut values, &mut gradients)
                    .expect("lengths")
            })
        },
    );
    group.bench_function(BenchmarkId::new("gradient-f64", few.len()), |b| {
        b.iter(|| {
            few.iter()
                .map(|p| f64_model.value_and_gradient(p).0)
                .sum::<f64>()
        })
    });
    group.finish();
}

criterion_group!(benches, eval);
criterion_main!(benches);
