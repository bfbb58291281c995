//! The voxelizer against an independent inside test (exact winding numbers) and against the
//! meshes' volumes.

use rbf_mesh::{
    TriMesh, VoxelMethod, VoxelSettings, read_mesh, voxelize, winding_numbers,
    winding_numbers_exact,
};

use crate::data;

#[test]
fn occupancy_agrees_with_winding_numbers_on_every_shipped_mesh() {
    for name in ["torus.obj", "knot.obj", "spot.obj"] {
        let mesh = read_mesh(&data(name)).unwrap();
        // One ray and one sample per voxel: the voxel's value is its centre's inside status.
        let s = VoxelSettings {
            resolution: 32,
            supersampling: 1,
            ..Default::default()
        };
        let v = voxelize(&mesh, &s).unwrap();
        let [nx, ny, nz] = v.shape;
        let centres: Vec<[f64; 3]> = (0..nx)
            .flat_map(|i| (0..ny).flat_map(move |j| (0..nz).map(move |k| (i, j, k))))
            .map(|(i, j, k)| v.centre(i, j, k))
            .collect();
        let w = winding_numbers_exact(&mesh, &centres);
        // The fast hierarchical evaluation is within a few hundredths and classifies every
        // centre the same way.
        let fast = winding_numbers(&mesh, &centres);
        for (a, b) in w.iter().zip(&fast) {
            assert!((a - b).abs() < 0.1, "{name}: {a} vs {b}");
            assert_eq!(*a > 0.5, *b > 0.5, "{name}: {a} vs {b}");
        }
        let agree = v
            .data
            .iter()
            .zip(&w)
            .filter(|(d, w)| (**d > 0.5) == (**w > 0.5))
            .count();
        let fraction = agree as f64 / w.len() as f64;
        assert!(fraction >= 0.995, "{name}: {fraction}");
        // Exactly, in fact, for centres not within rounding of the surface.
        assert!(
            w.len() - agree <= 2,
            "{name}: {} disagreements",
            w.len() - agree
        );
    }
}

#[test]
fn supersampled_densities_add_up_to_the_volume() {
    for name in ["torus.obj", "spot.obj"] {
        let mesh = read_mesh(&data(name)).unwrap();
        let v = voxelize(
            &mesh,
            &VoxelSettings {
                resolution: 48,
                ..Default::default()
            },
        )
        .unwrap();
        let total: f64 = v.data.iter().map(|&d| d as f64).sum::<f64>() * v.voxel_size.powi(3);
        let exact = mesh.volume();
        assert!(
            (total - exact).abs() < 0.01 * exact,
            "{name}: {total} vs {exact}"
        );
        // Partial densities only near the surface; the margin is empty.
        assert!(v.data.iter().all(|&d| (0.0..=1.0).contains(&d)));
        assert!(v.data.iter().any(|&d| d > 0.0 && d < 1.0));
        let [_, ny, nz] = v.shape;
        assert!(v.data[..ny * nz].iter().all(|&d| d == 0.0));
    }
}

#[test]
fn a_torus_with_holes_is_still_classified_by_winding_numbers() {
    let torus = read_mesh(&data("torus.obj")).unwrap();
    // Punch holes: drop every 97th triangle, and add a flipped copy of another.
    let mut tris: Vec<[u32; 3]> = torus
        .triangles()
        .iter()
        .enumerate()
        .filter(|(t, _)| t % 97 != 5)
        .map(|(_, t)| *t)
        .collect();
    let t = tris[10];
    tris.push([t[0], t[2], t[1]]);
    let holed = TriMesh::new(torus.positions().to_vec(), tris).unwrap();
    assert!(!holed.check().is_watertight());
    let s = VoxelSettings {
        resolution: 40,
        ..Default::default()
    };
    let auto = voxelize(&holed, &s).unwrap();
    let exact = voxelize(
        &torus,
        &VoxelSettings {
            method: VoxelMethod::Rays,
            ..s
        },
    )
    .unwrap();
    // Auto chose winding numbers: the result matches the intact torus almost everywhere.
    let differ = auto
        .data
        .iter()
        .zip(&exact.data)
        .filter(|(a, b)| (**a > 0.5) != (**b > 0.5))
        .count();
    assert!(
        (differ as f64) < 0.002 * exact.data.len() as f64,
        "{differ} voxels differ"
    );
    // The tube is inside, the hole of the ring and the far corner are outside.
    let at = |p: [f64; 3]| {
        let idx: [usize; 3] =
            core::array::from_fn(|d| ((p[d] - auto.origin[d]) / auto.voxel_size).round() as usize);
        auto.get(idx[0], idx[1], idx[2])
    };
    assert_eq!(at([1.0, 0.0, 0.0]), 1.0);
    assert_eq!(at([0.0, 0.0, 0.0]), 0.0);
    // Rays on the holed mesh, by contrast, leak.
    let rays = voxelize(
        &holed,
        &VoxelSettings {
            method: VoxelMethod::Rays,
            ..s
        },
    )
    .unwrap();
    let leaked = rays
        .data
        .iter()
        .zip(&exact.data)
        .filter(|(a, b)| (**a > 0.5) != (**b > 0.5))
        .count();
    assert!(leaked > differ, "rays {leaked} vs winding {differ}");
}

/// Found by fuzzing: a mesh whose extent is subnormal made the voxel size 0 and the grid's
/// size overflow. Now a clear error; tiny and huge meshes voxelize without a panic.
#[test]
fn meshes_too_small_or_too_large_to_voxelize_are_errors() {
    for scale in [5e-324, 1e-310, 1e300] {
        let mesh = rbf_mesh::TriMesh::new(
            vec![
                [0.0, 0.0, 0.0],
                [scale, 0.0, 0.0],
                [0.0, scale, 0.0],
                [0.0, 0.0, scale],
            ],
            vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
        )
        .unwrap();
        for method in [rbf_mesh::VoxelMethod::Rays, rbf_mesh::VoxelMethod::Winding] {
            let settings = rbf_mesh::VoxelSettings {
                resolution: 8,
                method,
                ..Default::default()
            };
            let result = rbf_mesh::voxelize(&mesh, &settings);
            // The smallest subnormal makes the voxel size 0: refused. The others must simply
            // not panic (their triangles' areas underflow, so nothing is inside).
            if scale == 5e-324 {
                let e = result.err().map(|e| e.to_string()).unwrap_or_default();
                assert!(e.contains("cannot be cut into voxels"), "{e}");
            }
        }
    }
}

#[test]
fn supersampling_outside_its_range_is_an_error_before_anything_is_allocated() {
    let mesh = TriMesh::new(
        vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    )
    .unwrap();
    for method in [VoxelMethod::Rays, VoxelMethod::Winding] {
        for supersampling in [0, rbf_mesh::MAX_SUPERSAMPLING + 1, 1 << 20] {
            let settings = VoxelSettings {
                resolution: 8,
                supersampling,
                method,
                ..Default::default()
            };
            let e = voxelize(&mesh, &settings).err().map(|e| e.to_string());
            assert!(
                e.as_deref().is_some_and(|e| e.contains("(1 to 16)")),
                "{supersampling}: {e:?}"
            );
        }
        let settings = VoxelSettings {
            resolution: 8,
            supersampling: rbf_mesh::MAX_SUPERSAMPLING,
            method,
            ..Default::default()
        };
        assert!(voxelize(&mesh, &settings).is_ok());
    }
}
