//! `rbf check`: what a mesh is made of and whether it is watertight.

use std::path::PathBuf;

use clap::Args;

use crate::common::read_mesh;
use crate::failure::Failure;

#[derive(Args, Debug)]
pub(crate) struct CheckArgs {
    /// Mesh file (.obj, .ply, .stl).
    mesh: PathBuf,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

pub(crate) fn run(args: &CheckArgs) -> Result<(), Failure> {
    let mesh = read_mesh(&args.mesh)?;
    let r = mesh.check();
    let (lo, hi) = r.bounding_box;
    if args.json {
        let json = serde_json::json!({
            "file": args.mesh.display().to_string(),
            "vertices": r.vertices,
            "unused_vertices": r.unused_vertices,
            "triangles": r.triangles,
            "edges": r.edges,
            "boundary_edges": r.boundary_edges,
            "non_manifold_edges": r.non_manifold_edges,
            "non_manifold_vertices": r.non_manifold_vertices,
            "inconsistent_edges": r.inconsistent_edges,
            "degenerate_triangles": r.degenerate_triangles,
            "duplicate_triangles": r.duplicate_triangles,
            "components": r.components,
            "euler_characteristic": r.euler_characteristic,
            "genus": r.genus,
            "watertight": r.is_watertight(),
            "volume": r.volume,
            "bounding_box": [lo, hi],
        });
        println!("{json}");
        return Ok(());
    }
    println!("{}", args.mesh.display());
    println!(
        "  {} vertices ({} unused), {} triangles, {} edges",
        r.vertices, r.unused_vertices, r.triangles, r.edges
    );
    println!(
        "  components {}, Euler characteristic {}, genus {}",
        r.components,
        r.euler_characteristic,
        r.genus
            .map_or("undefined (not a closed manifold)".into(), |g| g
                .to_string())
    );
    println!(
        "  boundary edges {}, non-manifold edges {}, non-manifold vertices {}, inconsistently oriented edges {}",
        r.boundary_edges, r.non_manifold_edges, r.non_manifold_vertices, r.inconsistent_edges
    );
    println!(
        "  degenerate triangles {}, duplicate triangles {}",
        r.degenerate_triangles, r.duplicate_triangles
    );
    println!("  bounding box {lo:?} – {hi:?}");
    if r.is_watertight() {
        let facing = if r.volume > 0.0 {
            "outward"
        } else {
            "inward (flip them)"
        };
        println!(
            "  watertight: yes; volume {:.6}, faces point {facing}",
            r.volume.abs()
        );
    } else {
        println!("  watertight: no");
    }
    Ok(())
}
