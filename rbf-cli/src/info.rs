//! `rbf info`: what a model file holds.

use std::path::PathBuf;

use clap::Args;
use rbf_core::{AnyModel, ConstraintKind, Model};

use crate::common::read_model;
use crate::failure::Failure;

#[derive(Args, Debug)]
pub(crate) struct InfoArgs {
    /// Model file.
    model: PathBuf,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

/// The figures of a model, in any dimension.
fn describe<const D: usize>(m: &Model<D>, file: &str) -> serde_json::Value {
    let count = |k: ConstraintKind| m.constraints.iter().filter(|c| c.kind == k).count();
    let (mut lo, mut hi) = (vec![f64::INFINITY; D], vec![f64::NEG_INFINITY; D]);
    for c in &m.constraints {
        for d in 0..D {
            lo[d] = lo[d].min(c.position[d]);
            hi[d] = hi[d].max(c.position[d]);
        }
    }
    serde_json::json!({
        "file": file,
        "format_version": rbf_core::MODEL_VERSION,
        "dimension": D,
        "kernel": m.interpolant.kernel().name(),
        "lambda": m.settings.lambda,
        "constraints": {
            "boundary": count(ConstraintKind::Boundary),
            "interior": count(ConstraintKind::Interior),
            "exterior": count(ConstraintKind::Exterior),
            "normal": count(ConstraintKind::Normal),
        },
        "centres": m.interpolant.centres().len(),
        "bounding_box": { "min": lo, "max": hi },
        "fit": m.report.map(|r| serde_json::json!({
            "rows": r.rows,
            "method": format!("{:?}", r.method),
            "residual": r.residual,
            "condition": r.condition,
            "iterations": r.iterations,
        })),
    })
}

pub(crate) fn run(args: &InfoArgs) -> Result<(), Failure> {
    let source = args.model.display().to_string();
    let model = read_model(&args.model)?;
    let v = match &model {
        AnyModel::Two(m) => describe(m, &source),
        AnyModel::Three(m) => describe(m, &source),
    };
    if args.json {
        println!("{}", serde_json::to_string_pretty(&v).unwrap_or_default());
        return Ok(());
    }
    let c = &v["constraints"];
    println!("{source}");
    println!(
        "  {}D model, kernel {}, λ = {}, file format version {}",
        v["dimension"],
        v["kernel"].as_str().unwrap_or("?"),
        v["lambda"],
        v["format_version"]
    );
    println!(
        "  constraints: {} boundary, {} interior, {} exterior, {} normal ({} centres)",
        c["boundary"], c["interior"], c["exterior"], c["normal"], v["centres"]
    );
    println!(
        "  bounding box of the constraints: {} – {}",
        v["bounding_box"]["min"], v["bounding_box"]["max"]
    );
    if let Some(f) = v["fit"].as_object() {
        let how = match f["condition"].as_f64() {
            Some(c) => format!("condition ≈ {c:.1e}"),
            None => format!("{} iterations", f["iterations"]),
        };
        println!(
            "  fit: {} rows by {}, residual {:.1e}, {how}",
            f["rows"],
            f["method"].as_str().unwrap_or("?"),
            f["residual"].as_f64().unwrap_or(f64::NAN),
        );
    }
    Ok(())
}
