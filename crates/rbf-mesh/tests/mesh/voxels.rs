//! The voxelizer against an independent inside test (exact winding numbers) and against the
//! meshes' volumes.

use rbf_mesh::{VoxelSettings, read_mesh, voxelize, winding_numbers};

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
        let w = winding_numbers(&mesh, &centres);
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
