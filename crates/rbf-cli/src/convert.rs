//! `rbf convert`: a polygon mesh to an implicit surface.

use std::path::PathBuf;
use std::time::Instant;

use clap::{Args, ValueEnum};
use rbf_convert::{NormalSettings, convert_normals};
use rbf_core::NormalOffset;
use rbf_mesh::read_mesh;

use crate::check::mesh_failure;
use crate::failure::{BAD_INPUT, Failure};
use crate::io::write_atomically;

pub(crate) const HELP: &str = "\
With --method normals (paper 000, §4.3) every vertex becomes a boundary constraint with a normal
constraint a small distance inside, against the vertex normal; meshes with more vertices than
--max-constraints are thinned to an evenly spread subset first.

Examples:
  rbf convert bunny.obj -o bunny.json
  rbf convert scan.ply -o scan.json --max-constraints 2000 --lambda 1e-6
  rbf mesh bunny.json -o smooth_bunny.obj";

#[derive(Args, Debug)]
pub(crate) struct ConvertArgs {
    /// Mesh file (.obj, .ply, .stl).
    mesh: PathBuf,
    /// Model file to write.
    #[arg(short, long, value_name = "MODEL.json")]
    output: PathBuf,
    /// Conversion method.
    #[arg(long, value_enum, default_value_t = Method::Normals)]
    method: Method,
    /// Most vertices used (each gives two constraint rows).
    #[arg(long, value_name = "N", default_value_t = 4000)]
    max_constraints: usize,
    /// Regularization λ of the fit.
    #[arg(long, value_name = "L", default_value_t = 0.0)]
    lambda: f64,
    /// Normal constraint offset as a fraction of the bounding box's longest side.
    #[arg(long, value_name = "F", default_value_t = 0.01)]
    offset: f64,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum Method {
    /// A boundary and a normal constraint at each vertex.
    Normals,
}

pub(crate) fn run(args: &ConvertArgs, quiet: bool) -> Result<(), Failure> {
    let mesh = read_mesh(&args.mesh).map_err(|e| mesh_failure(&e))?;
    let Method::Normals = args.method;
    let settings = NormalSettings {
        offset: NormalOffset::Relative(args.offset),
        max_vertices: args.max_constraints,
        lambda: args.lambda,
    };
    let start = Instant::now();
    let spinner = crate::fit::spinner(quiet, "fitting normal constraints".into());
    let result = convert_normals(&mesh, &settings);
    spinner.finish_and_clear();
    let source = args.mesh.display().to_string();
    let (model, report) = result.map_err(|e| match e {
        rbf_convert::ConvertError::Fit(f) => Failure::fit(&source, &f),
        other => Failure::new(BAD_INPUT, format!("{source}: {other}")),
    })?;
    write_atomically(&args.output, model.to_json().as_bytes())?;
    if !quiet {
        let thinned = if report.thinned {
            " (thinned evenly)"
        } else {
            ""
        };
        eprintln!(
            "{} of {} vertices used{thinned}, {} without a normal; {} rows, residual {:.1e}, condition ≈ {:.1e}; {:.2} s; wrote {}",
            report.vertices_used,
            report.vertices,
            report.without_normal,
            report.fit.rows,
            report.fit.residual,
            report.fit.condition,
            start.elapsed().as_secs_f64(),
            args.output.display()
        );
    }
    Ok(())
}
