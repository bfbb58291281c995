//! Greedy fitting: a few of the constraints as centres, enough that the surface meets all of
//! them within a tolerance (the centre reduction of Carr et al., SIGGRAPH 2001, beyond the
//! two papers).
//!
//! A dense fit of K rows costs K³/3 flops and 8K² bytes, so a scan of 10⁵ oriented points
//! cannot be fitted whole on this machine. Most of those constraints say again what their
//! neighbours already say: the greedy fit starts from an evenly spread subset, measures how far
//! the surface misses every constraint, adds the worst ones and fits again, until every
//! constraint is met within the tolerance or the budget of centres is spent (or, with λ > 0,
//! only the centres taken still miss: their smoothing misses on purpose).

use std::time::Instant;

use rayon::prelude::*;
use rbf_core::{Constraint, ConstraintKind, Fit, FitError, FitSettings, Interpolant, System};

use crate::fit;

/// Settings of [`fit_greedy`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GreedySettings {
    /// Constraints of the first fit, spread by farthest-point sampling: 100.
    pub initial: usize,
    /// Stop when the surface misses no constraint by more than this fraction of the bounding
    /// box's longest side: 1e-4. A constraint's miss is |f(x) − h| / |∇f(x)|, the distance to
    /// the level set it asks for (to first order), largest over its rows. With λ > 0 the
    /// surface misses on purpose (by about λ times the weights), so the tolerance must allow it.
    pub tolerance: f64,
    /// The most constraints the fit may use: 5000.
    pub max_constraints: usize,
    /// Each round adds the worst-met constraints, up to this fraction of the current count:
    /// 0.5.
    pub growth: f64,
    /// Leave out the normal constraints that the surface contradicts: it passes within the
    /// tolerance of the point but f at the offset point has the other sign (the normal points
    /// the wrong way, as a few of a scan's estimated normals do). They become no centres and
    /// do not hold off convergence; the worst-met constraints would otherwise be exactly
    /// these, and fitting them folds the surface. `false` by default: every constraint counts.
    pub skip_contradicted: bool,
}

impl Default for GreedySettings {
    fn default() -> Self {
        Self {
            initial: 100,
            tolerance: 1e-4,
            max_constraints: 5000,
            growth: 0.5,
            skip_contradicted: false,
        }
    }
}

/// Size, worst miss and timings of one round of [`fit_greedy`] (one fit, then adding the
/// worst-met constraints).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GreedyRound {
    /// Constraints in this round's fit.
    pub constraints: usize,
    /// The largest miss over all constraints, as a fraction of the box's longest side.
    pub max_error: f64,
    /// Seconds solving this round's fit.
    pub fit_seconds: f64,
    /// Seconds measuring the misses.
    pub evaluate_seconds: f64,
}

/// What [`fit_greedy`] did.
#[derive(Clone, Debug, PartialEq)]
pub struct GreedyReport<const D: usize> {
    /// Every round, in order.
    pub rounds: Vec<GreedyRound>,
    /// Indices (into the input) of the constraints the returned fit uses: the first spread in
    /// the order given, then each round's in the order taken (worst first).
    pub used: Vec<usize>,
    /// Those constraints as fitted: a normal constraint carries the offset that the whole set
    /// gave it (explicitly, so that a model of these constraints alone reproduces the fit).
    pub constraints: Vec<Constraint<D>>,
    /// Whether every constraint is met within the tolerance (but the contradicted ones, when
    /// [`GreedySettings::skip_contradicted`] leaves them out).
    pub converged: bool,
    /// Constraints the returned fit contradicts and that were left out (see
    /// [`GreedySettings::skip_contradicted`]).
    pub contradicted: usize,
}

