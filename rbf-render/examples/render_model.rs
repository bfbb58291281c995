//! Fit two shapes and render them: one scene with shadows and reflections, and their CSG
//! difference.
//!
//! Run: `cargo run --release -p rbf-render --example render_model [OUT_DIR]`

use rbf_core::{Constraint, FitSettings, fit};
use rbf_render::{Camera, Csg, Object, RenderSettings, render, surface_bounds};

/// Oriented points on a sphere.
fn sphere(centre: [f64; 3], radius: f64) -> Vec<Constraint<3>> {
    (0..60)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / 60.0;
            let t = i as f64 * 2.399_963;
            let r = (1.0 - z * z).sqrt();
            let d = [r * t.cos(), z, r * t.sin()];
            Constraint::normal(core::array::from_fn(|k| centre[k] + radius * d[k]), d)
        })
        .collect()
}

fn main() {
    let dir = std::env::args()
        .nth(1)
        .map_or_else(std::env::temp_dir, Into::into);
    let settings = FitSettings::default();
    let (Ok(a), Ok(b)) = (
        fit(&sphere([0.0; 3], 1.0), &settings),
        fit(&sphere([0.8, 0.3, 0.0], 0.7), &settings),
    ) else {
        eprintln!("fit failed");
        std::process::exit(3);
    };
    let models = [a.interpolant.view(), b.interpolant.view()];
    let look = RenderSettings {
        shadows: true,
        reflections: 1,
        ..Default::default()
    };
    for (name, objects) in [
        (
            "scene.png",
            vec![Object::new(Csg::Model(0), 0), Object::new(Csg::Model(1), 1)],
        ),
        (
            "difference.png",
            vec![Object::new(
                Csg::Difference(Box::new(Csg::Model(0)), Box::new(Csg::Model(1))),
                0,
            )],
        ),
    ] {
        let result = surface_bounds(&models, &objects, &look).and_then(|(lo, hi)| {
            let camera = Camera::orbit(lo, hi, 30.0, 25.0, 320, 240);
            render(&models, &objects, &camera, &look)
        });
        let written = result.and_then(|(image, stats)| {
            println!(
                "{name}: {} rays, {} evaluations",
                stats.rays, stats.evaluations
            );
            image.to_png()
        });
        match written.map(|png| std::fs::write(dir.join(name), png)) {
            Ok(Ok(())) => println!("wrote {}", dir.join(name).display()),
            Ok(Err(e)) => eprintln!("{e}"),
            Err(e) => eprintln!("{e}"),
        }
    }
}
