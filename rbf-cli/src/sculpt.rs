//! `rbf sculpt`: replay a script of edits from the paper's starting blob.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use rbf_render::{Camera, Csg, Object, RenderSettings, render};
use rbf_sculpt::{Answer, COMMANDS, Session, parse_commands, parse_script};

use crate::common::{read_text, write_atomically};
use crate::failure::{BAD_INPUT, Failure, NUMERICAL};

pub(crate) const HELP: &str = "\
Edits start from the paper's blob (through the corners of a tetrahedron, eight exterior
constraints at the corners of a cube of side 6; items 0–3 are the tetrahedron's corners, 4–11
the cube's). Each edit adds an item (numbered from 12 on, never reused) or changes one, and
updates the factorization instead of solving afresh.

SCRIPT is a JSON list of edits:
  {\"add_boundary\": {\"position\": [x, y, z]}}       the surface moves to pass through it
  {\"pick_boundary\": {\"origin\": [..], \"direction\": [..]}}   where a ray meets the surface
  {\"add_interior\": {\"position\": [..], \"value\": 1}}   {\"add_exterior\": {... \"value\": -1}}
  {\"move\": {\"item\": 12, \"to\": [..]}}   {\"delete\": {\"item\": 0}}
  {\"add_normal\": {\"item\": 12}}   {\"move_normal\": {\"item\": 13, \"to\": [..]}}
  \"undo\"   \"redo\"
or a text file of commands, one per line (# comments), or `-`: commands typed at a prompt,
each applied at once, with --preview re-rendered after every edit (open it in an image viewer
that reloads). A refused command leaves the session as it was. At the prompt, also: `list`
(the items), `save` (write the model now), `help`, `quit`. The commands:
  add X Y Z | pick OX OY OZ DX DY DZ | interior X Y Z [V] | exterior X Y Z [V]
  move ITEM X Y Z | normal ITEM | tip ITEM X Y Z | delete ITEM | undo | redo

Examples:
  rbf sculpt torus.json -o torus-model.json
  rbf sculpt torus.json -o torus-model.json --frames frames/
  rbf sculpt - -o blob.json --preview blob.png";

#[derive(Args, Debug)]
pub(crate) struct SculptArgs {
    /// Script of edits (JSON, or text commands one per line), or `-` for a prompt.
    script: PathBuf,
    /// Model file to write.
    #[arg(short, long, value_name = "MODEL.json")]
    output: PathBuf,
    /// Render a PNG after each edit into this directory.
    #[arg(long, value_name = "DIR")]
    frames: Option<PathBuf>,
    /// Render the surface to this PNG after each edit (replacing it).
    #[arg(long, value_name = "FILE.png")]
    preview: Option<PathBuf>,
    /// Frame and preview size in pixels (square).
    #[arg(long, default_value_t = 320)]
    frame_size: u32,
}

/// The surface as a PNG, from the view of the paper's figures.
fn picture(session: &Session, size: u32) -> Result<Vec<u8>, Failure> {
    let camera = Camera::orbit([-2.0; 3], [2.0; 3], 30.0, 25.0, size, size);
    let settings = RenderSettings {
        shadows: true,
        samples: 1,
        ..Default::default()
    };
    let view = [session.interpolant().view()];
    let (image, _) = render(&view, &[Object::new(Csg::Model(0), 0)], &camera, &settings)
        .map_err(|e| Failure::new(BAD_INPUT, e.to_string()))?;
    image
        .to_png()
        .map_err(|e| Failure::new(BAD_INPUT, e.to_string()))
}

pub(crate) fn run(args: &SculptArgs, quiet: bool) -> Result<(), Failure> {
    let source = args.script.display().to_string();
    let mut session = Session::new().map_err(|e| Failure::new(NUMERICAL, e.to_string()))?;
    if let Some(dir) = &args.frames {
        std::fs::create_dir_all(dir).map_err(|e| {
            Failure::new(BAD_INPUT, format!("cannot create {}: {e}", dir.display()))
        })?;
    }
    if args.script == std::path::Path::new("-") {
        return prompt(&mut session, args, quiet);
    }
    let text = read_text(&args.script)?;
    let edits = if text.trim_start().starts_with('[') {
        parse_script(&text).map_err(|e| Failure::new(BAD_INPUT, format!("{source}: {e}")))?
    } else {
        parse_commands(&text).map_err(|e| Failure::new(BAD_INPUT, format!("{source}: {e}")))?
    };
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
            let png = picture(&session, args.frame_size)?;
            write_atomically(&dir.join(format!("frame-{:03}.png", k + 1)), &png)?;
        }
        if let Some(path) = &args.preview {
            write_atomically(path, &picture(&session, args.frame_size)?)?;
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

/// Commands typed at a prompt (or piped), each applied and answered at once; the model is
/// written at the end of input, on `quit`, and on `save`.
fn prompt(session: &mut Session, args: &SculptArgs, quiet: bool) -> Result<(), Failure> {
    use std::io::{BufRead, IsTerminal, Write};
    let terminal = std::io::stdin().is_terminal();
    let save =
        |session: &Session| write_atomically(&args.output, session.model().to_json().as_bytes());
    if terminal && !quiet {
        eprintln!(
            "sculpting the paper's blob; `help` lists the commands, `quit` writes {} and ends",
            args.output.display()
        );
    }
    let (mut applied, mut refused) = (0, 0);
    let mut lines = std::io::stdin().lock().lines();
    loop {
        if terminal {
            eprint!("rbf> ");
            let _ = std::io::stderr().flush();
        }
        let Some(line) = lines.next() else { break };
        let line = line.map_err(|e| Failure::new(BAD_INPUT, format!("stdin: {e}")))?;
        match line.trim() {
            "quit" | "exit" => break,
            "help" => {
                println!("{COMMANDS}\nlist | save | help | quit");
                continue;
            }
            "list" => {
                for (i, item) in session.items().iter().enumerate() {
                    if let Some(item) = item {
                        println!("{i:4}  {item:?}");
                    }
                }
                continue;
            }
            "save" => {
                save(session)?;
                println!("wrote {}", args.output.display());
                continue;
            }
            _ => {}
        }
        let t = Instant::now();
        let answer = session.run_command(&line);
        let solve_ms = t.elapsed().as_secs_f64() * 1e3;
        match answer {
            Answer::Nothing => continue,
            Answer::Applied { .. } => {
                applied += 1;
                if let Some(path) = &args.preview {
                    write_atomically(path, &picture(session, args.frame_size)?)?;
                }
            }
            Answer::Refused(_) => refused += 1,
        }
        println!("{}", answer.line(solve_ms));
    }
    save(session)?;
    if !quiet {
        eprintln!(
            "{applied} edits applied, {refused} refused; {} constraints; wrote {}",
            session.items().iter().flatten().count(),
            args.output.display()
        );
    }
    Ok(())
}