/// Fits a subset of `constraints` chosen greedily so that the surface meets every one of them
/// within `greedy.tolerance` (see [`GreedySettings`]). Every constraint is checked first, as by
/// [`fit`]; normal constraints keep the offset the whole set gives them. The fit uses
/// [`GreedyReport::constraints`] (the input's [`GreedyReport::used`]); with a tolerance of 0
/// and room for all, it is the full fit. It stops, not converged, when the budget is spent or
/// when only the constraints it took miss (with λ > 0, which misses on purpose).
///
/// ```
/// use rbf_core::{Constraint, FitSettings};
/// use rbf_solve::{GreedySettings, fit_greedy};
/// // 2000 oriented points on a unit sphere.
/// let cs: Vec<Constraint<3>> = (0..2000)
///     .map(|i| {
///         let z = 1.0 - (2.0 * i as f64 + 1.0) / 2000.0;
///         let (r, a) = ((1.0 - z * z).sqrt(), i as f64 * 2.399963);
///         let p = [r * a.cos(), r * a.sin(), z];
///         Constraint::normal(p, p)
///     })
///     .collect();
/// let (fit, report) = fit_greedy(&cs, &FitSettings::default(), &GreedySettings::default(), |_| {}).unwrap();
/// assert!(report.converged && report.used.len() < 1000);
/// assert!(fit.interpolant.value(&[0.0, 0.0, 1.0]).abs() < 1e-3);
/// ```
pub fn fit_greedy<const D: usize>(
    constraints: &[Constraint<D>],
    settings: &FitSettings,
    greedy: &GreedySettings,
    mut progress: impl FnMut(&GreedyRound),
) -> Result<(Fit<D>, GreedyReport<D>), FitError> {
    let system = System::new(constraints, settings)?;
    let constraints = with_offsets(constraints, &system);
    // The longest side of the rows' bounding box (the system's scale is half of it).
    let longest = 2.0 * system.scale();
    let tolerance = greedy.tolerance.max(0.0) * longest;
    let budget = greedy.max_constraints.clamp(1, constraints.len());
    let mut used = spread(&constraints, greedy.initial.clamp(1, budget));
    let mut rounds = Vec::new();
    // Each round's fit starts from the last one's solution, and keeps its preconditioner for
    // the next: a round's constraints come after the ones before, so that a round that adds
    // few (the last ones add 1–70 to thousands) factors subdomains for those only.
    let mut last: Option<Interpolant<f64, D>> = None;
    let mut kept = crate::KeptPreconditioner::default();
    loop {
        let t = Instant::now();
        let subset: Vec<Constraint<D>> = used.iter().map(|&i| constraints[i]).collect();
        let fit = match &last {
            Some(previous) => crate::fit_from_keeping(&subset, settings, previous, &mut kept)?,
            None => fit(&subset, settings)?,
        };
        let fit_seconds = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let (mut misses, contradicted) =
            misses(&fit.interpolant, &system, constraints.len(), tolerance);
        let mut skipped = 0;
        if greedy.skip_contradicted {
            for (m, &c) in misses.iter_mut().zip(&contradicted) {
                if c {
                    *m = 0.0;
                    skipped += 1;
                }
            }
        }
        let max = misses.iter().copied().fold(0.0, f64::max);
        let round = GreedyRound {
            constraints: used.len(),
            max_error: max / longest,
            fit_seconds,
            evaluate_seconds: t.elapsed().as_secs_f64(),
        };
        progress(&round);
        rounds.push(round);
        let converged = max <= tolerance;
        let room = budget.saturating_sub(used.len());
        // With λ > 0 the taken constraints miss too; when only they do, nothing is left to add.
        let worst = if converged || room == 0 {
            Vec::new()
        } else {
            let add = ((used.len() as f64 * greedy.growth).ceil() as usize).clamp(1, room);
            worst_untaken(&constraints, &used, &misses, tolerance, add)
        };
        if worst.is_empty() {
            return Ok((
                fit,
                GreedyReport {
                    rounds,
                    used,
                    constraints: subset,
                    converged,
                    contradicted: skipped,
                },
            ));
        }
        last = Some(fit.interpolant);
        used.extend(worst);
    }
}

/// Up to `add` of the constraints not in `used` that miss by more than `tolerance`, worst
/// first. The worst-met crowd together where the surface is worst; taking them all would spend
/// the round on a few places, so picks stay half the centres' spacing apart.
fn worst_untaken<const D: usize>(
    constraints: &[Constraint<D>],
    used: &[usize],
    misses: &[f64],
    tolerance: f64,
    add: usize,
) -> Vec<usize> {
    let mut taken = vec![false; constraints.len()];
    for &i in used {
        taken[i] = true;
    }
    let mut worst: Vec<usize> = (0..constraints.len())
        .filter(|&i| !taken[i] && misses[i] > tolerance)
        .collect();
    worst.sort_unstable_by(|&a, &b| misses[b].total_cmp(&misses[a]));
    let positions: Vec<[f64; D]> = used.iter().map(|&i| constraints[i].position).collect();
    let mut picks = Spread::new(0.5 * mean_spacing(&positions));
    worst.retain(|&i| picks.len() < add && picks.insert(constraints[i].position));
    worst
}

/// The constraints with every normal constraint's offset made explicit, as the whole set
/// gives it, so that a subset keeps the same offset points.
fn with_offsets<const D: usize>(
    constraints: &[Constraint<D>],
    system: &System<D>,
) -> Vec<Constraint<D>> {
    let points = system.points();
    let mut out = constraints.to_vec();
    for (row, source) in system.sources().iter().enumerate() {
        if source.offset_point {
            let c = &mut out[source.constraint];
            let d = (0..D)
                .map(|k| (points[row][k] - c.position[k]).powi(2))
                .sum::<f64>()
                .sqrt();
            c.offset = Some(d);
        }
    }
    out
}

