//! The solid's function F sampled on a lattice [`SUB`] times finer than the tracer's cells, in
//! the cells that can hold surface (the band around it). Rays look for the surface of F's
//! trilinear interpolant, which costs no evaluation of the models; every candidate is then
//! confirmed by exact Newton steps. Each fine cell carries an estimate of how far the
//! interpolant can be from F (from second differences of the samples), and a ray that comes
//! that close to zero without crossing is checked exactly too, at its closest sample (a thin
//! feature whose peak lies between the samples along the ray can still be missed).

use rayon::prelude::*;
use rbf_core::ScalarField;
use rbf_core::vec3::Vec3;

use crate::camera::Ray;
use crate::csg::Csg;

/// Fine cells along each side of a tracer cell.
pub(crate) const SUB: usize = 4;
/// Lattice points along each side of a block.
const SIDE: usize = SUB + 1;

/// F's samples in the tracer cells that can hold surface.
pub(crate) struct Band {
    /// Per tracer cell: its block, or `u32::MAX` when the cell holds no surface.
    block_of: Vec<u32>,
    /// Per block: F at its SIDE³ lattice points (x slowest, z fastest, as the cells).
    values: Vec<f64>,
    /// Per block: for each of its SUB³ fine cells, a bound (estimated) on |F − interpolant|.
    error: Vec<f64>,
    /// Evaluations spent sampling.
    pub(crate) samples: usize,
}

/// What a ray meets in one fine cell.
pub(crate) enum Segment {
    /// The interpolant crosses zero (or is ≥ 0 where the ray enters) at this distance.
    Crossing(f64),
    /// It stays negative but comes within its error of zero here: worth an exact look.
    Close(f64),
    /// Nothing.
    Clear,
}

impl Band {
    /// Samples F in every cell (of the lattice of `n` cells of size `cell` from `lo`) for which
    /// `occupied` holds.
    pub(crate) fn new(
        views: &[&dyn ScalarField<3>],
        csg: &Csg,
        lo: Vec3,
        cell: Vec3,
        n: [usize; 3],
        occupied: impl Fn(usize) -> bool,
    ) -> Self {
        let total = n[0] * n[1] * n[2];
        let cells: Vec<usize> = (0..total).filter(|&i| occupied(i)).collect();
        let mut block_of = vec![u32::MAX; total];
        for (b, &i) in cells.iter().enumerate() {
            block_of[i] = b as u32;
        }
        let fine = [n[0] * SUB + 1, n[1] * SUB + 1, n[2] * SUB + 1];
        let key = |c: [usize; 3], s: [usize; 3]| -> u64 {
            let g: [usize; 3] = core::array::from_fn(|d| c[d] * SUB + s[d]);
            ((g[0] * fine[1] + g[1]) * fine[2] + g[2]) as u64
        };
        let coords = |i: usize| [i / (n[1] * n[2]), (i / n[2]) % n[1], i % n[2]];
        let local = |k: usize| [k / (SIDE * SIDE), (k / SIDE) % SIDE, k % SIDE];
        // Every lattice point once, in order.
        let mut keys: Vec<u64> = cells
            .iter()
            .flat_map(|&i| (0..SIDE.pow(3)).map(move |k| key(coords(i), local(k))))
            .collect();
        keys.par_sort_unstable();
        keys.dedup();
        let h: Vec3 = core::array::from_fn(|d| cell[d] / SUB as f64);
        let points: Vec<Vec3> = keys
            .iter()
            .map(|&k| {
                let k = k as usize;
                let g = [
                    k / (fine[1] * fine[2]),
                    (k / fine[2]) % fine[1],
                    k % fine[2],
                ];
                core::array::from_fn(|d| lo[d] + g[d] as f64 * h[d])
            })
            .collect();
        let used = csg.models();
        let mut per_model = vec![Vec::new(); views.len()];
        // The samples only steer (every hit is confirmed through the models themselves): a
        // model's coarse field samples it where it has one, and its error widens every fine
        // cell's (the solid's min and max move no more than the models they take).
        let mut sample_error = 0.0_f64;
        for &m in &used {
            per_model[m] = vec![0.0; points.len()];
            let (field, error) = crate::tracer::steering(views[m]);
            sample_error = sample_error.max(error);
            // Equal lengths by construction.
            let _ = field.field_values(&points, &mut per_model[m]);
        }
        let solid: Vec<f64> = (0..points.len())
            .into_par_iter()
            .map_init(
                || vec![0.0; views.len()],
                |here, p| {
                    for &m in &used {
                        here[m] = per_model[m][p];
                    }
                    csg.active(here).0
                },
            )
            .collect();
        let per_block: Vec<(Vec<f64>, Vec<f64>)> = cells
            .par_iter()
            .map(|&i| {
                let c = coords(i);
                let values: Vec<f64> = (0..SIDE.pow(3))
                    .map(|k| {
                        let at = keys.binary_search(&key(c, local(k))).unwrap_or_default();
                        solid[at]
                    })
                    .collect();
                let mut error = block_error(&values);
                error.iter_mut().for_each(|e| *e += sample_error);
                (values, error)
            })
            .collect();
        let (mut values, mut error) = (Vec::new(), Vec::new());
        for (v, e) in per_block {
            values.extend(v);
            error.extend(e);
        }
        Self {
            block_of,
            values,
            error,
            samples: points.len(),
        }
    }

