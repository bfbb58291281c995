//! Fit a surface, then evaluate it the way a device would: an `InterpolantView` over plain
//! slices, in f32, with no allocation (what `rbf export` bakes into flash).
//!
//! Run: `cargo run -p rbf-core --example fit_and_evaluate`

use rbf_core::{Constraint, FitSettings, InterpolantView, fit};

fn main() {
    // Six oriented points on the unit sphere: boundary constraints with outward normals.
    let directions = [
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let constraints: Vec<Constraint<3>> = directions
        .iter()
        .map(|&d| Constraint::normal(d, d))
        .collect();
    let fitted = match fit(&constraints, &FitSettings::default()) {
        Ok(f) => f,
        Err(e) => {
            eprintln!("fit failed: {e}");
            std::process::exit(3);
        }
    };
    println!(
        "fitted {} rows, residual {:.1e}",
        fitted.report.rows, fitted.report.residual
    );
    // What a device holds: arrays of f32 and a view over them.
    let small = fitted.interpolant.cast::<f32>();
    let (centres, weights) = (small.centres().to_vec(), small.weights().to_vec());
    let Ok(device) = InterpolantView::new(
        small.kernel(),
        &centres,
        &weights,
        small.constant(),
        small.linear(),
    ) else {
        unreachable!("as many weights as centres");
    };
    for p in [
        [0.0_f32, 0.0, 0.0],
        [0.7, 0.7, 0.0],
        [1.0, 0.0, 0.0],
        [1.5, 0.0, 0.0],
    ] {
        let v = device.value(&p);
        let side = if v > 0.0 {
            "inside"
        } else if v < 0.0 {
            "outside"
        } else {
            "on the surface"
        };
        println!("f({p:?}) = {v:+.5} ({side})");
    }
}
