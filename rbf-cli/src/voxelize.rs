//! `rbf voxelize`: a mesh's inside as densities (or signed distances) on a grid, for NumPy.

use std::path::PathBuf;
use std::time::Instant;

use clap::{Args, ValueEnum};
use rbf_mesh::{VoxelMethod, VoxelSettings, signed_distance, voxelize};

use crate::common::{read_mesh, write_atomically};
use crate::failure::{BAD_INPUT, Failure};

pub(crate) const HELP: &str = "\
Writes OUT.npy, a float32 array indexed [x][y][z] (numpy.load reads it), and beside it OUT.json
with `origin` (the centre of voxel (0,0,0)), `voxel_size` and `shape`. Values are the fraction of
each voxel inside the mesh (0…1), or with --signed-distance the distance to the surface,
positive inside, in the mesh's units.

Examples:
  rbf voxelize bunny.obj --resolution 128 -o bunny.npy
  rbf voxelize scan.ply --resolution 64 --signed-distance -o scan_sd.npy
  python3 -c \"import numpy; print(numpy.load('bunny.npy').shape)\"";

#[derive(Args, Debug)]
pub(crate) struct VoxelizeArgs {
    /// Mesh file (.obj, .ply, .stl).
    mesh: PathBuf,
    /// Output array (.npy); its metadata goes to the same name with .json.
    #[arg(short, long, value_name = "OUT.npy")]
    output: PathBuf,
    /// Voxels along the longest side of the mesh's bounding box.
    #[arg(long, value_name = "N", default_value_t = 128)]
    resolution: usize,
    /// Sub-samples along each axis of a voxel.
    #[arg(long, value_name = "S", default_value_t = 4)]
    supersampling: usize,
    /// Write signed distances instead of densities.
    #[arg(long)]
    signed_distance: bool,
    /// Inside test [default: rays for watertight meshes, winding numbers otherwise].
    #[arg(long, value_enum, default_value_t = MethodArg::Auto)]
    method: MethodArg,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum MethodArg {
    /// Rays if the mesh is watertight, winding numbers if not.
    Auto,
    /// Parallel rays counting signed crossings.
    Rays,
    /// Generalized winding numbers (for meshes with holes or overlaps).
    Winding,
}

pub(crate) fn run(args: &VoxelizeArgs, quiet: bool) -> Result<(), Failure> {
    let mesh = read_mesh(&args.mesh)?;
    let settings = VoxelSettings {
        resolution: args.resolution,
        supersampling: args.supersampling,
        method: match args.method {
            MethodArg::Auto => VoxelMethod::Auto,
            MethodArg::Rays => VoxelMethod::Rays,
            MethodArg::Winding => VoxelMethod::Winding,
        },
        memory_limit: rbf_solve::memory_budget(),
        ..Default::default()
    };
    let start = Instant::now();
    let spinner = crate::common::spinner(quiet, "voxelizing".into());
    let result = voxelize(&mesh, &settings);
    let volume = match result {
        Ok(v) if args.signed_distance => Ok(signed_distance(&v)),
        other => other,
    };
    spinner.finish_and_clear();
    let volume =
        volume.map_err(|e| Failure::new(BAD_INPUT, format!("{}: {e}", args.mesh.display())))?;
    write_atomically(&args.output, &volume.to_npy())?;
    let meta = serde_json::json!({
        "origin": volume.origin,
        "voxel_size": volume.voxel_size,
        "shape": volume.shape,
        "values": if args.signed_distance { "signed distance, positive inside" } else { "fraction inside" },
    });
    let meta_path = args.output.with_extension("json");
    write_atomically(&meta_path, meta.to_string().as_bytes())?;
    if !quiet {
        eprintln!(
            "{} × {} × {} voxels of {:.4} in {:.2} s; wrote {} and {}",
            volume.shape[0],
            volume.shape[1],
            volume.shape[2],
            volume.voxel_size,
            start.elapsed().as_secs_f64(),
            args.output.display(),
            meta_path.display()
        );
    }
    Ok(())
}
