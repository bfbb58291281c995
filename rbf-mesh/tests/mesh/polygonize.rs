//! Polygonizers on closed test surfaces: watertight, right genus and components, vertices on
//! the surface, outward normals.

use rbf_core::{Constraint, FitSettings, Interpolant, InterpolantView, Kernel, Model, fit};
use rbf_mesh::{
    BlockSkip, PolygonizeSettings, Resolution, TriMesh, polygonize_continuation, polygonize_grid,
    surface_extent, surface_seeds,
};

use rbf_core::shapes::{fibonacci_sphere, tetrahedron_blob};

fn fibonacci(n: usize) -> impl Iterator<Item = [f64; 3]> {
    fibonacci_sphere(n).into_iter()
}

fn model(constraints: Vec<Constraint<3>>) -> Model<3> {
    let settings = FitSettings::default();
    let f = fit(&constraints, &settings).unwrap();
    Model {
        constraints,
        settings,
        interpolant: f.interpolant,
        report: Some(f.report),
    }
}

fn sphere_at(centre: [f64; 3], n: usize) -> Vec<Constraint<3>> {
    fibonacci(n)
        .map(|d| Constraint::normal([centre[0] + d[0], centre[1] + d[1], centre[2] + d[2]], d))
        .collect()
}

fn torus(n: usize) -> Vec<Constraint<3>> {
    rbf_core::shapes::torus(n, 0.4)
}

/// Every property a polygonizer promises, checked on one mesh.
fn assert_good(name: &str, f: &Interpolant<f64, 3>, mesh: &TriMesh, genus: i64, components: usize) {
    let r = mesh.check();
    assert!(r.is_watertight(), "{name}: {r:?}");
    assert_eq!(r.genus, Some(genus), "{name}");
    assert_eq!(r.components, components, "{name}");
    assert_eq!(
        (
            r.duplicate_triangles,
            r.degenerate_triangles,
            r.unused_vertices
        ),
        (0, 0, 0),
        "{name}"
    );
    assert!(r.volume > 0.0, "{name}: triangles face outward");
    let (lo, hi) = r.bounding_box;
    let diagonal = crate::norm([hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]]);
    let normals = mesh.normals().unwrap();
    for (p, n) in mesh.positions().iter().zip(normals) {
        let (v, g) = f.value_and_gradient(p);
        let distance = v.abs() / crate::norm(g);
        assert!(
            distance < 1e-6 * diagonal,
            "{name}: vertex {p:?} is {distance:e} from the surface"
        );
        // Outward: against the gradient (f decreases outward).
        assert!((crate::norm(*n) - 1.0).abs() < 1e-12);
        assert!(n[0] * g[0] + n[1] * g[1] + n[2] * g[2] < 0.0);
    }
    // No slivers, and no triangle turned over: each faces the way its vertices' normals do.
    let p = mesh.positions();
    for t in mesh.triangles() {
        let [a, b, c] = t.map(|v| p[v as usize]);
        let e: [[f64; 3]; 2] = [
            core::array::from_fn(|d| b[d] - a[d]),
            core::array::from_fn(|d| c[d] - a[d]),
        ];
        let n = [
            e[0][1] * e[1][2] - e[0][2] * e[1][1],
            e[0][2] * e[1][0] - e[0][0] * e[1][2],
            e[0][0] * e[1][1] - e[0][1] * e[1][0],
        ];
        let vertex_normal: f64 = t
            .iter()
            .map(|&v| (0..3).map(|d| n[d] * normals[v as usize][d]).sum::<f64>())
            .sum();
        assert!(
            vertex_normal > 0.0,
            "{name}: triangle {t:?} faces against its vertices' normals"
        );
    }
    for t in mesh.triangles() {
        let angle = smallest_angle(t.map(|v| p[v as usize]));
        assert!(angle >= 5.0, "{name}: a triangle with an angle of {angle}°");
    }
    // No two vertices within 1e-7 of the diagonal (well under 1e-6 of a cell here), and the
    // mesh keeps its topology when vertices within 1e-8 of it are merged, as mesh tools do.
    let tolerance = 1e-8 * diagonal;
    let (merged, closest) = merge_close_vertices(mesh, tolerance);
    assert!(
        closest >= 1e-7 * diagonal,
        "{name}: two vertices {closest:e} apart"
    );
    let m = merged.check();
    assert!(m.is_watertight(), "{name} after merging: {m:?}");
    assert_eq!(
        (m.genus, m.components),
        (r.genus, r.components),
        "{name} after merging"
    );
}

