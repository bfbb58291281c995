//! `rbf sculpt`: replay a script of edits from the paper's starting blob.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use rbf_render::{Camera, Csg, Object, RenderSettings, render};
use rbf_sculpt::{Session, parse_script};

use crate::failure::{BAD_INPUT, Failure, NUMERICAL};
use crate::io::{read_text, write_atomically};

pub(crate) const HELP: &str = "\
A script is a JSON list of edits, applied in order to the paper's start (a blob through the
corners of a tetrahedron, eight exterior constraints at the corners of a cube of side 6;
items 0–3 are the tetrahedron's corners, 4–11 the cube's). Each edit adds an item (numbered
from 12 on, never reused) or changes one:
  {\"add_boundary\": {\"position\": [x, y, z]}}       the surface moves to pass through it
  {\"pick_boundary\": {\"origin\": [..], \"direction\": [..]}}   where a ray meets the surface
  {\"add_interior\": {\"position\": [..], \"value\": 1}}   {\"add_exterior\": {... \"value\": -1}}
  {\"move\": {\"item\": 12, \"to\": [..]}}   {\"delete\": {\"item\": 0}}
  {\"add_normal\": {\"item\": 12}}   {\"move_normal\": {\"item\": 13, \"to\": [..]}}
  \"undo\"   \"redo\"
Each edit updates the factorization instead of solving afresh.

Examples:
  rbf sculpt torus.json -o torus-model.json
  rbf sculpt torus.json -o torus-model.json --frames frames/";

#[derive(Args, Debug)]
pub(crate) struct SculptArgs {
    /// Script of edits (JSON).
    script: PathBuf,
    /// Model file to write.
    #[arg(short, long, value_name = "MODEL.json")]
    output: PathBuf,
    /// Render a PNG after each edit into this directory.
    #[arg(long, value_name = "DIR")]
    frames: Option<PathBuf>,
    /// Frame size in pixels (square).
    #[arg(long, default_value_t = 320)]
    frame_size: u32,
}

pub(crate) fn run(args: &SculptArgs, quiet: bool) -> Result<(), Failure> {
    let source = args.script.display().to_string();
    let edits = parse_script(&read_text(&args.script)?)
        .map_err(|e| Failure::new(BAD_INPUT, format!("{source}: {e}")))?;
    let mut session = Session::new().map_err(|e| Failure::new(NUMERICAL, e.to_string()))?;
    if let Some(dir) = &args.frames {
        std::fs::create_dir_all(dir).map_err(|e| {
            Failure::new(BAD_INPUT, format!("cannot create {}: {e}", dir.display()))
        })?;
    }
    let start = Instant::now();
    let mut solve_seconds = 0.0;
    let bar = indicatif::ProgressBar::new(edits.len() as u64);
    if quiet {
        bar.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    }
    for (k, edit) in edits.iter().enumerate() {
        bar.set_position(k as u64);
        let t = Instant::now();
        session.apply(edit).map_err(|e| {
            Failure::new(
                BAD_INPUT,
                format!("{source}: edit {} ({edit:?}): {e}", k + 1),
            )
        })?;
        solve_seconds += t.elapsed().as_secs_f64();
        if let Some(dir) = &args.frames {
            let camera = Camera::orbit(
                [-2.0; 3],
                [2.0; 3],
                30.0,
                25.0,
                args.frame_size,
                args.frame_size,
            );
            let settings = RenderSettings {
                shadows: true,
                samples: 1,
                ..Default::default()
            };
            let view = [session.interpolant().view()];
            let (image, _) = render(&view, &[Object::new(Csg::Model(0), 0)], &camera, &settings)
                .map_err(|e| Failure::new(BAD_INPUT, e.to_string()))?;
            let png = image
                .to_png()
                .map_err(|e| Failure::new(BAD_INPUT, e.to_string()))?;
            write_atomically(&dir.join(format!("frame-{:03}.png", k + 1)), &png)?;
        }
    }
    bar.finish_and_clear();
    write_atomically(&args.output, session.model().to_json().as_bytes())?;
    if !quiet {
        eprintln!(
            "applied {} edits ({:.3} s solving, {:.2} s in all); {} constraints; wrote {}",
            edits.len(),
            solve_seconds,
            start.elapsed().as_secs_f64(),
            session.items().iter().flatten().count(),
            args.output.display()
        );
    }
    Ok(())
}
