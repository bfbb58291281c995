//! Conversions keep the mesh's topology where its parts come closer than a voxel: shapes made
//! here with gaps and holes narrower than the conversion's voxels.

use std::collections::HashMap;

use rbf_convert::{IterativeReport, IterativeSettings, convert_iterative};
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

/// A bowl: a spherical shell of radius `r` and wall `t` around the origin, below the plane
/// z = `rim`, closed by a flat rim; `around` × `down` quads on each side.
fn bowl(r: f64, t: f64, rim: f64, around: u32, down: u32) -> TriMesh {
    let tau = std::f64::consts::TAU;
    let mut positions = Vec::new();
    // Outer side first, then inner: a pole and `down` rings each, the last ring on the rim.
    for radius in [r + 0.5 * t, r - 0.5 * t] {
        positions.push([0.0, 0.0, -radius]);
        let top = (-rim / radius).acos();
        for k in 1..=down {
            let polar = top * k as f64 / down as f64;
            for i in 0..around {
                let a = tau * i as f64 / around as f64;
                let ring = radius * polar.sin();
                positions.push([ring * a.cos(), ring * a.sin(), -radius * polar.cos()]);
            }
        }
    }
    let side = 1 + down * around;
    let at = |s: u32, k: u32, i: u32| s * side + 1 + (k - 1) * around + i % around;
    let mut triangles = Vec::new();
    for s in 0..2 {
        // The outer side faces away from the centre, the inner towards it.
        let mut push = |t: [u32; 3]| triangles.push(if s == 0 { t } else { [t[0], t[2], t[1]] });
        for i in 0..around {
            push([s * side, at(s, 1, i + 1), at(s, 1, i)]);
            for k in 1..down {
                let (a, b) = (at(s, k, i), at(s, k, i + 1));
                let (c, d) = (at(s, k + 1, i + 1), at(s, k + 1, i));
                push([a, b, c]);
                push([a, c, d]);
            }
        }
    }
    for i in 0..around {
        let (a, b) = (at(0, down, i), at(0, down, i + 1));
        let (c, d) = (at(1, down, i + 1), at(1, down, i));
        triangles.push([a, b, c]);
        triangles.push([a, c, d]);
    }
    let mut mesh = TriMesh::new(positions, triangles).unwrap();
    if mesh.volume() < 0.0 {
        mesh.flip();
    }
    mesh
}

/// A watertight bowl of genus 0 with a wall `wall` thick, converted at 32 voxels with a budget
/// of 1000 constraints.
fn bowl_at_32_voxels(wall: f64) -> (IterativeSettings, Model<3>, IterativeReport) {
    let mesh = bowl(0.9, wall, 0.5, 96, 40);
    let r = mesh.check();
    assert!(r.is_watertight() && r.genus == Some(0), "{r:?}");
    let settings = IterativeSettings {
        resolution: 32,
        max_constraints: 1000,
        ..Default::default()
    };
    let (model, report) = convert_iterative(&mesh, &settings, |_, _| {}).unwrap();
    (settings, model, report)
}

#[test]
fn a_bowl_with_a_wall_under_a_voxel_is_not_given_up_to_its_probes() {
    // A wall of 0.046 against voxels of 1.85 / 32 = 0.058: 0.8 voxel. Every vertex lies on a
    // part thinner than two voxels; the first fits leave nearly all of their probes violated,
    // more than the budget holds. Taken at once, they filled it after the first iteration,
    // whose model (3.5 voxels off) was the one kept; added a share at a time, the loop places
    // its own constraints too and ends within two voxels.
    let (settings, model, report) = bowl_at_32_voxels(0.046);
    let t = report.topology.unwrap();
    assert!(t.probes > settings.max_constraints, "{t:?}");
    // The loop's own best model (its rival, normal constraints at the vertices, may be kept
    // instead where the loop falls short: here it is, 1.0 voxel off with the bowl's genus).
    let best = &report.iterations[report.best - 1];
    assert!(best.max_error <= 2.0, "{best:?}");
    assert!(best.boundary + best.interior + best.exterior > settings.max_constraints / 2);
    assert!(report.rival.is_some_and(|r| r.kept), "{:?}", report.rival);
    // Inside the wall, and outside both in the bowl and under it.
    assert!(model.interpolant.value(&[0.0, 0.0, -0.9]) > 0.0);
    assert!(model.interpolant.value(&[0.0, 0.0, -0.6]) < 0.0);
    assert!(model.interpolant.value(&[0.0, 0.0, -1.2]) < 0.0);
}

#[test]
fn a_shell_two_voxels_thick_that_the_loop_cannot_hold_goes_to_its_rival() {
    // A bowl's wall of 0.116 against voxels of 1.9 / 32 = 0.059: two voxels, just too thick
    // for the thin-part probes. The loop's best model (1.7 voxels off, 1000 constraints) has
    // a topology other than the bowl's; normal constraints at the vertices, their inside
    // points kept within the wall, hold both sides.
    let (settings, model, report) = bowl_at_32_voxels(0.116);
    let rival = report.rival.expect("the loop falls short");
    assert!(rival.kept, "{rival:?} {:?}", report.topology);
    let t = report.topology.unwrap();
    assert!(t.agrees(), "{t:?}");
    assert!(rival.max_error <= 2.0, "{rival:?}");
    let rows: usize = model.constraints.iter().map(|c| c.rows()).sum();
    assert!(rows <= settings.max_constraints, "{rows}");
    // Inside the wall, and outside both in the bowl and under it.
    assert!(model.interpolant.value(&[0.0, 0.0, -0.9]) > 0.0);
    assert!(model.interpolant.value(&[0.0, 0.0, -0.75]) < 0.0);
    assert!(model.interpolant.value(&[0.0, 0.0, -1.05]) < 0.0);
}

#[test]
fn a_shell_two_voxels_thick_at_128_is_held_by_slabs() {
    // A bowl's wall of 0.03 against voxels of 1.9 / 128 = 0.0148: two voxels, just too thick
    // for the thin-part probes and under two normal offsets (0.038). The loop's own model falls
    // short (2.45 voxels off, and before slabs its rival too: genus 64); the rival's slabs
    // hold both sides of the wall, and its refinement ends the wall at the rim.
    let mesh = bowl(0.9, 0.03, 0.5, 96, 40);
    let (model, report) =
        convert_iterative(&mesh, &IterativeSettings::default(), |_, _| {}).unwrap();
    let rival = report.rival.expect("the loop falls short");
    assert!(rival.kept, "{rival:?}");
    assert!(
        rival.max_error <= 1.5 && rival.rms_error <= 0.2,
        "{rival:?}"
    );
    let t = report.topology.unwrap();
    assert_eq!(t.components, 1, "{t:?}");
    assert!(t.genus.is_some_and(|g| g <= 1), "{t:?}");
    // Inside the wall, outside it on both sides, all around the bowl.
    for k in 0..12 {
        let a = k as f64 * std::f64::consts::TAU / 12.0;
        let at = |r: f64| [r * 0.6 * a.cos(), r * 0.6 * a.sin(), -r * 0.8];
        assert!(model.interpolant.value(&at(0.9)) > 0.0, "{k}");
        assert!(model.interpolant.value(&at(0.9 - 0.045)) < 0.0, "{k}");
        assert!(model.interpolant.value(&at(0.9 + 0.045)) < 0.0, "{k}");
    }
}
