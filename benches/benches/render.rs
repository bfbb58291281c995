//! Rendering 3000-row models: a Fibonacci torus (1500 oriented points) and the peers' random
//! sphere (1500 random points and 1500 inside them), at 512² with the default settings
//! (anti-aliasing, shadows, floor) and as a 256² one-ray preview; the proved sphere tracer on
//! the preview for comparison.

use criterion::{Criterion, criterion_group, criterion_main};
use rbf_benches::{random_sphere_model, torus_model};
use rbf_render::{Camera, Csg, Lipschitz, Object, RenderSettings, render, surface_bounds};

fn render_models(c: &mut Criterion) {
    let mut group = c.benchmark_group("render");
    group.sample_size(10);
    let objects = [Object::new(Csg::Model(0), 0)];
    for (name, model) in [
        ("fibonacci torus", torus_model(1500)),
        ("random sphere", random_sphere_model(3000)),
    ] {
        let views = [model.interpolant.view()];
        let preview = RenderSettings {
            samples: 1,
            shadows: false,
            ..Default::default()
        };
        let proved = RenderSettings {
            lipschitz: Lipschitz::Guaranteed,
            ..preview.clone()
        };
        for (label, settings, side) in [
            ("512² default", RenderSettings::default(), 512),
            ("256² preview", preview, 256),
            ("256² preview guaranteed", proved, 256),
        ] {
            let (lo, hi) = surface_bounds(&views, &objects, &settings).expect("bounds");
            let camera = Camera::orbit(lo, hi, 30.0, 30.0, side, side);
            group.bench_function(format!("{name} 3000 rows {label}"), |b| {
                b.iter(|| render(&views, &objects, &camera, &settings).expect("render"))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, render_models);
criterion_main!(benches);
