//! Sculpt from the paper's starting blob: pull a point out, tilt it with a normal handle,
//! undo, and let floaters follow the surface.
//!
//! Run: `cargo run --release -p rbf-sculpt --example sculpt`

use rbf_sculpt::{FloaterSettings, SculptError, Session};

fn main() -> Result<(), SculptError> {
    let mut session = Session::new()?;
    session.start_floaters(FloaterSettings::for_size(3.5));
    let count = |s: &Session| s.floaters().map_or(0, |f| f.len());
    println!("start: {} floaters on the blob", count(&session));
    // A boundary constraint where a ray from the camera meets the surface: nothing moves.
    let picked = session.pick_boundary([0.0, 0.0, 5.0], [0.0, 0.0, -1.0])?;
    // Pull it out: the surface follows.
    session.move_item(picked, [0.0, 0.0, 2.0])?;
    println!(
        "pulled: f(0, 0, 1.8) = {:+.3}, {} floaters",
        session.interpolant().value(&[0.0, 0.0, 1.8]),
        count(&session)
    );
    let handle = session.add_normal(picked)?;
    session.move_normal(handle, [0.4, 0.0, 2.2])?;
    session.undo()?;
    session.undo()?;
    println!(
        "after two undos: {} items",
        session.items().iter().flatten().count()
    );
    Ok(())
}
