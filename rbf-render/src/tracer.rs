//! Sphere tracing (Hart 1996) of one solid. Its box is cut into cells; each cell carries a
//! Lipschitz constant of the solid over the cell (guaranteed from the kernel's derivatives and
//! the weights, or the paper's sampled estimate) and whether the surface can be in it at all.
//! A ray skips cells that cannot hold surface and, elsewhere, steps |F| / L: never farther than
//! the surface can be, so no ray passes through it. Steps below a small length hand over to a
//! bracketing root finder that puts the hit on the surface.

use rayon::prelude::*;
use rbf_core::{Kernel, ScalarField};

use crate::band::Band;
use crate::camera::Ray;
use crate::csg::Csg;
use rbf_core::vec3::{Vec3, along, dot, norm};

use crate::slope::{Slope, Spread, estimate_cells, sampled_slope};

/// Which Lipschitz constant steps the rays.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lipschitz {
    /// Fast, the default: cells skipped as [`Lipschitz::Estimated`] does, then F sampled on a
    /// lattice four times finer in the cells that remain; rays find the zeros of its trilinear
    /// interpolant without evaluating the models, and each is confirmed (or dropped) by exact
    /// Newton steps. Where the interpolant comes within its estimated error (from second
    /// differences of the samples) of zero without crossing, the ray is checked exactly too. A
    /// feature thinner than the fine lattice and away from its samples can be missed.
    Auto,
    /// Proved from the kernel's derivatives and the weights: per cell for skipping empty space
    /// (see [`rbf_core::InterpolantView::ball_bound`]) and, for r³, per point from the exact
    /// gradient and Σ|wⱼ|·6r bounds on the Hessian. No ray can pass through the surface
    /// inside the traced box ([`rbf_core::InterpolantView::surface_box`]).
    Guaranteed,
    /// 1.5 times the largest |∇f| at each cell's corners and centre, per cell: tight and fast,
    /// though a feature thinner than a cell can be stepped over.
    Estimated,
    /// Turk & O'Brien (2002), §7.2: the largest |∇f| over this many samples of the box, for the
    /// whole box.
    Sampled(usize),
}

/// Cells grow the bound's ball by this fraction, so a ray may step slightly past a cell's face.
const BALL_SLACK: f64 = 0.02;
/// Steps per ray before giving up (counted as a miss).
const MAX_STEPS: usize = 4000;

/// A solid prepared for tracing.
pub(crate) struct Tracer<'s, 'm> {
    pub(crate) views: &'s [&'m dyn ScalarField<3>],
    pub(crate) csg: &'s Csg,
    pub(crate) used: Vec<usize>,
    pub(crate) lo: Vec3,
    pub(crate) hi: Vec3,
    n: [usize; 3],
    pub(crate) cell: Vec3,
    /// Per cell: the solid's Lipschitz constant, or 0 when the surface cannot be in the cell.
    pub(crate) lipschitz: Vec<f64>,
    /// F sampled finely in the cells that can hold surface ([`Lipschitz::Auto`]).
    band: Option<Band>,
    /// Per model and cell: the model's Lipschitz constant (models with `local` only).
    cell_lipschitz: Vec<Vec<f64>>,
    /// Per model: whether its steps use cell bounds (kernels without a per-point bound).
    local: Vec<bool>,
    /// Per model: the sampled slope (sampled mode), or the global bound Σ|wⱼ| + |b| of φ = r.
    sampled: Vec<f64>,
    /// Per r³ model: its curvature bound.
    spread: Vec<Option<Spread>>,
    mode: Lipschitz,
    /// Steps shorter than this end in root finding.
    pub(crate) epsilon: f64,
}

/// Counts of work done.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TraceCounts {
    /// Rays traced.
    pub rays: u64,
    /// Points where the models were evaluated.
    pub evaluations: u64,
}

