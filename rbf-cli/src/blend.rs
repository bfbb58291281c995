//! `rbf blend`: one smooth surface from overlapping models (Turk & O'Brien 2002, §6).

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use rbf_core::{AnyModel, Model};

use crate::common::{read_model, write_atomically};
use crate::failure::{BAD_INPUT, Failure, USAGE};

pub(crate) const HELP: &str = "\
Each model keeps the constraints that lie outside all the others; one interpolant is fitted
through what is kept. Where models overlap, the new surface bridges the crease smoothly;
elsewhere it passes through the same constraints as before. Models must have the same
dimension and kernel; the first model's settings (λ, normal offset) are used.

Examples:
  rbf blend a.json b.json -o ab.json
  rbf blend t1.json t2.json t3.json -o tori.json && rbf render tori.json -o tori.png";

#[derive(Args, Debug)]
pub(crate) struct BlendArgs {
    /// Model files to blend (two or more).
    #[arg(required = true, num_args = 2..)]
    models: Vec<PathBuf>,
    /// Model file to write.
    #[arg(short, long, value_name = "OUT.json")]
    output: PathBuf,
}

pub(crate) fn run(args: &BlendArgs, quiet: bool) -> Result<(), Failure> {
    let start = Instant::now();
    let mut two: Vec<Model<2>> = Vec::new();
    let mut three: Vec<Model<3>> = Vec::new();
    for path in &args.models {
        match read_model(path)? {
            AnyModel::Two(m) => two.push(m),
            AnyModel::Three(m) => three.push(m),
        }
    }
    if !two.is_empty() && !three.is_empty() {
        return Err(Failure::new(
            USAGE,
            "cannot blend 2D and 3D models together",
        ));
    }
    let failure = |e: rbf_convert::ConvertError| match e {
        rbf_convert::ConvertError::Fit(f) => Failure::fit("the blend", &f),
        other => Failure::new(BAD_INPUT, other.to_string()),
    };
    let (json, report) = if three.is_empty() {
        let refs: Vec<&Model<2>> = two.iter().collect();
        let (m, r) = rbf_convert::blend(&refs).map_err(failure)?;
        (m.to_json(), r)
    } else {
        let refs: Vec<&Model<3>> = three.iter().collect();
        let (m, r) = rbf_convert::blend(&refs).map_err(failure)?;
        (m.to_json(), r)
    };
    write_atomically(&args.output, json.as_bytes())?;
    if !quiet {
        for (path, (kept, total)) in args
            .models
            .iter()
            .zip(report.kept.iter().zip(&report.total))
        {
            eprintln!("{}: kept {kept} of {total} constraints", path.display());
        }
        eprintln!(
            "wrote {} in {:.2} s",
            args.output.display(),
            start.elapsed().as_secs_f64()
        );
    }
    Ok(())
}
