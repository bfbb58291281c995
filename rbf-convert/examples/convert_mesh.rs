//! Convert a polygon mesh to an implicit surface by the iterative method, printing each
//! iteration's errors.
//!
//! Run: `cargo run --release -p rbf-convert --example convert_mesh [MESH] [RESOLUTION]`

use std::path::PathBuf;

use rbf_convert::{IterativeSettings, convert_iterative};

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args.next().map_or_else(
        || PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../data/meshes/torus.obj"),
        PathBuf::from,
    );
    let resolution = args.next().and_then(|r| r.parse().ok()).unwrap_or(48);
    let mesh = match rbf_mesh::read_mesh(&path) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(2);
        }
    };
    let settings = IterativeSettings {
        resolution,
        ..Default::default()
    };
    let result = convert_iterative(&mesh, &settings, |it, _| {
        println!(
            "iteration {:2}: {} boundary / {} interior / {} exterior constraints, max error {:.2} voxels, RMS {:.2}",
            it.iteration, it.boundary, it.interior, it.exterior, it.max_error, it.rms_error
        );
    });
    match result {
        Ok((model, report)) => println!(
            "kept iteration {} of {}: {} constraints",
            report.best,
            report.iterations.len(),
            model.constraints.len()
        ),
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(3);
        }
    }
}
