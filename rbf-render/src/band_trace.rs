//! Tracing through the sampled band ([`crate::band::Band`]): each ray walks the tracer's cells,
//! skips those that hold no surface and, in the others, the fine cells where the interpolant of
//! F's samples stays clear of zero; where it crosses zero or comes within its error of it, the
//! ray stops for exact Newton steps on the models (safeguarded by bisection once a point inside
//! is known). Every round evaluates the models once at all stopped rays of the batch, through
//! the vectorized evaluator. A candidate that does not lead to a root near it is dropped and the
//! ray walks on.

use rbf_core::vec3::{Vec3, along, dot, normalize, scale};

use crate::band::{Band, SUB, Segment};
use crate::camera::Ray;
use crate::tracer::{TraceCounts, Tracer};

/// A ray stopped for exact root finding.
struct Polish {
    ray: usize,
    /// Where it is evaluated next.
    t: f64,
    /// The farthest point known outside the solid, and the nearest known inside.
    outside: f64,
    inside: f64,
    /// Where a root may be accepted.
    window: (f64, f64),
    /// Where the walk resumes if no root is found.
    resume: f64,
    rounds: u32,
}

/// Newton rounds before a candidate is given up.
const MAX_ROUNDS: u32 = 24;

/// A Newton step shorter than this fraction of a fine cell's diagonal ends the search: the
/// point it reaches is within about its square (10⁻⁶ of the cell) of the root.
const NEWTON_DONE: f64 = 1e-3;

impl Tracer<'_, '_> {
    /// The first hit of each ray before its limit, through the band, with the outward normal
    /// there when the last Newton step's gradient gives it (from within 10⁻³ of a fine cell).
    pub(crate) fn trace_band(
        &self,
        band: &Band,
        rays: &[Ray],
        limits: &[f64],
        counts: &mut TraceCounts,
    ) -> (Vec<Option<f64>>, Vec<Option<Vec3>>) {
        counts.rays += rays.len() as u64;
        let mut hits = vec![None; rays.len()];
        let mut normals = vec![None; rays.len()];
        let mut start = vec![0.0; rays.len()];
        let mut end = vec![0.0; rays.len()];
        let mut walking: Vec<(usize, f64)> = Vec::new();
        for (i, ray) in rays.iter().enumerate() {
            if let Some((a, b)) = crate::tracer::clip(ray, self.lo, self.hi) {
                start[i] = a.max(0.0);
                end[i] = b.min(limits[i]);
                if start[i] <= end[i] {
                    walking.push((i, start[i]));
                }
            }
        }
        let fine: Vec3 = core::array::from_fn(|d| self.cell[d] / SUB as f64);
        // A root is looked for up to a fine cell's diagonal around the candidate's cell.
        let reach = dot(fine, fine).sqrt();
        let tolerance = 1e-9 * self.size();
        let models = self.views.len();
        let mut polishing: Vec<Polish> = Vec::new();
        let mut points: Vec<Vec3> = Vec::new();
        let mut values = vec![Vec::new(); models];
        let mut gradients = vec![Vec::new(); models];
        let mut here = vec![0.0; models];
        loop {
            for (i, t) in walking.drain(..) {
                if let Some((candidate, a, b)) = self.walk(band, &rays[i], t, end[i], fine) {
                    polishing.push(Polish {
                        ray: i,
                        t: candidate,
                        outside: f64::NEG_INFINITY,
                        inside: f64::INFINITY,
                        window: (start[i].max(a - reach), b + reach),
                        resume: b,
                        rounds: 0,
                    });
                }
            }
            if polishing.is_empty() {
                break;
            }
            points.clear();
            points.extend(
                polishing
                    .iter()
                    .map(|p| along(rays[p.ray].origin, rays[p.ray].direction, p.t)),
            );
            counts.evaluations += points.len() as u64;
            for &m in &self.used {
                values[m].resize(points.len(), 0.0);
                gradients[m].resize(points.len(), [0.0; 3]);
                // Equal lengths by construction.
                let _ = self.views[m].field_values_and_gradients(
                    &points,
                    &mut values[m],
                    &mut gradients[m],
                );
            }
            let mut k = 0;
            polishing.retain_mut(|p| {
                let j = k;
                k += 1;
                for &m in &self.used {
                    here[m] = values[m][j];
                }
                let (f, model, sign) = self.csg.active(&here);
                let direction = rays[p.ray].direction;
                if f >= 0.0 {
                    if p.t <= start[p.ray] {
                        // The ray starts inside the solid.
                        hits[p.ray] = Some(start[p.ray]);
                        return false;
                    }
                    p.inside = p.inside.min(p.t);
                } else {
                    p.outside = p.outside.max(p.t);
                }
                let rate = sign * dot(gradients[model][j], direction);
                let mut next = p.t - f / rate;
                let bracketed = p.outside < p.inside && p.inside.is_finite();
                let in_window = next >= p.window.0 && next <= p.window.1;
                let in_bracket = !bracketed || (next > p.outside && next < p.inside);
                // Whether the Newton step is taken (else the bracket or window is halved).
                let newton = next.is_finite() && in_window && in_bracket;
                if !newton {
                    next = if bracketed && p.outside.is_finite() {
                        0.5 * (p.outside + p.inside)
                    } else if p.inside.is_finite() {
                        // Inside, with nothing outside known yet: the walk came from outside.
                        0.5 * (p.window.0 + p.inside)
                    } else {
                        f64::NAN
                    };
                }
                p.rounds += 1;
                // A Newton step this short leaves an error of the order of its square over
                // the reach: accepted without another evaluation.
                let converged = (next - p.t).abs() <= tolerance
                    || (bracketed && p.inside - p.outside <= tolerance)
                    || (newton && (next - p.t).abs() <= NEWTON_DONE * reach);
                if converged && next.is_finite() {
                    hits[p.ray] = Some(next);
                    normals[p.ray] = Some(normalize(scale(gradients[model][j], -sign)));
                    return false;
                }
                if !next.is_finite() || p.rounds >= MAX_ROUNDS {
                    // No root near this candidate: walk on past its cell.
                    walking.push((p.ray, p.resume + 1e-6 * reach));
                    return false;
                }
                p.t = next;
                true
            });
        }
        (hits, normals)
    }

