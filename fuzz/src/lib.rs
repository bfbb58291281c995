//! The bodies of the fuzz targets, as plain functions: each takes arbitrary bytes and must
//! return (an error is fine) without panicking, hanging or exhausting memory. The targets in
//! `fuzz_targets/` call them under libFuzzer; `tests/replay.rs` calls them on the corpora.

use std::path::Path;

use rbf_core::{AnyModel, Constraint, ConstraintFile, FitSettings, InterpolantView, Kernel};
use rbf_mesh::{PolygonizeSettings, Resolution, TriMesh, VoxelMethod, VoxelSettings};

/// Reads bytes as a mesh of the format named by `extension`, and checks it.
fn mesh(extension: &str, data: &[u8]) {
    if let Ok(m) = rbf_mesh::read_mesh_bytes(Path::new(&format!("input.{extension}")), data) {
        let _ = m.check();
    }
}

/// OBJ reader and mesh check.
pub fn obj(data: &[u8]) {
    mesh("obj", data);
}

/// PLY reader (ASCII and binary) and mesh check.
pub fn ply(data: &[u8]) {
    mesh("ply", data);
}

/// Point clouds: the `.npy` reader and the PLY reader's normals.
pub fn point_cloud(data: &[u8]) {
    let _ = rbf_mesh::read_npy_matrix("cloud.npy".as_ref(), data);
    let _ = rbf_mesh::read_point_cloud_bytes("cloud.npy".as_ref(), data);
    let _ = rbf_mesh::read_point_cloud_bytes("cloud.ply".as_ref(), data);
}

/// STL reader (ASCII and binary) and mesh check.
pub fn stl(data: &[u8]) {
    mesh("stl", data);
}

/// Text constraint files, 2D and 3D, and point files.
pub fn constraints_text(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    let _ = rbf_core::parse_constraints::<3>(&text);
    let _ = rbf_core::parse_constraints::<2>(&text);
    let _ = rbf_core::parse_points::<3>(&text);
}

/// JSON constraint files, then the system they describe (checks, no solve).
pub fn constraints_json(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    if let Ok(file) = ConstraintFile::from_json(&text) {
        let settings = file.settings(FitSettings::default());
        match file.dimension() {
            Ok(2) => {
                if let Ok(c) = file.constraints::<2>() {
                    let _ = rbf_core::System::new(&c, &settings);
                }
            }
            Ok(3) => {
                if let Ok(c) = file.constraints::<3>() {
                    let _ = rbf_core::System::new(&c, &settings);
                }
            }
            _ => {}
        }
    }
}

/// Model files; a model that reads is evaluated once.
pub fn model_json(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    match AnyModel::from_json(&text) {
        Ok(AnyModel::Two(m)) => {
            let _ = m.interpolant.value(&[0.5, 0.5]);
        }
        Ok(AnyModel::Three(m)) => {
            let _ = m.interpolant.value(&[0.5, 0.5, 0.5]);
        }
        Err(_) => {}
    }
}

