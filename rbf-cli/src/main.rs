//! `rbf`: variational implicit surfaces from the shell.
//!
//! The methods are those of Greg Turk and James F. O'Brien, "Modelling with Implicit Surfaces
//! that Interpolate", ACM Transactions on Graphics 21(4), 2002 (Turk & O'Brien 2002), and of
//! Gary Yngve and Greg Turk, "Robust Creation of Implicit Surfaces from Polygonal Meshes", IEEE
//! Transactions on Visualization and Computer Graphics 8(4), 2002 (Yngve & Turk 2002).

mod accuracy;
mod blend;
mod check;
mod common;
mod compare;
mod completions;
mod convert;
mod demo;
mod eval;
mod export;
mod failure;
mod fit;
mod fit_progress;
mod floaters;
mod gallery;
mod info;
mod mesh;
mod plot;
mod reconstruct;
mod render;
mod sculpt;
mod studio;
mod voxelize;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};

use crate::failure::Failure;

/// Variational implicit surfaces: smooth surfaces that pass exactly through given points.
///
/// Fit constraints (points on the surface, inside, outside, with normals) to an interpolating
/// function f, positive inside and negative outside, then evaluate f anywhere.
///
/// Exit codes: 0 success, 1 usage error, 2 bad input, 3 numerical failure.
#[derive(Parser, Debug)]
#[command(name = "rbf", version, propagate_version = true)]
#[command(
    after_help = "Examples:\n  rbf demo\n  rbf fit points.txt -o model.json\n  echo '0 0 0' | rbf eval model.json - --gradient"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Print nothing but results and errors.
    #[arg(short, long, global = true, conflicts_with = "verbose")]
    quiet: bool,
    /// Print more: every iteration of a conversion and every round of a greedy fit with their
    /// timings, the work of a render.
    #[arg(short, long, global = true)]
    verbose: bool,
    /// Worker threads (default: one per core).
    #[arg(long, global = true, value_name = "N")]
    threads: Option<usize>,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Fit constraints to an interpolant and write it as a model file.
    #[command(after_help = fit::HELP)]
    Fit(fit::FitArgs),
    /// Evaluate a model at points: one line per point, the value (then the gradient).
    #[command(after_help = eval::HELP)]
    Eval(eval::EvalArgs),
    /// Convert a polygon mesh to an implicit surface model.
    #[command(after_help = convert::HELP)]
    Convert(convert::ConvertArgs),
    /// Reconstruct a closed surface from a scan (a point cloud, normals optional).
    #[command(after_help = reconstruct::HELP)]
    Reconstruct(reconstruct::ReconstructArgs),
    /// Measure how far a model's surface lies from a mesh, both ways (mean, RMS, Hausdorff).
    #[command(after_help = compare::HELP)]
    Compare(compare::CompareArgs),
    /// Polygonize a model's surface into a triangle mesh (OBJ, PLY or STL).
    #[command(after_help = mesh::HELP)]
    Mesh(mesh::MeshArgs),
    /// Voxelize a mesh: densities or signed distances on a grid, as a NumPy array.
    #[command(after_help = voxelize::HELP)]
    Voxelize(voxelize::VoxelizeArgs),
    /// Blend overlapping models into one smooth surface (constraint selection, Turk & O'Brien 2002, §6).
    #[command(after_help = blend::HELP)]
    Blend(blend::BlendArgs),
    /// Replay a script of sculpting edits (Turk & O'Brien 2002, §5) and write the model.
    #[command(after_help = sculpt::HELP)]
    Sculpt(sculpt::SculptArgs),
    /// Sculpt in the browser: serve rbf studio on 127.0.0.1 (build it first: web/build.sh).
    #[command(after_help = studio::HELP)]
    Studio(studio::StudioArgs),
    /// Sample a model's surface evenly with floaters (positions and normals).
    #[command(after_help = floaters::HELP)]
    Floaters(floaters::FloatersArgs),
    /// Render models (ray traced, with CSG, shadows, reflections) or a mesh to PNG.
    #[command(after_help = render::HELP)]
    Render(render::RenderArgs),
    /// Plot a 2D model's curve and its constraints to PNG.
    #[command(after_help = plot::HELP)]
    Plot(plot::PlotArgs),
    /// Recompute the paper's figures: PNGs, their models, what they measured, an index.html.
    #[command(after_help = gallery::HELP)]
    Gallery(gallery::GalleryArgs),
    /// Describe a model file: dimension, kernel, constraints by kind, bounding box, λ, version.
    #[command(after_help = "Examples:\n  rbf info model.json\n  rbf info model.json --json")]
    Info(info::InfoArgs),
    /// Write a model as source code (constant arrays) for targets without an allocator.
    #[command(after_help = export::HELP)]
    Export(export::ExportArgs),
    /// Print a shell completion script (bash, zsh, fish, elvish, powershell).
    #[command(
        after_help = "Examples:\n  rbf completions bash > ~/.local/share/bash-completion/completions/rbf\n  rbf completions zsh > ~/.zfunc/_rbf"
    )]
    Completions {
        /// Shell to write the completion script for.
        shell: clap_complete::Shell,
    },
    /// Check a mesh: holes, non-manifold edges and vertices, orientation, components, genus.
    #[command(after_help = "Examples:\n  rbf check bunny.obj\n  rbf check scan.ply --json")]
    Check(check::CheckArgs),
    /// The main job on built-in data: convert a mesh shipped in the binary to an implicit
    /// surface, polygonize it, render it next to the original; then fit the paper's examples.
    #[command(after_help = "Example:\n  rbf demo -o demo-out")]
    Demo {
        /// Directory for the models written.
        #[arg(short, long, default_value = "rbf-demo")]
        output: PathBuf,
    },
}

