//! `rbf eval`: a model and points in, values (and gradients) out.

use std::io::{BufWriter, Write};
use std::path::PathBuf;

use clap::Args;
use rayon::prelude::*;
use rbf_core::{AnyModel, Model};

use crate::common::{read_model, read_text};
use crate::failure::{BAD_INPUT, Failure};

pub(crate) const HELP: &str = "\
POINTS holds one point per line (x y z, or x y for a 2D model); # starts a comment.
Output: one line per point, `value` or `value gx gy gz` with --gradient.
f is positive inside, negative outside and zero on the surface.

Examples:
  rbf eval model.json grid.txt > values.txt
  printf '0 0 0\\n1 0 0\\n' | rbf eval model.json - --gradient";

#[derive(Args, Debug)]
pub(crate) struct EvalArgs {
    /// Model file written by `rbf fit`.
    model: PathBuf,
    /// Points file; `-` reads stdin.
    points: PathBuf,
    /// Print the gradient after each value.
    #[arg(long)]
    gradient: bool,
}

pub(crate) fn run(args: &EvalArgs) -> Result<(), Failure> {
    let model = read_model(&args.model)?;
    let text = read_text(&args.points)?;
    match &model {
        AnyModel::Two(m) => eval(m, &text, args),
        AnyModel::Three(m) => eval(m, &text, args),
    }
}

fn eval<const D: usize>(model: &Model<D>, text: &str, args: &EvalArgs) -> Result<(), Failure> {
    let points = rbf_core::parse_points::<D>(text).map_err(|e| {
        Failure::new(
            BAD_INPUT,
            format!("{}: {e} (the model is {D}D)", args.points.display()),
        )
    })?;
    let f = model.interpolant.view();
    let lines: Vec<String> = if args.gradient {
        points
            .par_iter()
            .map(|p| {
                let (v, g) = f.value_and_gradient(p);
                let mut s = format!("{v:?}");
                for c in g {
                    s.push(' ');
                    s.push_str(&format!("{c:?}"));
                }
                s
            })
            .collect()
    } else {
        let mut values = vec![0.0; points.len()];
        let _ = f.par_values(&points, &mut values);
        values.iter().map(|v| format!("{v:?}")).collect()
    };
    let stdout = std::io::stdout();
    let mut out = BufWriter::new(stdout.lock());
    for l in lines {
        if writeln!(out, "{l}").is_err() {
            // A closed pipe (`| head`) is not an error of ours.
            return Ok(());
        }
    }
    let _ = out.flush();
    Ok(())
}
