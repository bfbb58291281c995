//! # rbf-web
//!
//! The engine of **rbf studio**, the browser page in `web/` where the interactive modelling of
//! Greg Turk and James F. O'Brien, "Modelling with Implicit Surfaces that Interpolate", ACM
//! Transactions on Graphics 21(4), 2002, §5, happens live: a click on the surface adds a
//! boundary constraint there (knot insertion), dragging a handle moves it while the surface
//! follows, normal handles turn the surface, undo and redo; the model saves as the CLI's JSON.
//!
//! [`Studio`] is the engine in plain Rust, tested natively: an `rbf_sculpt::Session`, its
//! surface polygonized by rbf-mesh into WebGL-ready buffers, its handles, model and mesh files.
//! [`WebStudio`] is the same for JavaScript, compiled to `wasm32-unknown-unknown` by
//! `web/build.sh` (wasm-bindgen, no threads: rayon runs on the page's one thread).
//!
//! ```
//! let mut studio = rbf_web::Studio::new().unwrap();
//! let before = studio.surface().indices.len();
//! assert!(matches!(studio.run("pick 0 0 5 0 0 -1"), rbf_sculpt::Answer::Applied { .. }));
//! studio.remesh(rbf_web::FINE_CELLS).unwrap();
//! assert_eq!(studio.handles().len(), 13);
//! assert!(studio.surface().indices.len().abs_diff(before) < before / 10); // it did not move
//! ```

mod bindings;
mod single;
mod studio;

pub use bindings::{WebStudio, coarse_cells, fine_cells};
pub use studio::{
    COARSE_CELLS, FINE_CELLS, Handle, MAX_MESH_VERTICES, MAX_MODEL_ROWS, SCOUT_CELLS, Studio,
    StudioError, Surface,
};