impl<'s, 'm> Tracer<'s, 'm> {
    /// Prepares `csg` over the models `views`, with about `cells` cells along the box's longest
    /// side; with [`Lipschitz::Auto`] and `sample_band`, samples F finely in the cells that can
    /// hold surface and traces through those samples.
    pub(crate) fn new(
        views: &'s [&'m dyn ScalarField<3>],
        csg: &'s Csg,
        cells: usize,
        mode: Lipschitz,
        sample_band: bool,
    ) -> Self {
        let used = csg.models();
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for &m in &used {
            let (a, b) = views[m].direct().surface_box(0.05);
            for d in 0..3 {
                lo[d] = lo[d].min(a[d]);
                hi[d] = hi[d].max(b[d]);
            }
        }
        let longest = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
        let h = longest / cells.max(1) as f64;
        let n: [usize; 3] =
            core::array::from_fn(|d| ((hi[d] - lo[d]) / h).ceil().max(1.0) as usize);
        let cell: Vec3 = core::array::from_fn(|d| (hi[d] - lo[d]) / n[d] as f64);
        let radius = 0.5 * norm(cell) * (1.0 + BALL_SLACK);
        let centre_of = |i: usize| -> Vec3 {
            let c = [i / (n[1] * n[2]), (i / n[2]) % n[1], i % n[2]];
            core::array::from_fn(|d| lo[d] + (c[d] as f64 + 0.5) * cell[d])
        };
        let cells_total = n[0] * n[1] * n[2];
        // Estimated slopes per model and cell, and f at each cell's centre.
        let mut estimated: Vec<Vec<f64>> = vec![Vec::new(); views.len()];
        let mut centre_values: Vec<Vec<f64>> = vec![Vec::new(); views.len()];
        // By default the estimates only steer (cells skipped, then the band's samples, whose
        // hits are confirmed exactly): a model's coarse field takes them, its error widening
        // every cell's interval. Stepped by the estimates, rays take the model itself.
        let mut coarse_error = vec![0.0; views.len()];
        for &m in &used {
            let (field, error) = match mode {
                Lipschitz::Auto => steering(views[m]),
                _ => (views[m], 0.0),
            };
            let (e, v) = estimate_cells(field, lo, cell, n);
            estimated[m] = e;
            centre_values[m] = v;
            coarse_error[m] = error;
        }
        let interval_empty = |bounds: &[(f64, f64)]| {
            let (a, b) = csg.interval(bounds);
            a > 0.0 || b < 0.0
        };
        // Proved slopes per model and cell, and whether each cell is proved empty.
        let proved: Vec<(bool, Vec<f64>)> = if mode == Lipschitz::Guaranteed {
            (0..cells_total)
                .into_par_iter()
                .map(|i| {
                    let centre = centre_of(i);
                    let mut bounds = vec![(0.0, 0.0); views.len()];
                    let mut slopes = vec![0.0; views.len()];
                    for &m in &used {
                        let b = views[m].direct().ball_bound(&centre, radius);
                        bounds[m] = (b.value - b.change, b.value + b.change);
                        slopes[m] = b.lipschitz;
                    }
                    (interval_empty(&bounds), slopes)
                })
                .collect()
        } else {
            Vec::new()
        };
        let estimated_empty = |i: usize| {
            let mut bounds = vec![(0.0, 0.0); views.len()];
            for &m in &used {
                let c = estimated[m][i] * radius + coarse_error[m];
                bounds[m] = (centre_values[m][i] - c, centre_values[m][i] + c);
            }
            interval_empty(&bounds)
        };
        // Auto: cells skipped by the estimate, then the sampled band (or, without one, sphere
        // tracing by the estimate).
        let sampled_band = sample_band && mode == Lipschitz::Auto;
        let mode = match mode {
            Lipschitz::Auto => Lipschitz::Estimated,
            m => m,
        };
        let spread: Vec<Option<Spread>> = views
            .iter()
            .enumerate()
            .map(|(m, v)| {
                (mode == Lipschitz::Guaranteed
                    && used.contains(&m)
                    && v.direct().kernel() == Kernel::Cubic)
                    .then(|| Spread::new(&v.direct()))
            })
            .collect();
        // Models whose steps stop at their cell's far side (their bound holds in the cell only).
        let local: Vec<bool> = views
            .iter()
            .map(|v| match mode {
                Lipschitz::Estimated => true,
                Lipschitz::Guaranteed => v.direct().kernel() == Kernel::ThinPlate,
                _ => false,
            })
            .collect();
        let sampled: Vec<f64> = views
            .iter()
            .enumerate()
            .map(|(m, v)| match mode {
                _ if !used.contains(&m) => 0.0,
                Lipschitz::Sampled(count) => sampled_slope(&v.direct(), lo, hi, count),
                _ => {
                    let w: f64 = v.direct().weights().iter().map(|w| w.abs()).sum();
                    w + norm(v.direct().linear())
                }
            })
            .collect();
        let cell_lipschitz: Vec<Vec<f64>> = (0..views.len())
            .map(|m| match mode {
                Lipschitz::Estimated if used.contains(&m) => estimated[m].clone(),
                Lipschitz::Guaranteed if local[m] => proved.iter().map(|c| c.1[m]).collect(),
                _ => Vec::new(),
            })
            .collect();
        let lipschitz: Vec<f64> = (0..cells_total)
            .map(|i| {
                let (empty, slope) = match mode {
                    Lipschitz::Guaranteed => {
                        (proved[i].0, proved[i].1.iter().copied().fold(0.0, f64::max))
                    }
                    Lipschitz::Sampled(_) => {
                        let mut bounds = vec![(0.0, 0.0); views.len()];
                        for &m in &used {
                            let c = sampled[m] * radius;
                            bounds[m] = (centre_values[m][i] - c, centre_values[m][i] + c);
                        }
                        (interval_empty(&bounds), 1.0)
                    }
                    _ => (estimated_empty(i), 1.0),
                };
                if empty { 0.0 } else { slope.max(1e-300) }
            })
            .collect();
        let band =
            sampled_band.then(|| Band::new(views, csg, lo, cell, n, |i| lipschitz[i] != 0.0));
        Self {
            views,
            csg,
            used,
            lo,
            hi,
            n,
            cell,
            lipschitz,
            band,
            cell_lipschitz,
            local,
            sampled,
            spread,
            mode,
            // Proved steps converge on the surface like Newton's method; estimated ones only
            // linearly, so they stop ten times sooner.
            epsilon: if mode == Lipschitz::Guaranteed {
                1e-6
            } else {
                1e-5
            } * longest,
        }
    }

    /// The box the solid is traced in.
    pub(crate) fn bounds(&self) -> (Vec3, Vec3) {
        (self.lo, self.hi)
    }

    /// The box of the cells that can hold surface, if any.
    pub(crate) fn occupied_bounds(&self) -> Option<(Vec3, Vec3)> {
        let (mut lo, mut hi) = ([usize::MAX; 3], [0usize; 3]);
        for (i, &l) in self.lipschitz.iter().enumerate() {
            if l == 0.0 {
                continue;
            }
            let c = [
                i / (self.n[1] * self.n[2]),
                (i / self.n[2]) % self.n[1],
                i % self.n[2],
            ];
            for d in 0..3 {
                lo[d] = lo[d].min(c[d]);
                hi[d] = hi[d].max(c[d] + 1);
            }
        }
        (lo[0] != usize::MAX).then(|| {
            (
                core::array::from_fn(|d| self.lo[d] + lo[d] as f64 * self.cell[d]),
                core::array::from_fn(|d| self.lo[d] + hi[d] as f64 * self.cell[d]),
            )
        })
    }

    /// The longest side of the traced box.
    pub(crate) fn size(&self) -> f64 {
        (0..3).map(|d| self.hi[d] - self.lo[d]).fold(0.0, f64::max)
    }

    /// The cell's position along x, y, z.
    pub(crate) fn cell_coords(&self, index: usize) -> [usize; 3] {
        [
            index / (self.n[1] * self.n[2]),
            (index / self.n[2]) % self.n[1],
            index % self.n[2],
        ]
    }

    /// Evaluations spent sampling the band, if there is one.
    pub(crate) fn band_samples(&self) -> usize {
        self.band.as_ref().map_or(0, |b| b.samples)
    }

    pub(crate) fn cell_of(&self, p: Vec3) -> usize {
        let c: [usize; 3] = core::array::from_fn(|d| {
            (((p[d] - self.lo[d]) / self.cell[d]).floor().max(0.0) as usize).min(self.n[d] - 1)
        });
        (c[0] * self.n[1] + c[1]) * self.n[2] + c[2]
    }

    /// Where the ray leaves the cell it is in at t.
    pub(crate) fn cell_exit(&self, ray: &Ray, t: f64, index: usize) -> f64 {
        let c = [
            index / (self.n[1] * self.n[2]),
            (index / self.n[2]) % self.n[1],
            index % self.n[2],
        ];
        let mut exit = f64::INFINITY;
        for d in 0..3 {
            let dir = ray.direction[d];
            if dir != 0.0 {
                let face =
                    self.lo[d] + (c[d] as f64 + if dir > 0.0 { 1.0 } else { 0.0 }) * self.cell[d];
                exit = exit.min((face - ray.origin[d]) / dir);
            }
        }
        exit.max(t)
    }

    /// The solid's outward unit normals at the points, from the gradient of the model on
    /// whose surface each lies, evaluated together.
    pub(crate) fn normals(&self, points: &[Vec3]) -> Vec<Vec3> {
        let models = self.views.len();
        let mut values = vec![Vec::new(); models];
        let mut gradients = vec![Vec::new(); models];
        for &m in &self.used {
            values[m] = vec![0.0; points.len()];
            gradients[m] = vec![[0.0; 3]; points.len()];
            // Equal lengths by construction.
            let _ =
                self.views[m].field_values_and_gradients(points, &mut values[m], &mut gradients[m]);
        }
        let mut here = vec![0.0; models];
        (0..points.len())
            .map(|j| {
                for &m in &self.used {
                    here[m] = values[m][j];
                }
                let (_, m, sign) = self.csg.active(&here);
                rbf_core::vec3::normalize(rbf_core::vec3::scale(gradients[m][j], -sign))
            })
            .collect()
    }

    /// How far f_m can move from its value at a point within distance s, for the slope data
    /// of that point.
    fn change(&self, slope: &Slope, s: f64) -> f64 {
        match *slope {
            // |∇f(x)| ≤ |∇f(p)| + ‖∇²f‖ s with ‖∇²f‖ ≤ Σ|wⱼ| 6 (|p − cⱼ| + s) for r³, so
            // |f(x) − f(p)| ≤ G s + 3 (g + W s) s².
            Slope::Cubic {
                gradient,
                spread,
                total,
            } => gradient * s + 3.0 * (spread + total * s) * s * s,
            Slope::Constant(l) => l * s,
        }
    }

    /// The largest step from a point at which the solid's function cannot vanish, by bisection
    /// on the interval bounds of every model, at most `most`.
    fn safe_step(
        &self,
        values: &[f64],
        slopes: &[Slope],
        most: f64,
        bounds: &mut [(f64, f64)],
    ) -> f64 {
        let clear = |s: f64, bounds: &mut [(f64, f64)]| {
            for &m in &self.used {
                let c = self.change(&slopes[m], s);
                bounds[m] = (values[m] - c, values[m] + c);
            }
            let (a, b) = self.csg.interval(bounds);
            a > 0.0 || b < 0.0
        };
        if clear(most, bounds) {
            return most;
        }
        let (mut lo, mut hi) = (0.0, most);
        for _ in 0..40 {
            let mid = 0.5 * (lo + hi);
            if clear(mid, bounds) {
                lo = mid;
            } else {
                hi = mid;
            }
            if hi - lo < 1e-3 * lo {
                break;
            }
        }
        lo
    }

    /// The first hit of each ray before its `limit`, as the distance along it. Rays are traced
    /// together: each round evaluates the models (value and gradient) at every unfinished ray's
    /// point at once, then steps each ray as far as the bounds allow.
    pub(crate) fn trace(
        &self,
        rays: &[Ray],
        limits: &[f64],
        counts: &mut TraceCounts,
    ) -> Vec<Option<f64>> {
        self.trace_with_normals(rays, limits, counts).0
    }

    /// [`Tracer::trace`], with the outward normal at each hit where tracing found it on the
    /// way (the sampled band's last Newton step); the others are left to [`Tracer::normals`].
    pub(crate) fn trace_with_normals(
        &self,
        rays: &[Ray],
        limits: &[f64],
        counts: &mut TraceCounts,
    ) -> (Vec<Option<f64>>, Vec<Option<Vec3>>) {
        if let Some(band) = &self.band {
            return self.trace_band(band, rays, limits, counts);
        }
        (
            self.trace_stepping(rays, limits, counts),
            vec![None; rays.len()],
        )
    }

    /// Sphere tracing (no band): the first hit of each ray before its limit.
    fn trace_stepping(
        &self,
        rays: &[Ray],
        limits: &[f64],
        counts: &mut TraceCounts,
    ) -> Vec<Option<f64>> {
        let mut hits = vec![None; rays.len()];
        let mut t = vec![0.0; rays.len()];
        let mut end = vec![0.0; rays.len()];
        let mut steps = vec![0usize; rays.len()];
        let mut active: Vec<usize> = Vec::with_capacity(rays.len());
        for (i, ray) in rays.iter().enumerate() {
            if let Some((a, b)) = clip(ray, self.lo, self.hi) {
                t[i] = a.max(0.0);
                end[i] = b.min(limits[i]);
                if t[i] <= end[i] {
                    active.push(i);
                }
            }
        }
        counts.rays += rays.len() as u64;
        let models = self.views.len();
        let mut points: Vec<Vec3> = Vec::with_capacity(rays.len());
        let mut cells: Vec<usize> = Vec::with_capacity(rays.len());
        let mut values: Vec<Vec<f64>> = vec![Vec::new(); models];
        let mut gradients: Vec<Vec<Vec3>> = vec![Vec::new(); models];
        let mut spreads: Vec<Vec<f64>> = vec![Vec::new(); models];
        let mut here = vec![0.0; models];
        let mut slopes = vec![Slope::Constant(0.0); models];
        let mut bounds = vec![(0.0, 0.0); models];
        let nudge = BALL_SLACK * 0.25 * self.cell_min();
        while !active.is_empty() {
            // Move every ray through cells without surface to its next point to evaluate.
            points.clear();
            cells.clear();
            active.retain(|&i| {
                let ray = &rays[i];
                loop {
                    if t[i] > end[i] || steps[i] >= MAX_STEPS {
                        return false;
                    }
                    let p = along(ray.origin, ray.direction, t[i]);
                    let c = self.cell_of(p);
                    if self.lipschitz[c] == 0.0 {
                        t[i] = self.cell_exit(ray, t[i], c) + nudge;
                        steps[i] += 1;
                        continue;
                    }
                    points.push(p);
                    cells.push(c);
                    return true;
                }
            });
            if active.is_empty() {
                break;
            }
            counts.evaluations += points.len() as u64;
            for &m in &self.used {
                values[m].resize(points.len(), 0.0);
                if self.spread[m].is_none() {
                    // Steps need no gradient here: values alone are about twice as fast.
                    let _ = self.views[m].field_values(&points, &mut values[m]);
                    continue;
                }
                gradients[m].resize(points.len(), [0.0; 3]);
                let _ = self.views[m].field_values_and_gradients(
                    &points,
                    &mut values[m],
                    &mut gradients[m],
                );
                if let Some(spread) = &self.spread[m] {
                    spreads[m].resize(points.len(), 0.0);
                    let _ = spread.view().values(&points, &mut spreads[m]);
                }
            }
            let mut k = 0;
            active.retain(|&i| {
                let j = k;
                k += 1;
                for &m in &self.used {
                    here[m] = values[m][j];
                    slopes[m] = match (&self.spread[m], self.mode) {
                        (Some(spread), Lipschitz::Guaranteed) => Slope::Cubic {
                            gradient: norm(gradients[m][j]),
                            spread: spreads[m][j],
                            total: spread.total,
                        },
                        _ => Slope::Constant(self.model_lipschitz(m, cells[j])),
                    };
                }
                let (f, active_model, sign) = self.csg.active(&here);
                let ray = &rays[i];
                if f >= 0.0 {
                    // On or inside the solid (the ray started inside, or landed on it exactly).
                    hits[i] = Some(t[i]);
                    return false;
                }
                // Bounds that hold only in the cell stop the step at its far side.
                let cell_bound = self
                    .used
                    .iter()
                    .any(|&m| matches!(slopes[m], Slope::Constant(_)) && self.local[m]);
                let most = if cell_bound {
                    self.cell_exit(ray, t[i], cells[j]) + nudge - t[i]
                } else {
                    end[i] - t[i] + nudge
                };
                let step = self.safe_step(&here, &slopes, most.max(0.0), &mut bounds);
                if step < self.epsilon {
                    hits[i] = Some(self.polish(ray, t[i], active_model, sign, f));
                    return false;
                }
                t[i] += step;
                steps[i] += 1;
                true
            });
        }
        hits
    }

    /// Newton steps along the ray from a point within reach of the surface of `model` (which
    /// enters the solid with `sign`), each kept only while short and improving: the hit then
    /// lies on the surface to rounding.
    fn polish(&self, ray: &Ray, t: f64, model: usize, sign: f64, f: f64) -> f64 {
        let start = t;
        let (mut best, mut best_value) = (t, f.abs());
        let mut t = t;
        for _ in 0..4 {
            let (v, g) =
                self.views[model]
                    .direct()
                    .value_and_gradient(&along(ray.origin, ray.direction, t));
            let (v, rate) = (sign * v, sign * dot(g, ray.direction));
            if v.abs() <= best_value {
                (best, best_value) = (t, v.abs());
            } else {
                break; // Newton along a grazing ray: keep the best point seen
            }
            let step = if rate != 0.0 { -v / rate } else { 0.0 };
            let next = t + step;
            if step == 0.0 || !((next - start).abs() < 16.0 * self.epsilon) {
                break;
            }
            t = next;
        }
        best
    }

    /// The Lipschitz constant of model m for the sampled mode, or the proved one of a model
    /// whose kernel has no per-point bound: per cell, or global for φ = r.
    fn model_lipschitz(&self, m: usize, cell: usize) -> f64 {
        if self.local[m] {
            self.cell_lipschitz[m][cell]
        } else {
            self.sampled[m]
        }
    }

    /// Whether rays are stepped by proved bounds.
    pub(crate) fn guaranteed(&self) -> bool {
        self.mode == Lipschitz::Guaranteed && self.band.is_none()
    }

    fn cell_min(&self) -> f64 {
        self.cell.iter().copied().fold(f64::INFINITY, f64::min)
    }
}

/// What samples that only steer evaluate: the model's coarse field and its measured error
/// ([`ScalarField::coarse`]), or the model itself, exact.
pub(crate) fn steering(view: &dyn ScalarField<3>) -> (&dyn ScalarField<3>, f64) {
    view.coarse().unwrap_or((view, 0.0))
}

/// The part of the ray inside the box, as distances along it.
pub(crate) fn clip(ray: &Ray, lo: Vec3, hi: Vec3) -> Option<(f64, f64)> {
    let (mut a, mut b) = (f64::NEG_INFINITY, f64::INFINITY);
    for d in 0..3 {
        let dir = ray.direction[d];
        if dir == 0.0 {
            if ray.origin[d] < lo[d] || ray.origin[d] > hi[d] {
                return None;
            }
            continue;
        }
        let (t0, t1) = ((lo[d] - ray.origin[d]) / dir, (hi[d] - ray.origin[d]) / dir);
        a = a.max(t0.min(t1));
        b = b.min(t0.max(t1));
    }
    (a <= b && b >= 0.0).then_some((a, b))
}