/// The smallest angle of a triangle, in degrees.
fn smallest_angle(t: [[f64; 3]; 3]) -> f64 {
    (0..3)
        .map(|k| {
            let a: [f64; 3] = core::array::from_fn(|d| t[(k + 1) % 3][d] - t[k][d]);
            let b: [f64; 3] = core::array::from_fn(|d| t[(k + 2) % 3][d] - t[k][d]);
            let c = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (crate::norm(a) * crate::norm(b));
            c.clamp(-1.0, 1.0).acos().to_degrees()
        })
        .fold(f64::INFINITY, f64::min)
}

/// Merges vertices within `tolerance` of each other (as trimesh's `merge_vertices` and
/// MeshLab's "merge close vertices" do) and drops the triangles that collapse; also the
/// smallest distance between two vertices.
fn merge_close_vertices(mesh: &TriMesh, tolerance: f64) -> (TriMesh, f64) {
    use std::collections::HashMap;
    let p = mesh.positions();
    let mut root: Vec<usize> = (0..p.len()).collect();
    let find = |root: &mut Vec<usize>, mut i: usize| {
        while root[i] != i {
            root[i] = root[root[i]];
            i = root[i];
        }
        i
    };
    // Pairs by a grid of cells of 1e5 tolerances (1e-3 of the diagonal).
    let coarse = tolerance * 1e5;
    let mut buckets: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for (i, q) in p.iter().enumerate() {
        buckets
            .entry(q.map(|c| (c / coarse).floor() as i64))
            .or_default()
            .push(i);
    }
    let mut closest = f64::INFINITY;
    for (i, q) in p.iter().enumerate() {
        let k = q.map(|c| (c / coarse).floor() as i64);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    for &j in buckets
                        .get(&[k[0] + dx, k[1] + dy, k[2] + dz])
                        .into_iter()
                        .flatten()
                    {
                        if j > i {
                            let d = crate::norm(core::array::from_fn(|c| p[j][c] - q[c]));
                            closest = closest.min(d);
                            if d <= tolerance {
                                let (a, b) = (find(&mut root, i), find(&mut root, j));
                                root[a] = b;
                            }
                        }
                    }
                }
            }
        }
    }
    // Keep one vertex per merged group, numbered afresh.
    let mut index = vec![u32::MAX; p.len()];
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for t in mesh.triangles() {
        let t = t.map(|v| find(&mut root, v as usize));
        if t[0] == t[1] || t[1] == t[2] || t[2] == t[0] {
            continue;
        }
        triangles.push(t.map(|v| {
            if index[v] == u32::MAX {
                index[v] = positions.len() as u32;
                positions.push(p[v]);
            }
            index[v]
        }));
    }
    (TriMesh::new(positions, triangles).unwrap(), closest)
}

fn settings(cells: usize) -> PolygonizeSettings {
    PolygonizeSettings {
        resolution: Resolution::Cells(cells),
        ..Default::default()
    }
}

#[test]
fn sphere_by_both_methods() {
    let m = model(sphere_at([0.0; 3], 150));
    let f = m.interpolant.view();
    let (grid, _) = polygonize_grid(&f, &settings(40)).unwrap();
    assert_good("sphere/grid", &m.interpolant, &grid, 0, 1);
    // Finer, most blocks lie away from the surface and are skipped; the surface is the same.
    let (fine, stats) = polygonize_grid(&f, &settings(96)).unwrap();
    assert_good("sphere/grid/96", &m.interpolant, &fine, 0, 1);
    assert!(stats.skipped_blocks > 0, "{stats:?}");
    let s = PolygonizeSettings {
        skip: BlockSkip::Never,
        ..settings(96)
    };
    let (all, _) = polygonize_grid(&f, &s).unwrap();
    assert_eq!(all.triangles().len(), fine.triangles().len());
    let volume = grid.check().volume;
    assert!(
        (volume - 4.0 / 3.0 * std::f64::consts::PI).abs() < 0.02 * volume,
        "{volume}"
    );
    let (cont, _) = polygonize_continuation(&f, &surface_seeds(&m), &settings(40)).unwrap();
    assert_good("sphere/continuation", &m.interpolant, &cont, 0, 1);
    // The same lattice and cells: the same surface.
    assert_eq!(cont.triangles().len(), grid.triangles().len());
}

#[test]
fn torus_has_genus_one() {
    let m = model(torus(400));
    let f = m.interpolant.view();
    let (grid, _) = polygonize_grid(&f, &settings(48)).unwrap();
    assert_good("torus/grid", &m.interpolant, &grid, 1, 1);
    let (cont, _) = polygonize_continuation(&f, &surface_seeds(&m), &settings(48)).unwrap();
    assert_good("torus/continuation", &m.interpolant, &cont, 1, 1);
    // Finer, the lattice's mesh has about 7·10⁴ vertices before simplification (three per
    // vertex kept), which is then done in four parts, in parallel: the guarantees hold across
    // the seams between parts.
    let (fine, _) = polygonize_continuation(&f, &surface_seeds(&m), &settings(128)).unwrap();
    assert!(
        fine.positions().len() > 20_000,
        "{}",
        fine.positions().len()
    );
    assert_good("torus/continuation/128", &m.interpolant, &fine, 1, 1);
}

