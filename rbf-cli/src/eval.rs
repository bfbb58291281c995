//! `rbf eval`: a model and points in, values (and gradients) out, as text or NumPy `.npy`.

use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use clap::Args;
use rayon::prelude::*;
use rbf_core::{AnyModel, Model};

use crate::accuracy::AccuracyArgs;
use crate::common::{read_model, read_text, write_atomically};
use crate::failure::{BAD_INPUT, Failure};

pub(crate) const HELP: &str = "\
POINTS holds one point per line (x y z, or x y for a 2D model; # starts a comment), or is a
NumPy .npy array of shape (N, 3) (or (N, 2)), float64 or float32, as numpy.save writes it.
Output: one line per point, `value` or `value gx gy gz` with --gradient; with -o OUT.npy, an
array of shape (N,) of values, or (N, 4) (or (N, 3)) of values and gradients.
f is positive inside, negative outside and zero on the surface.
Models of 15 000 centres and more are evaluated through a far field (clusters of centres far
from a group of points replaced by Chebyshev proxies) when that is within --accuracy, measured
against direct sums at 1000 sampled points before the rest are evaluated; --exact sums every
centre directly.

Examples:
  rbf eval model.json grid.txt > values.txt
  rbf eval model.json points.npy -o values.npy
  rbf eval model.json points.npy -o values.npy --gradient
  rbf eval big.json points.npy -o values.npy --accuracy 1e-8
  printf '0 0 0\\n1 0 0\\n' | rbf eval model.json - --gradient";

#[derive(Args, Debug)]
pub(crate) struct EvalArgs {
    /// Model file written by `rbf fit`.
    model: PathBuf,
    /// Points: a text file (`-` reads stdin) or a NumPy `.npy` array, one point a row.
    points: PathBuf,
    /// Add the gradient after each value.
    #[arg(long)]
    gradient: bool,
    /// Write the output here instead of stdout: a NumPy array if it ends in `.npy`, text
    /// otherwise.
    #[arg(short, long, value_name = "OUT")]
    output: Option<PathBuf>,
    #[command(flatten)]
    sums: AccuracyArgs,
}

pub(crate) fn run(args: &EvalArgs) -> Result<(), Failure> {
    let model = read_model(&args.model)?;
    match &model {
        AnyModel::Two(m) => eval(m, args),
        AnyModel::Three(m) => eval(m, args),
    }
}

fn is_npy(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("npy"))
}

/// The points of the file, in the model's dimension.
fn read_points<const D: usize>(path: &Path) -> Result<Vec<[f64; D]>, Failure> {
    let name = path.display();
    if is_npy(path) {
        let bytes =
            std::fs::read(path).map_err(|e| Failure::new(BAD_INPUT, format!("{name}: {e}")))?;
        let m = rbf_mesh::read_npy_matrix(path, &bytes)
            .map_err(|e| Failure::new(BAD_INPUT, e.to_string()))?;
        if m.cols != D {
            return Err(Failure::new(
                BAD_INPUT,
                format!(
                    "{name}: an array of shape ({}, {}); the model is {D}D, so give shape (N, {D})",
                    m.rows, m.cols
                ),
            ));
        }
        if let Some(i) = m.data.iter().position(|v| !v.is_finite()) {
            return Err(Failure::new(
                BAD_INPUT,
                format!(
                    "{name}: point {} has a coordinate that is not a finite number",
                    i / D
                ),
            ));
        }
        return Ok(m
            .data
            .chunks_exact(D)
            .map(|c| core::array::from_fn(|d| c[d]))
            .collect());
    }
    rbf_core::parse_points::<D>(&read_text(path)?)
        .map_err(|e| Failure::new(BAD_INPUT, format!("{name}: {e} (the model is {D}D)")))
}

fn eval<const D: usize>(model: &Model<D>, args: &EvalArgs) -> Result<(), Failure> {
    let points = read_points::<D>(&args.points)?;
    let f = args.sums.evaluator(model.interpolant.view(), &points)?;
    // Row by row: the value, then the gradient if asked.
    let width = if args.gradient { 1 + D } else { 1 };
    let mut out = vec![0.0; points.len() * width];
    if args.gradient {
        let mut values = vec![0.0; points.len()];
        let mut gradients = vec![[0.0; D]; points.len()];
        let _ = f.values_and_gradients(&points, &mut values, &mut gradients);
        out.par_chunks_mut(width)
            .zip(values.par_iter().zip(&gradients))
            .for_each(|(row, (v, g))| {
                row[0] = *v;
                row[1..].copy_from_slice(g);
            });
    } else {
        let _ = f.values(&points, &mut out);
    }
    match &args.output {
        Some(path) if is_npy(path) => {
            let shape: &[usize] = if args.gradient {
                &[points.len(), width]
            } else {
                &[points.len()]
            };
            write_atomically(path, &rbf_mesh::npy_f64_bytes(shape, &out))
        }
        Some(path) => {
            let mut text = String::with_capacity(out.len() * 24);
            for row in out.chunks_exact(width) {
                push_row(&mut text, row);
            }
            write_atomically(path, text.as_bytes())
        }
        None => {
            let stdout = std::io::stdout();
            let mut w = BufWriter::new(stdout.lock());
            let mut line = String::new();
            for row in out.chunks_exact(width) {
                line.clear();
                push_row(&mut line, row);
                if w.write_all(line.as_bytes()).is_err() {
                    // A closed pipe (`| head`) is not an error of ours.
                    return Ok(());
                }
            }
            let _ = w.flush();
            Ok(())
        }
    }
}

/// One output line: the numbers in full precision, separated by spaces.
fn push_row(text: &mut String, row: &[f64]) {
    use std::fmt::Write as _;
    for (i, v) in row.iter().enumerate() {
        if i > 0 {
            text.push(' ');
        }
        let _ = write!(text, "{v:?}");
    }
    text.push('\n');
}