/// Little-endian f64s from bytes (any bit pattern: NaN, infinities, huge, tiny).
fn floats(data: &[u8]) -> Vec<f64> {
    data.chunks_exact(8)
        .map(|c| f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
        .collect()
}

/// Floats from bytes, kept finite and moderate half of the time so that fits get far.
fn tame(data: &[u8]) -> Vec<f64> {
    let raw = floats(data);
    if data.first().is_some_and(|b| b & 1 == 0) {
        raw
    } else {
        raw.into_iter()
            .map(|v| if v.is_finite() { v.clamp(-1e3, 1e3) } else { 0.5 })
            .collect()
    }
}

/// Up to 24 constraints from arbitrary floats (kinds from the first byte's bits), fitted by
/// both solvers.
pub fn fit(data: &[u8]) {
    let Some((&kinds, rest)) = data.split_first() else {
        return;
    };
    let v = tame(rest);
    let constraints: Vec<Constraint<3>> = v
        .chunks_exact(4)
        .take(24)
        .enumerate()
        .map(|(i, c)| {
            let p = [c[0], c[1], c[2]];
            match (kinds >> (i % 4)) & 3 {
                0 => Constraint::boundary(p),
                1 => Constraint::interior(p, c[3]),
                2 => Constraint::exterior(p, c[3]),
                _ => Constraint::normal(p, [c[3], 1.0, 0.0]),
            }
        })
        .collect();
    let settings = FitSettings {
        kernel: Some(if kinds & 0x80 == 0 { Kernel::Cubic } else { Kernel::Linear }),
        ..Default::default()
    };
    let _ = rbf_core::fit(&constraints, &settings);
    let _ = rbf_solve::fit(&constraints, &settings);
    // Greedily, from a subset of four grown two at a time.
    let greedy = rbf_solve::GreedySettings {
        initial: 4,
        max_constraints: 12,
        ..Default::default()
    };
    let _ = rbf_solve::fit_greedy(&constraints, &settings, &greedy, |_| {});
}

/// An arbitrary model (centres, weights, affine part) evaluated at arbitrary points, one at a
/// time and in batches.
pub fn evaluate(data: &[u8]) {
    let v = floats(data);
    if v.len() < 8 {
        return;
    }
    let n = (v.len() - 4) / 8;
    let centres: Vec<[f64; 3]> = v[4..4 + 3 * n].chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    let weights: Vec<f64> = v[4 + 3 * n..4 + 4 * n].to_vec();
    let points: Vec<[f64; 3]> = v[4 + 4 * n..].chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    for kernel in [Kernel::Cubic, Kernel::Linear, Kernel::ThinPlate] {
        let Ok(f) = InterpolantView::new(kernel, &centres, &weights, v[0], [v[1], v[2], v[3]]) else {
            continue;
        };
        let mut out = vec![0.0; points.len()];
        let _ = f.values(&points, &mut out);
        for p in &points {
            let _ = f.value_gradient_hessian(p);
        }
    }
}

/// A small fitted model polygonized on a coarse lattice, both methods.
pub fn polygonize(data: &[u8]) {
    let v = tame(data);
    let constraints: Vec<Constraint<3>> = v
        .chunks_exact(3)
        .take(12)
        .map(|c| Constraint::boundary([c[0], c[1], c[2]]))
        .chain(core::iter::once(Constraint::interior([0.0; 3], 1.0)))
        .collect();
    let Ok(fit) = rbf_core::fit(&constraints, &FitSettings::default()) else {
        return;
    };
    let settings = PolygonizeSettings {
        resolution: Resolution::Cells(12),
        ..Default::default()
    };
    let f = fit.interpolant.view();
    let _ = rbf_mesh::polygonize_grid(&f, &settings);
    let seeds: Vec<[f64; 3]> = constraints.iter().map(|c| c.position).collect();
    let _ = rbf_mesh::polygonize_continuation(&f, &seeds, &settings);
}

/// A small arbitrary mesh (vertices from floats, triangles from bytes) voxelized both ways.
pub fn voxelize(data: &[u8]) {
    if data.len() < 2 {
        return;
    }
    let (counts, rest) = data.split_at(2);
    let vertices = usize::from(counts[0] % 16) + 1;
    let (vbytes, tbytes) = rest.split_at((vertices * 24).min(rest.len()));
    let positions: Vec<[f64; 3]> = tame(vbytes).chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    let triangles: Vec<[u32; 3]> = tbytes
        .chunks_exact(3)
        .take(usize::from(counts[1] % 32))
        .map(|t| [t[0], t[1], t[2]].map(|i| u32::from(i) % (positions.len().max(1) as u32)))
        .collect();
    let Ok(mesh) = TriMesh::new(positions, triangles) else {
        return;
    };
    for method in [VoxelMethod::Rays, VoxelMethod::Winding] {
        let settings = VoxelSettings {
            resolution: 8,
            supersampling: 2,
            method,
            ..Default::default()
        };
        if let Ok(v) = rbf_mesh::voxelize(&mesh, &settings) {
            let _ = rbf_mesh::signed_distance(&v);
        }
    }
}

/// The far field of an arbitrary cloud (any floats, duplicates, a point, a line) with arbitrary
/// settings from the first bytes, at arbitrary targets: values, gradients and the product at
/// the centres; then the evaluator's choice of method at an arbitrary accuracy.
pub fn far_field(data: &[u8]) {
    if data.len() < 4 {
        return;
    }
    let (head, rest) = data.split_at(4);
    let settings = rbf_far::FarFieldSettings {
        order: usize::from(head[0] % 18),
        theta: f64::from(head[1]) / 128.0,
        leaf: usize::from(head[2] % 20),
        target_leaf: usize::from(head[3] % 40),
    };
    let v = tame(rest);
    let n = (v.len() / 7).min(400);
    let centres: Vec<[f64; 3]> = v[..3 * n].chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    let weights = &v[3 * n..4 * n];
    let targets: Vec<[f64; 3]> = v[4 * n..].chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    for kernel in [Kernel::Cubic, Kernel::Linear, Kernel::ThinPlate] {
        let field = rbf_far::FarField::new(kernel, &centres, &settings);
        let Ok(charges) = field.charges(weights) else {
            continue;
        };
        let mut out = vec![0.0; targets.len()];
        let mut gradients = vec![[0.0; 3]; targets.len()];
        let _ = field.values(&charges, &targets, &mut out);
        let _ = field.values_and_gradients(&charges, &targets, &mut out, &mut gradients);
        let mut at_centres = vec![0.0; centres.len()];
        let _ = field.self_values(&charges, &mut at_centres);
        if let Ok(view) = InterpolantView::new(kernel, &centres, weights, 0.0, [0.0; 3]) {
            let accuracy = f64::from(head[0]) * 1e-3;
            let evaluator = rbf_far::Evaluator::new(view, &targets, accuracy);
            let _ = evaluator.values(&targets, &mut out);
        }
    }
}
