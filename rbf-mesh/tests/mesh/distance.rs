//! The distance transform against brute force, and signed distances of a voxelized mesh.

use rbf_mesh::{VoxelSettings, read_mesh, signed_distance, squared_distance_transform, voxelize};

use crate::data;

#[test]
fn the_transform_equals_brute_force_on_random_volumes() {
    let mut state = 0x2545_F491_4F6C_DD1D_u64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for round in 0..60 {
        let shape = [
            1 + (next() * 7.0) as usize,
            1 + (next() * 6.0) as usize,
            1 + (next() * 5.0) as usize,
        ];
        let n = shape[0] * shape[1] * shape[2];
        let density = if round % 3 == 0 { 0.05 } else { 0.3 };
        let cost: Vec<f64> = (0..n)
            .map(|_| {
                if next() < density {
                    (next() * 4.0).floor() * 0.25
                } else {
                    f64::INFINITY
                }
            })
            .collect();
        let mut fast = cost.clone();
        squared_distance_transform(shape, &mut fast);
        let coords = |p: usize| {
            [
                p / (shape[1] * shape[2]),
                (p / shape[2]) % shape[1],
                p % shape[2],
            ]
        };
        for p in 0..n {
            let a = coords(p);
            let brute = (0..n)
                .filter(|&q| cost[q].is_finite())
                .map(|q| {
                    let b = coords(q);
                    (0..3)
                        .map(|d| (a[d] as f64 - b[d] as f64).powi(2))
                        .sum::<f64>()
                        + cost[q]
                })
                .fold(f64::INFINITY, f64::min);
            assert!(
                brute == fast[p] || (brute - fast[p]).abs() < 1e-9,
                "round {round}, shape {shape:?}, voxel {a:?}: {} vs {brute}",
                fast[p]
            );
        }
    }
}

#[test]
fn signed_distance_of_a_torus_matches_the_analytic_distance() {
    // The shipped torus has radii 1 and 0.25 around the y axis (bounding box ±1.25, ±0.25).
    let mesh = read_mesh(&data("torus.obj")).unwrap();
    let v = voxelize(
        &mesh,
        &VoxelSettings {
            resolution: 64,
            ..Default::default()
        },
    )
    .unwrap();
    let sd = signed_distance(&v);
    let [nx, ny, nz] = sd.shape;
    let mut worst = 0.0_f64;
    for i in 0..nx {
        for j in 0..ny {
            for k in 0..nz {
                let p = sd.centre(i, j, k);
                let ring = (p[0] * p[0] + p[2] * p[2]).sqrt() - 1.0;
                let exact = 0.25 - (ring * ring + p[1] * p[1]).sqrt();
                // Within four voxels of the surface, where the conversion
                // of Yngve & Turk (2002) uses the field.
                if exact.abs() < 4.0 * sd.voxel_size {
                    worst = worst.max((sd.get(i, j, k) as f64 - exact).abs());
                }
            }
        }
    }
    // A voxel-level transform is exact between voxel centres; where the surface passes near a
    // voxel corner its sub-voxel placement from densities is off by up to about a voxel.
    assert!(
        worst < 1.0 * sd.voxel_size,
        "worst error {worst} with voxels of {}",
        sd.voxel_size
    );
}
