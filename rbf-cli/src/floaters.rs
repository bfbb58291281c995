//! `rbf floaters`: an even sampling of a model's surface by floaters.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use rbf_sculpt::{FloaterSettings, Floaters};

use crate::common::{read_model_3d, write_atomically};
use crate::failure::{Failure, NUMERICAL, USAGE};

pub(crate) const HELP: &str = "\
Floaters (Witkin & Heckbert 1994) stick to the surface f = 0, repel each other, split where they
are sparse and die where they are crowded; the spacing is tuned until about COUNT of them
cover the surface. Output: one floater per line, `x y z nx ny nz` (outward unit normal).

Example:
  rbf floaters model.json -n 2000 -o points.xyz";

#[derive(Args, Debug)]
pub(crate) struct FloatersArgs {
    /// Model file (3D).
    model: PathBuf,
    /// About how many floaters.
    #[arg(short = 'n', long, default_value_t = 1000)]
    count: usize,
    /// Points file to write.
    #[arg(short, long, value_name = "POINTS.xyz")]
    output: PathBuf,
}

pub(crate) fn run(args: &FloatersArgs, quiet: bool) -> Result<(), Failure> {
    if args.count == 0 || args.count > 1_000_000 {
        return Err(Failure::new(USAGE, "-n must be 1 to 1000000"));
    }
    let start = Instant::now();
    let model = read_model_3d(&args.model, "floaters")?;
    let f = model.interpolant.view();
    let seeds = rbf_mesh::surface_seeds(&model);
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in &seeds {
        for d in 0..3 {
            lo[d] = lo[d].min(p[d]);
            hi[d] = hi[d].max(p[d]);
        }
    }
    let diagonal = (0..3).map(|d| (hi[d] - lo[d]).powi(2)).sum::<f64>().sqrt();
    if seeds.is_empty() || !(diagonal > 0.0) {
        return Err(Failure::new(
            NUMERICAL,
            "the model has no surface to put floaters on",
        ));
    }
    // A first spacing from the area of the box's sphere, then tuned to the count.
    let area = std::f64::consts::PI * diagonal * diagonal;
    let hexagon = 3.0_f64.sqrt() / 2.0;
    let mut spacing = (area / (args.count as f64 * hexagon)).sqrt();
    let spinner = crate::common::spinner(quiet, format!("settling about {} floaters", args.count));
    let mut floaters = Floaters::new(
        &f,
        &seeds,
        FloaterSettings {
            spacing,
            ..FloaterSettings::for_size(diagonal)
        },
    );
    for _ in 0..4 {
        floaters.set_spacing(spacing);
        floaters.settle(&f, 120);
        if floaters.is_empty() {
            return Err(Failure::new(NUMERICAL, "every floater left the surface"));
        }
        spacing *= (floaters.len() as f64 / args.count as f64).sqrt();
    }
    spinner.finish_and_clear();
    let mut text = String::new();
    for (p, n) in floaters.points().iter().zip(floaters.normals(&f)) {
        let _ = writeln!(
            text,
            "{} {} {} {} {} {}",
            p[0], p[1], p[2], n[0], n[1], n[2]
        );
    }
    write_atomically(&args.output, text.as_bytes())?;
    if !quiet {
        eprintln!(
            "{} floaters, spacing {spacing:.4}, in {:.2} s; wrote {}",
            floaters.len(),
            start.elapsed().as_secs_f64(),
            args.output.display()
        );
    }
    Ok(())
}