#[test]
fn without_root_finding_the_same_topology_near_the_surface() {
    // A torus and a sphere: no root finding leaves each vertex at its edge's secant point,
    // within 0.15 of a cube of the surface (0.11 here), and keeps the sign pattern's genus
    // and components, the same as with root finding.
    let mut constraints = torus(400);
    constraints.extend(sphere_at([3.0, 0.0, 0.0], 150));
    let m = model(constraints);
    let f = m.interpolant.view();
    let rough = PolygonizeSettings {
        root_iterations: 0,
        ..settings(64)
    };
    let (exact, _) = polygonize_continuation(&f, &surface_seeds(&m), &settings(64)).unwrap();
    let (secant, stats) = polygonize_continuation(&f, &surface_seeds(&m), &rough).unwrap();
    let (a, b) = (exact.check(), secant.check());
    assert!(b.is_watertight(), "{b:?}");
    assert_eq!((b.genus, b.components), (Some(1), 2));
    assert_eq!((a.genus, a.components), (b.genus, b.components));
    assert!(secant.normals().is_none());
    let mut worst: f64 = 0.0;
    for p in secant.positions() {
        let (v, g) = m.interpolant.value_and_gradient(p);
        worst = worst.max(v.abs() / crate::norm(g) / stats.cell_size);
    }
    assert!(worst < 0.15, "{worst}");
    // The vertex counts differ by what the second simplification after root finding merges.
    let (na, nb) = (exact.positions().len(), secant.positions().len());
    assert!(na.abs_diff(nb) * 20 < na, "{na} {nb}");
}

#[test]
fn surface_extent_is_the_box_of_the_mesh_within_a_fraction_of_a_cube() {
    // The torus lies in the box [−1.4, 1.4]² × [−0.4, 0.4] (radii 1 and 0.4).
    let m = model(torus(400));
    let f = m.interpolant.view();
    let seeds = surface_seeds(&m);
    for cells in [12, 40] {
        let ((lo, hi), stats) = surface_extent(&f, &seeds, &settings(cells)).unwrap();
        let (mesh, mesh_stats) = polygonize_continuation(&f, &seeds, &settings(cells)).unwrap();
        assert_eq!(stats.cell_size, mesh_stats.cell_size);
        let (mlo, mhi) = mesh.bounding_box();
        // Linear interpolation along an edge is off the root by a fraction of the edge.
        let near = 0.2 * stats.cell_size;
        for d in 0..3 {
            assert!((lo[d] - mlo[d]).abs() < near, "{cells}: {lo:?} {mlo:?}");
            assert!((hi[d] - mhi[d]).abs() < near, "{cells}: {hi:?} {mhi:?}");
        }
        assert!(
            (hi[2] - 0.4).abs() < 0.05 && (lo[0] + 1.4).abs() < 0.05,
            "{lo:?} {hi:?}"
        );
    }
    // Nothing to find from a seed far from any surface of a field without one.
    let empty = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[0.0], -1.0, [0.0; 3]).unwrap();
    let s = PolygonizeSettings {
        bounds: Some(([-1.0; 3], [1.0; 3])),
        ..settings(8)
    };
    assert!(matches!(
        surface_extent(&empty, &[[0.5; 3]], &s),
        Err(rbf_mesh::MeshError::Empty)
    ));
}

#[test]
fn tetrahedron_blob_of_paper_000() {
    let m = model(tetrahedron_blob());
    let f = m.interpolant.view();
    let (grid, _) = polygonize_grid(&f, &settings(30)).unwrap();
    assert_good("blob/grid", &m.interpolant, &grid, 0, 1);
    let (cont, _) = polygonize_continuation(&f, &surface_seeds(&m), &settings(30)).unwrap();
    assert_good("blob/continuation", &m.interpolant, &cont, 0, 1);
}

#[test]
fn two_components_are_both_found() {
    let mut cs = sphere_at([0.0; 3], 100);
    cs.extend(sphere_at([3.5, 0.0, 0.0], 100));
    let m = model(cs);
    let f = m.interpolant.view();
    let (grid, _) = polygonize_grid(&f, &settings(60)).unwrap();
    assert_good("two/grid", &m.interpolant, &grid, 0, 2);
    let (cont, _) = polygonize_continuation(&f, &surface_seeds(&m), &settings(60)).unwrap();
    assert_good("two/continuation", &m.interpolant, &cont, 0, 2);
    // Seeded on one sphere only, continuation finds that one alone.
    let (one, _) = polygonize_continuation(&f, &[[1.0, 0.0, 0.0]], &settings(60)).unwrap();
    assert_eq!(one.check().components, 1);
}

