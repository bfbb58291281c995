//! `rbf mesh`: a model's surface as a triangle mesh.

use std::path::PathBuf;
use std::time::Instant;

use clap::{Args, ValueEnum};
use rbf_mesh::{
    PolygonizeSettings, Resolution, polygonize_continuation, polygonize_grid, surface_seeds,
    write_mesh,
};

use crate::accuracy::AccuracyArgs;
use crate::common::read_model_3d;
use crate::failure::{BAD_INPUT, Failure};

pub(crate) const HELP: &str = "\
Both methods split the cube lattice into tetrahedra (no ambiguous cases), so a closed surface
gives a watertight mesh with outward triangles; vertices are placed on the surface by root
finding and carry normals from the gradient.

Examples:
  rbf mesh model.json -o surface.obj
  rbf mesh model.json -o surface.ply --resolution 256
  rbf mesh model.json -o surface.stl --cell-size 0.01 --method grid
  rbf mesh big.json -o big.ply --resolution 256 --accuracy 1e-5";

#[derive(Args, Debug)]
pub(crate) struct MeshArgs {
    /// Model file written by `rbf fit` (3D).
    model: PathBuf,
    /// Mesh to write: .obj, .ply or .stl.
    #[arg(short, long, value_name = "OUT")]
    output: PathBuf,
    /// Cubes across the longest side of the box [default: 128].
    #[arg(long, value_name = "N", conflicts_with = "cell_size")]
    resolution: Option<usize>,
    /// Edge length of a cube, in the model's units.
    #[arg(long, value_name = "H")]
    cell_size: Option<f64>,
    /// Polygonizer: crawl the surface from its constraints, or sample the whole grid.
    #[arg(long, value_enum, default_value_t = Method::Continuation)]
    method: Method,
    #[command(flatten)]
    sums: AccuracyArgs,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum Method {
    /// Crawl from the model's boundary constraints across the surface; samples f only near it.
    Continuation,
    /// Every cube of the box, skipping blocks the surface cannot cross; finds components
    /// without seeds.
    #[value(alias = "marching-cubes")]
    Grid,
}

pub(crate) fn run(args: &MeshArgs, quiet: bool) -> Result<(), Failure> {
    let source = args.model.display().to_string();
    let model = read_model_3d(&args.model, "mesh")?;
    let resolution = match (args.cell_size, args.resolution) {
        (Some(h), _) => Resolution::CellSize(h),
        (None, Some(n)) => Resolution::Cells(n),
        (None, None) => Resolution::Cells(128),
    };
    let settings = PolygonizeSettings {
        resolution,
        ..Default::default()
    };
    let start = Instant::now();
    let view = model.interpolant.view();
    let f = args.sums.evaluator(view, view.centres())?;
    let spinner = crate::common::spinner(quiet, "polygonizing".into());
    let result = match args.method {
        Method::Continuation => polygonize_continuation(&f, &surface_seeds(&model), &settings),
        Method::Grid => polygonize_grid(&f, &settings),
    };
    spinner.finish_and_clear();
    let (mesh, stats) = result.map_err(|e| Failure::new(BAD_INPUT, format!("{source}: {e}")))?;
    // The file is written while the mesh is checked for the summary.
    let (written, report) = rayon::join(
        || write_mesh(&args.output, &mesh),
        || (!quiet).then(|| mesh.check()),
    );
    written.map_err(|e| Failure::mesh(&e))?;
    if let Some(r) = report {
        eprintln!(
            "{} vertices, {} triangles ({} × {} × {} cubes, {} samples) in {:.2} s; {}; wrote {}",
            r.vertices,
            r.triangles,
            stats.cells[0],
            stats.cells[1],
            stats.cells[2],
            stats.samples,
            start.elapsed().as_secs_f64(),
            crate::common::surface_topology(&r, "open (the surface leaves the box)"),
            args.output.display()
        );
    }
    Ok(())
}
