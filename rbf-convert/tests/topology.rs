//! Conversions keep the mesh's topology where its parts come closer than a voxel: shapes made
//! here with gaps and holes narrower than the conversion's voxels.

use std::collections::HashMap;

use rbf_convert::{IterativeSettings, convert_iterative};
use rbf_core::Model;
use rbf_mesh::TriMesh;

/// The boundary of a union of cubes of side `s` (cell (i, j, k) spans [i s, (i + 1) s] …),
/// triangles facing outward. Closed and manifold when no two filled cubes touch only along an
/// edge or at a corner.
fn blocky(filled: impl Fn([i64; 3]) -> bool, n: [i64; 3], s: f64) -> TriMesh {
    let mut index: HashMap<[i64; 3], u32> = HashMap::new();
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    let mut vertex = |p: [i64; 3]| {
        *index.entry(p).or_insert_with(|| {
            positions.push(p.map(|c| c as f64 * s));
            (positions.len() - 1) as u32
        })
    };
    for i in 0..n[0] {
        for j in 0..n[1] {
            for k in 0..n[2] {
                let c = [i, j, k];
                if !filled(c) {
                    continue;
                }
                for axis in 0..3 {
                    for side in [0, 1] {
                        let mut next = c;
                        next[axis] += if side == 1 { 1 } else { -1 };
                        if filled(next) {
                            continue;
                        }
                        // The face's corners, counter-clockwise seen from outside.
                        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
                        let corner = |a: i64, b: i64| {
                            let mut p = c;
                            p[axis] += side;
                            p[u] += a;
                            p[v] += b;
                            p
                        };
                        let mut q = [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)];
                        if side == 0 {
                            q.reverse();
                        }
                        let q = q.map(&mut vertex);
                        triangles.push([q[0], q[1], q[2]]);
                        triangles.push([q[0], q[2], q[3]]);
                    }
                }
            }
        }
    }
    TriMesh::new(positions, triangles).unwrap()
}

/// A torus around the y axis, radii `big` and `small`.
fn torus_mesh(big: f64, small: f64, around: u32, across: u32) -> TriMesh {
    let tau = std::f64::consts::TAU;
    let mut positions = Vec::new();
    for i in 0..around {
        for j in 0..across {
            let (u, v) = (
                tau * i as f64 / around as f64,
                tau * j as f64 / across as f64,
            );
            let ring = big + small * v.cos();
            positions.push([ring * u.cos(), small * v.sin(), ring * u.sin()]);
        }
    }
    let at = |i: u32, j: u32| (i % around) * across + (j % across);
    let mut triangles = Vec::new();
    for i in 0..around {
        for j in 0..across {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            triangles.push([a, c, b]);
            triangles.push([a, d, c]);
        }
    }
    let mut mesh = TriMesh::new(positions, triangles).unwrap();
    if mesh.volume() < 0.0 {
        mesh.flip();
    }
    mesh
}

/// Converts at `resolution` and checks the topology report against the mesh, and that f is
/// negative at every point of `gaps` (the middles of the narrow gaps).
fn converts_keeping_topology(
    name: &str,
    mesh: &TriMesh,
    resolution: usize,
    gaps: &[[f64; 3]],
) -> Model<3> {
    let r = mesh.check();
    assert!(r.is_watertight(), "{name}: the test mesh itself: {r:?}");
    let settings = IterativeSettings {
        resolution,
        ..Default::default()
    };
    let (model, report) = convert_iterative(mesh, &settings, |_, _| {}).unwrap();
    let t = report
        .topology
        .expect("a closed mesh gets the topology check");
    assert_eq!(
        (t.goal_genus, t.goal_components),
        (r.genus.unwrap(), r.components),
        "{name}"
    );
    assert!(t.agrees(), "{name}: {t:?}");
    for g in gaps {
        let v = model.interpolant.value(g);
        assert!(v < 0.0, "{name}: f = {v} in the gap at {g:?}");
    }
    model
}

#[test]
fn two_spheres_half_a_voxel_apart_stay_two() {
    // Voxels of (4 + g)/48 across the box and a gap g of half of one.
    let gap = 4.0 / 95.0;
    let shift = 1.0 + 0.5 * gap;
    let sphere = TriMesh::icosphere(4);
    let moved = |dx: f64| {
        sphere
            .positions()
            .iter()
            .map(move |p| [p[0] + dx, p[1], p[2]])
    };
    let positions: Vec<[f64; 3]> = moved(-shift).chain(moved(shift)).collect();
    let offset = sphere.positions().len() as u32;
    let triangles: Vec<[u32; 3]> = sphere
        .triangles()
        .iter()
        .copied()
        .chain(sphere.triangles().iter().map(|t| t.map(|v| v + offset)))
        .collect();
    let mesh = TriMesh::new(positions, triangles).unwrap();
    converts_keeping_topology("two spheres", &mesh, 48, &[[0.0; 3]]);
}

#[test]
fn a_comb_with_teeth_one_voxel_apart_stays_one_comb() {
    // Cells of half a voxel: teeth 4 cells wide, gaps of 2 (one voxel), a spine 4 cells high.
    let teeth = 5;
    let width = teeth * 4 + (teeth - 1) * 2;
    let filled = |c: [i64; 3]| {
        let inside = c.iter().all(|&x| x >= 0) && c[0] < width && c[1] < 20 && c[2] < 6;
        inside && (c[1] < 4 || c[0] % 6 < 4)
    };
    let s = 0.1;
    let mesh = blocky(filled, [width, 20, 6], s);
    // The longest side is `width` cells: width / 2 voxels.
    let gaps: Vec<[f64; 3]> = (0..teeth - 1)
        .map(|i| [(6 * i + 5) as f64 * s, 12.0 * s, 3.0 * s])
        .collect();
    converts_keeping_topology("comb", &mesh, (width / 2) as usize, &gaps);
}

#[test]
fn a_torus_with_a_hole_under_two_voxels_keeps_it() {
    // Hole 2 (1 − 0.93) = 0.14 across; voxels of 3.86 / 48 ≈ 0.080: 1.74 voxels.
    let mesh = torus_mesh(1.0, 0.93, 96, 48);
    converts_keeping_topology("torus", &mesh, 48, &[[0.0; 3]]);
}

#[test]
fn fingers_closer_than_a_voxel_stay_apart() {
    // Cells of 0.6 voxel: a palm and four fingers 3 cells wide, 1 cell (0.6 voxel) apart.
    let filled = |c: [i64; 3]| {
        let inside = c.iter().all(|&x| x >= 0) && c[0] < 15 && c[1] < 24 && c[2] < 4;
        inside && (c[1] < 10 || c[0] % 4 < 3)
    };
    let s = 0.1;
    let mesh = blocky(filled, [15, 24, 4], s);
    // The longest side, 24 cells, is 24 × 0.6 voxels.
    let gaps: Vec<[f64; 3]> = (0..3)
        .map(|i| [(4 * i + 3) as f64 * s + 0.5 * s, 18.0 * s, 2.0 * s])
        .collect();
    converts_keeping_topology("hand", &mesh, 14, &gaps);
}
