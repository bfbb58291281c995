//! Shared workloads of the benchmarks, identical to those of `../shared/peers/peer_rbf.py`, so
//! that criterion figures and peer figures describe the same work.

use rbf_core::{Constraint, FitSettings, Model};

/// A small deterministic generator (SplitMix64), so that benchmarks need no extra crate.
pub struct Rng(u64);

impl Rng {
    /// A generator whose sequence is fixed by `seed`: the same seed gives the same numbers.
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }
    /// A uniform number in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
    /// A standard normal number (Box–Muller).
    pub fn normal(&mut self) -> f64 {
        let u = self.uniform().max(1e-300);
        let v = self.uniform();
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    }
}

/// The peers' workload: K/2 random points on the unit sphere (f = 0) and each one moved 0.01
/// inward (f = 1): K value constraints, as `make_constraints` in `peer_rbf.py`.
pub fn sphere_constraints(k: usize, seed: u64) -> Vec<Constraint<3>> {
    let mut rng = Rng::new(seed);
    let n = k / 2;
    let dirs: Vec<[f64; 3]> = (0..n)
        .map(|_| {
            let v = [rng.normal(), rng.normal(), rng.normal()];
            let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            [v[0] / l, v[1] / l, v[2] / l]
        })
        .collect();
    let on = dirs.iter().map(|&d| Constraint::boundary(d));
    let inside = dirs
        .iter()
        .map(|d| Constraint::interior(d.map(|x| x * 0.99), 1.0));
    on.chain(inside).collect()
}

/// The peers' evaluation grid: `n`³ points spanning [−1.1, 1.1]³.
pub fn grid(n: usize) -> Vec<[f64; 3]> {
    let step = 2.2 / (n.max(2) - 1) as f64;
    let mut out = Vec::with_capacity(n * n * n);
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                out.push([
                    -1.1 + i as f64 * step,
                    -1.1 + j as f64 * step,
                    -1.1 + k as f64 * step,
                ]);
            }
        }
    }
    out
}

/// The icosphere of `trimesh.creation.icosphere(subdivisions, radius=1)`: see
/// [`rbf_mesh::TriMesh::icosphere`].
pub fn icosphere(subdivisions: usize) -> rbf_mesh::TriMesh {
    rbf_mesh::TriMesh::icosphere(subdivisions)
}

/// The peers' distance-transform volume (`peer_edt.py`): m³ voxel centres over
/// [−1.25, 1.25]³, 1 inside a solid torus (R = 0.8, r = 0.3) united with a ball (radius 0.5)
/// at (0, 0, 0.55).
pub fn torus_and_ball(m: usize) -> rbf_mesh::Volume<f32> {
    let h = 2.5 / (m - 1) as f64;
    let mut v = rbf_mesh::Volume::filled([-1.25; 3], h, [m; 3], 0.0_f32);
    for i in 0..m {
        for j in 0..m {
            for k in 0..m {
                let [x, y, z] = v.centre(i, j, k);
                let q = (x * x + y * y).sqrt() - 0.8;
                let inside =
                    q * q + z * z <= 0.09 || x * x + y * y + (z - 0.55) * (z - 0.55) <= 0.25;
                let at = v.index(i, j, k);
                v.data[at] = if inside { 1.0 } else { 0.0 };
            }
        }
    }
    v
}

/// A torus of `n` oriented points (3000 rows for n = 1500), fitted.
pub fn torus_model(n: usize) -> Model<3> {
    fitted(rbf_core::shapes::torus(n, 0.35))
}

/// The peers' random sphere problem of `rows` rows ([`sphere_constraints`]), fitted: the
/// unfavourable case beside the Fibonacci torus.
pub fn random_sphere_model(rows: usize) -> Model<3> {
    fitted(sphere_constraints(rows, 7))
}

fn fitted(cs: Vec<Constraint<3>>) -> Model<3> {
    let settings = FitSettings::default();
    let fit = rbf_solve::fit(&cs, &settings).expect("the torus fits");
    Model {
        constraints: cs,
        settings,
        interpolant: fit.interpolant,
        report: None,
    }
}