#[test]
fn zeros_exactly_at_lattice_points_open_no_holes() {
    // f = 1 − |x|³ is exactly 0 at (±1, 0, 0) etc., which are lattice points here (h = 0.25).
    let f = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[-1.0], 1.0, [0.0; 3]).unwrap();
    let owned = Interpolant::new(Kernel::Cubic, vec![[0.0; 3]], vec![-1.0], 1.0, [0.0; 3]).unwrap();
    let s = PolygonizeSettings {
        bounds: Some(([-1.5; 3], [1.5; 3])),
        resolution: Resolution::CellSize(0.25),
        ..Default::default()
    };
    assert_eq!(f.value(&[1.0, 0.0, 0.0]), 0.0);
    let (mesh, _) = polygonize_grid(&f, &s).unwrap();
    assert_good("exact zeros", &owned, &mesh, 0, 1);
}

#[test]
fn bad_settings_are_errors() {
    let f = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[-1.0], 1.0, [0.0; 3]).unwrap();
    for resolution in [
        Resolution::CellSize(0.0),
        Resolution::CellSize(f64::NAN),
        Resolution::Cells(0),
        Resolution::CellSize(1e-9),
    ] {
        let s = PolygonizeSettings {
            resolution,
            ..Default::default()
        };
        assert!(polygonize_grid(&f, &s).is_err(), "{resolution:?}");
    }
    let s = PolygonizeSettings {
        bounds: Some(([5.0; 3], [6.0; 3])),
        ..Default::default()
    };
    let e = polygonize_grid(&f, &s).unwrap_err();
    assert!(e.to_string().contains("no surface"), "{e}");
}

/// scikit-image's marching cubes on the same lattices (`fixtures/marching_cubes.json`, made by
/// `fixtures/make_marching_cubes_fixture.py` from scipy's fit of the same constraints): both
/// polygonizers make at most 1.3 times its triangles, and keep every promise above.
#[test]
fn at_most_1_3_times_the_triangles_of_marching_cubes() {
    let text = include_str!("../fixtures/marching_cubes.json");
    let fixture: serde_json::Value = serde_json::from_str(text).unwrap();
    for case in fixture["cases"].as_array().unwrap() {
        let name = case["name"].as_str().unwrap();
        let triple = |v: &serde_json::Value| -> [f64; 3] {
            core::array::from_fn(|d| v[d].as_f64().unwrap())
        };
        let constraints: Vec<Constraint<3>> = case["points"]
            .as_array()
            .unwrap()
            .iter()
            .zip(case["values"].as_array().unwrap())
            .map(|(p, v)| match v.as_f64().unwrap() {
                0.0 => Constraint::boundary(triple(p)),
                value => Constraint::interior(triple(p), value),
            })
            .collect();
        let m = model(constraints);
        let f = m.interpolant.view();
        let s = PolygonizeSettings {
            bounds: Some((triple(&case["lo"]), triple(&case["hi"]))),
            resolution: Resolution::Cells(case["cells"].as_u64().unwrap() as usize),
            ..Default::default()
        };
        let reference = case["marching_cubes_triangles"].as_u64().unwrap() as f64;
        let genus = case["genus"].as_i64().unwrap();
        let (grid, stats) = polygonize_grid(&f, &s).unwrap();
        assert_eq!(stats.cells, [64; 3], "{name}: the fixture's lattice");
        let (cont, _) = polygonize_continuation(&f, &surface_seeds(&m), &s).unwrap();
        for (method, mesh) in [("grid", grid), ("continuation", cont)] {
            let ratio = mesh.triangles().len() as f64 / reference;
            assert!(
                ratio <= 1.3 && ratio > 0.5,
                "{name}/{method}: {ratio} × marching cubes"
            );
            assert_good(&format!("{name}/{method}"), &m.interpolant, &mesh, genus, 1);
        }
    }
}

/// A lattice too large to sample whole (2000³ cubes over the unit sphere's box) is refused
/// before anything is allocated, with the cube counts and what to do.
#[test]
fn a_grid_too_large_is_refused_not_allocated() {
    let f = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[-1.0], 1.0, [0.0; 3]).unwrap();
    let settings = PolygonizeSettings {
        bounds: Some(([-1.5; 3], [1.5; 3])),
        resolution: Resolution::Cells(2000),
        ..Default::default()
    };
    let err = polygonize_grid(&f, &settings).unwrap_err().to_string();
    assert!(err.contains("[2000, 2000, 2000] cubes"), "{err}");
    assert!(err.contains("larger cell size"), "{err}");
}