/// `count` constraints spread by farthest-point sampling from the first, plus the first
/// constraint that gives f a non-zero value if none of those does (a fit needs one).
fn spread<const D: usize>(constraints: &[Constraint<D>], count: usize) -> Vec<usize> {
    let distance2 = |a: &[f64; D], b: &[f64; D]| (0..D).map(|d| (a[d] - b[d]).powi(2)).sum::<f64>();
    let mut nearest = vec![f64::INFINITY; constraints.len()];
    let mut chosen = Vec::with_capacity(count + 1);
    let mut next = 0;
    while chosen.len() < count {
        chosen.push(next);
        let at = constraints[next].position;
        let (far, _) = nearest
            .par_iter_mut()
            .zip(constraints.par_iter())
            .enumerate()
            .map(|(i, (n, c))| {
                *n = n.min(distance2(&c.position, &at));
                (i, *n)
            })
            .reduce(|| (0, -1.0), |a, b| if b.1 > a.1 { b } else { a });
        if nearest[far] <= 0.0 {
            break;
        }
        next = far;
    }
    let gives_value = |c: &Constraint<D>| c.kind == ConstraintKind::Normal || c.value != 0.0;
    if !chosen.iter().any(|&i| gives_value(&constraints[i]))
        && let Some(i) = constraints.iter().position(gives_value)
    {
        chosen.push(i);
    }
    chosen.sort_unstable();
    chosen
}

/// The mean distance from each point to its nearest neighbour among them, through one k-d tree
/// (it searched every pair: n² distances a round).
fn mean_spacing<const D: usize>(points: &[[f64; D]]) -> f64 {
    if points.len() < 2 {
        return 0.0;
    }
    let tree = rbf_cloud::PointTree::new(points);
    let total: f64 = (points.par_iter().enumerate())
        .map(|(i, p)| {
            // The point itself is among the two nearest (a duplicate may come first).
            (tree.k_nearest(p, 2).into_iter())
                .find(|n| n.0 != i)
                .map_or(0.0, |n| n.1)
        })
        .sum();
    total / points.len() as f64
}

/// Points kept at least `apart` from each other, in a hash grid of that cell size.
struct Spread<const D: usize> {
    apart: f64,
    cells: std::collections::HashMap<[i64; D], Vec<[f64; D]>>,
    count: usize,
}

impl<const D: usize> Spread<D> {
    fn new(apart: f64) -> Self {
        Self {
            apart,
            cells: std::collections::HashMap::new(),
            count: 0,
        }
    }

    fn len(&self) -> usize {
        self.count
    }

    /// Adds `p` unless a point already kept lies nearer than `apart`; says whether it did.
    fn insert(&mut self, p: [f64; D]) -> bool {
        if self.apart > 0.0 && self.apart.is_finite() {
            let cell: [i64; D] = core::array::from_fn(|d| (p[d] / self.apart).floor() as i64);
            let near = (0..3usize.pow(D as u32)).any(|n| {
                let key: [i64; D] =
                    core::array::from_fn(|d| cell[d] + (n / 3usize.pow(d as u32) % 3) as i64 - 1);
                self.cells.get(&key).is_some_and(|ps| {
                    ps.iter().any(|q| {
                        (0..D).map(|d| (p[d] - q[d]).powi(2)).sum::<f64>() < self.apart * self.apart
                    })
                })
            });
            if near {
                return false;
            }
            self.cells.entry(cell).or_default().push(p);
        }
        self.count += 1;
        true
    }
}

/// Each constraint's miss: the largest |f − h| / |∇f| over its rows.
/// Each constraint's miss (the largest over its rows), and whether the surface contradicts it:
/// a normal constraint whose surface passes within `tolerance` of its point (or within its
/// offset) while its offset point has f of the other sign than asked.
fn misses<const D: usize>(
    f: &Interpolant<f64, D>,
    system: &System<D>,
    count: usize,
    tolerance: f64,
) -> (Vec<f64>, Vec<bool>) {
    let points = system.points();
    let mut values = vec![0.0; points.len()];
    let mut gradients = vec![[0.0; D]; points.len()];
    // Equal lengths by construction.
    let _ = f
        .view()
        .par_values_and_gradients(points, &mut values, &mut gradients);
    let per_row: Vec<f64> = values
        .par_iter()
        .zip(&gradients)
        .zip(system.values())
        .map(|((v, g), h)| {
            let slope = g.iter().map(|x| x * x).sum::<f64>().sqrt();
            let miss = (v - h).abs();
            if miss == 0.0 { 0.0 } else { miss / slope }
        })
        .collect();
    let mut out = vec![0.0_f64; count];
    let mut surface_miss = vec![0.0_f64; count];
    let mut surface_at = vec![None; count];
    let mut offset_at = vec![None; count];
    let mut wrong_side = vec![false; count];
    for (row, (source, h)) in system.sources().iter().zip(system.values()).enumerate() {
        let c = source.constraint;
        out[c] = out[c].max(per_row[row]);
        if source.offset_point {
            wrong_side[c] = values[row] * h < 0.0;
            offset_at[c] = Some(points[row]);
        } else {
            surface_miss[c] = surface_miss[c].max(per_row[row]);
            surface_at[c] = Some(points[row]);
        }
    }
    // Near enough: within the tolerance, or within the offset (the surface is there, if not
    // yet close).
    let contradicted = (0..count)
        .map(|c| {
            let reach = match (surface_at[c], offset_at[c]) {
                (Some(a), Some(b)) => (0..D).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt(),
                _ => 0.0,
            };
            wrong_side[c] && surface_miss[c] <= tolerance.max(reach)
        })
        .collect();
    (out, contradicted)
}