    /// Looks along the ray from `a` to `b`, both within fine cell `fine` of tracer cell `cell`
    /// whose lowest corner is `corner` (fine cells of size `h`), for the interpolant's first
    /// zero.
    pub(crate) fn segment(
        &self,
        cell: usize,
        fine: [usize; 3],
        corner: Vec3,
        h: Vec3,
        ray: &Ray,
        (a, b): (f64, f64),
    ) -> Segment {
        let block = self.block_of[cell] as usize;
        let values = &self.values[block * SIDE.pow(3)..(block + 1) * SIDE.pow(3)];
        let v: [f64; 8] = core::array::from_fn(|k| {
            let s = [
                fine[0] + (k >> 2),
                fine[1] + ((k >> 1) & 1),
                fine[2] + (k & 1),
            ];
            values[(s[0] * SIDE + s[1]) * SIDE + s[2]]
        });
        let error = self.error[block * SUB.pow(3) + (fine[0] * SUB + fine[1]) * SUB + fine[2]];
        if v.iter().all(|&x| x < -error) {
            return Segment::Clear;
        }
        let at = |t: f64| -> f64 {
            let u: Vec3 = core::array::from_fn(|d| {
                ((ray.origin[d] + t * ray.direction[d] - corner[d]) / h[d]).clamp(0.0, 1.0)
            });
            trilinear(&v, u)
        };
        const STEPS: usize = 8;
        let (mut previous_t, mut previous) = (a, at(a));
        if previous >= 0.0 {
            return Segment::Crossing(a);
        }
        let (mut closest_t, mut closest) = (a, previous);
        for k in 1..=STEPS {
            let t = a + (b - a) * k as f64 / STEPS as f64;
            let value = at(t);
            if value >= 0.0 {
                // Regula falsi on the interpolant between the last two samples.
                let (mut lo, mut hi, mut f_lo, mut f_hi) = (previous_t, t, previous, value);
                for _ in 0..30 {
                    let mid = if f_hi > f_lo {
                        lo + (hi - lo) * (-f_lo / (f_hi - f_lo)).clamp(0.05, 0.95)
                    } else {
                        0.5 * (lo + hi)
                    };
                    let f = at(mid);
                    if f >= 0.0 {
                        (hi, f_hi) = (mid, f);
                    } else {
                        (lo, f_lo) = (mid, f);
                    }
                    if hi - lo < 1e-4 * (b - a) {
                        break;
                    }
                }
                return Segment::Crossing(hi);
            }
            if value > closest {
                (closest_t, closest) = (t, value);
            }
            (previous_t, previous) = (t, value);
        }
        if closest >= -error {
            Segment::Close(closest_t)
        } else {
            Segment::Clear
        }
    }
}

