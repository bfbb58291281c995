//! # rbf-sculpt
//!
//! Interactive modelling with interpolating implicit surfaces, after §5 of Greg Turk and
//! James F. O'Brien, "Modelling with Implicit Surfaces that Interpolate", ACM Transactions on
//! Graphics 21(4), 2002 (Turk & O'Brien 2002):
//! a [`Session`] of constraints edited one at a time (add a boundary constraint where a ray
//! meets the surface, move it, add and pull normal handles, delete, undo, redo), each edit
//! re-solved by updating a factorization ([`IncrementalFit`]: O(n²) instead of a fresh O(n³)
//! fit), and [`Floaters`] that keep an even sampling of the surface as it changes. Scripts of
//! edits ([`Edit`], JSON) replay a session.
//!
//! ```
//! use rbf_sculpt::Session;
//! let mut s = Session::new().unwrap(); // the paper's start: a blob through a tetrahedron
//! let top = s.add_boundary([0.0, 1.5, 0.0]).unwrap(); // pull the surface up to here
//! assert!(s.interpolant().value(&[0.0, 1.5, 0.0]).abs() < 1e-9);
//! let handle = s.add_normal(top).unwrap();
//! s.move_normal(handle, [0.3, 1.6, 0.0]).unwrap(); // tilt the surface there
//! s.delete(top).unwrap(); // the handle goes with it
//! assert!(s.items()[handle].is_none());
//! ```

mod answer;
mod command;
mod error;
mod floaters;
mod incremental;
mod script;
mod session;

pub use answer::Answer;
pub use command::{COMMANDS, parse_command, parse_commands};
pub use error::{ParseError, ParseProblem, SculptError};
pub use floaters::{FloaterSettings, Floaters};
pub use incremental::{IncrementalFit, Row};
pub use script::{Edit, parse_script};
pub use session::{Item, Session};

/// A script of edits (JSON, see [`parse_script`]) that sculpts a torus from the paper's start:
/// Turk & O'Brien (2002), Figure 7. The gallery replays it; `scripts/torus.json` is the file.
#[doc(hidden)]
pub const TORUS_SCRIPT: &str = include_str!("../scripts/torus.json");