    /// Walks the ray from t to `end` until the band calls for an exact look: the candidate and
    /// the fine cell's part of the ray.
    fn walk(
        &self,
        band: &Band,
        ray: &Ray,
        mut t: f64,
        end: f64,
        fine: Vec3,
    ) -> Option<(f64, f64, f64)> {
        let nudge = 1e-6 * self.size();
        loop {
            if t > end {
                return None;
            }
            let p = along(ray.origin, ray.direction, t);
            let c = self.cell_of(p);
            if self.lipschitz[c] == 0.0 {
                t = self.cell_exit(ray, t, c) + nudge;
                continue;
            }
            let index = self.cell_coords(c);
            let s: [usize; 3] = core::array::from_fn(|d| {
                let corner = self.lo[d] + index[d] as f64 * self.cell[d];
                (((p[d] - corner) / fine[d]).floor().max(0.0) as usize).min(SUB - 1)
            });
            let corner: Vec3 = core::array::from_fn(|d| {
                self.lo[d] + index[d] as f64 * self.cell[d] + s[d] as f64 * fine[d]
            });
            let exit = box_exit(ray, t, corner, fine);
            let b = exit.min(end);
            match band.segment(c, s, corner, fine, ray, (t, b)) {
                Segment::Crossing(x) | Segment::Close(x) => return Some((x, t, b)),
                Segment::Clear => t = exit + nudge,
            }
        }
    }
}

/// Where the ray, at t inside the box from `corner` of size `size`, leaves it.
fn box_exit(ray: &Ray, t: f64, corner: Vec3, size: Vec3) -> f64 {
    let mut exit = f64::INFINITY;
    for d in 0..3 {
        let dir = ray.direction[d];
        if dir != 0.0 {
            let face = corner[d] + if dir > 0.0 { size[d] } else { 0.0 };
            exit = exit.min((face - ray.origin[d]) / dir);
        }
    }
    exit.max(t)
}