/// Trilinear interpolation of the corner values `v` (index bits: x 4, y 2, z 1) at `u` in
/// [0, 1]³.
fn trilinear(v: &[f64; 8], u: Vec3) -> f64 {
    let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
    let x: [f64; 4] = core::array::from_fn(|k| lerp(v[k], v[k + 4], u[0]));
    let y = [lerp(x[0], x[2], u[1]), lerp(x[1], x[3], u[1])];
    lerp(y[0], y[1], u[2])
}

/// Per fine cell of a block: twice the trilinear interpolation error bound
/// (1/8) Σ_d h_d² max|∂²F/∂x_d²|, the second derivatives estimated by second differences at the
/// cell's corners (one-sided at the block's faces).
fn block_error(values: &[f64]) -> Vec<f64> {
    let at = |s: [usize; 3]| values[(s[0] * SIDE + s[1]) * SIDE + s[2]];
    let scale = values.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let mut second = vec![[0.0; 3]; SIDE.pow(3)];
    for (k, out) in second.iter_mut().enumerate() {
        let s = [k / (SIDE * SIDE), (k / SIDE) % SIDE, k % SIDE];
        for d in 0..3 {
            let centre = s[d].clamp(1, SIDE - 2);
            let mut q = s;
            q[d] = centre - 1;
            let below = at(q);
            q[d] = centre;
            let middle = at(q);
            q[d] = centre + 1;
            out[d] = (below - 2.0 * middle + at(q)).abs();
        }
    }
    (0..SUB.pow(3))
        .map(|k| {
            let s = [k / (SUB * SUB), (k / SUB) % SUB, k % SUB];
            let mut most = [0.0_f64; 3];
            for c in 0..8 {
                let q = [s[0] + (c >> 2), s[1] + ((c >> 1) & 1), s[2] + (c & 1)];
                let d2 = second[(q[0] * SIDE + q[1]) * SIDE + q[2]];
                for d in 0..3 {
                    most[d] = most[d].max(d2[d]);
                }
            }
            0.25 * (most[0] + most[1] + most[2]) + 1e-9 * scale
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trilinear_meets_its_corners_and_is_exact_for_linear_functions() {
        let f = |p: Vec3| 2.0 * p[0] - 3.0 * p[1] + 0.5 * p[2] + 1.0;
        let v: [f64; 8] =
            core::array::from_fn(|k| f([(k >> 2) as f64, ((k >> 1) & 1) as f64, (k & 1) as f64]));
        for u in [
            [0.0, 0.0, 0.0],
            [1.0, 1.0, 1.0],
            [0.3, 0.7, 0.2],
            [1.0, 0.0, 0.5],
        ] {
            assert!((trilinear(&v, u) - f(u)).abs() < 1e-12);
        }
    }

    #[test]
    fn the_error_estimate_bounds_a_quadratic_s_interpolation_error() {
        // F = x² + y² + z² − 1 on a block of spacing 1/4: the trilinear error is at most
        // 3 h²/4 (the bound is attained at cell centres) and the estimate must not be below.
        let h = 0.25;
        let values: Vec<f64> = (0..SIDE.pow(3))
            .map(|k| {
                let s = [k / (SIDE * SIDE), (k / SIDE) % SIDE, k % SIDE];
                s.iter().map(|&c| (c as f64 * h).powi(2)).sum::<f64>() - 1.0
            })
            .collect();
        let error = block_error(&values);
        let truth = 3.0 * h * h / 4.0;
        assert!(
            error.iter().all(|&e| e >= truth && e < 3.0 * truth),
            "{error:?}"
        );
    }
}
