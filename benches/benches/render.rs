//! Rendering: sphere tracing a 3000-row model (a torus of 1500 oriented points).

use criterion::{Criterion, criterion_group, criterion_main};
use rbf_benches::torus_model;
use rbf_render::{Camera, Csg, Lipschitz, Object, RenderSettings, render, surface_bounds};

fn render_torus(c: &mut Criterion) {
    let mut group = c.benchmark_group("render");
    group.sample_size(10);
    let model = torus_model(1500);
    let views = [model.interpolant.view()];
    let objects = [Object::new(Csg::Model(0), 0)];
    for (name, lipschitz, shadows) in [
        ("auto", Lipschitz::Auto, false),
        ("auto+shadows", Lipschitz::Auto, true),
        ("guaranteed", Lipschitz::Guaranteed, false),
    ] {
        let settings = RenderSettings {
            samples: 1,
            shadows,
            lipschitz,
            ..Default::default()
        };
        let (lo, hi) = surface_bounds(&views, &objects, &settings).expect("bounds");
        let camera = Camera::orbit(lo, hi, 30.0, 30.0, 256, 256);
        group.bench_function(format!("torus 3000 rows 256² {name}"), |b| {
            b.iter(|| render(&views, &objects, &camera, &settings).expect("render"))
        });
    }
    group.finish();
}

criterion_group!(benches, render_torus);
criterion_main!(benches);