/// The kernels, by their command-line names.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub(crate) enum KernelArg {
    /// φ(r) = r³, the 3D default.
    Cubic,
    /// φ(r) = r.
    Linear,
    /// φ(r) = r² log r, the 2D default.
    ThinPlate,
}

impl From<KernelArg> for rbf_core::Kernel {
    fn from(k: KernelArg) -> Self {
        match k {
            KernelArg::Cubic => rbf_core::Kernel::Cubic,
            KernelArg::Linear => rbf_core::Kernel::Linear,
            KernelArg::ThinPlate => rbf_core::Kernel::ThinPlate,
        }
    }
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let code = if e.use_stderr() { 1 } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    if let Some(n) = cli.threads
        && let Err(e) = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()
    {
        eprintln!("rbf: cannot start {n} threads: {e}");
        return ExitCode::from(1);
    }
    let result = match cli.command {
        Command::Fit(args) => fit::run(&args, cli.quiet, cli.verbose),
        Command::Eval(args) => eval::run(&args),
        Command::Check(args) => check::run(&args),
        Command::Convert(args) => convert::run(&args, cli.quiet, cli.verbose),
        Command::Reconstruct(args) => reconstruct::run(&args, cli.quiet),
        Command::Compare(args) => compare::run(&args, cli.quiet),
        Command::Mesh(args) => mesh::run(&args, cli.quiet),
        Command::Voxelize(args) => voxelize::run(&args, cli.quiet),
        Command::Render(args) => render::run(&args, cli.quiet, cli.verbose),
        Command::Studio(args) => studio::run(&args, cli.quiet),
        Command::Blend(args) => blend::run(&args, cli.quiet),
        Command::Sculpt(args) => sculpt::run(&args, cli.quiet),
        Command::Floaters(args) => floaters::run(&args, cli.quiet),
        Command::Plot(args) => plot::run(&args, cli.quiet),
        Command::Demo { output } => demo::run(&output, cli.quiet),
        Command::Info(args) => info::run(&args),
        Command::Gallery(args) => gallery::run(&args, cli.quiet),
        Command::Export(args) => export::run(&args, cli.quiet),
        Command::Completions { shell } => {
            completions::run::<Cli>(shell);
            Ok(())
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure { code, message }) => {
            eprintln!("rbf: {message}");
            ExitCode::from(code)
        }
    }
}
