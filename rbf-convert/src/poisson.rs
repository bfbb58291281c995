//! Evenly spread subsets of points: Poisson-disk sampling by greedy elimination on a grid.

use rustc_hash::FxHashMap;

/// Indices of at most `target` of `points`, no two closer than a radius chosen so that the
/// count comes within 0.2 % of `target` from below (or the radius is pinned to 0.05 %). Points
/// are visited in a fixed pseudo-random order, so the result is deterministic.
///
/// The radius is found by the secant method on log count against log radius (a surface's count
/// falls as the square of the radius, a curve's as the radius), kept inside a bracket: five to
/// eight passes over the points where forty steps of bisection took forty (0.8 s of a
/// 10⁵-point scan's reconstruction).
///
/// ```
/// let grid: Vec<[f64; 3]> = (0..1000).map(|i| [(i % 10) as f64, ((i / 10) % 10) as f64, (i / 100) as f64]).collect();
/// let kept = rbf_convert::poisson_subset(&grid, 125);
/// assert!(kept.len() <= 125 && kept.len() >= 100);
/// ```
pub fn poisson_subset(points: &[[f64; 3]], target: usize) -> Vec<usize> {
    if points.len() <= target {
        return (0..points.len()).collect();
    }
    if target == 0 {
        return Vec::new();
    }
    let order = shuffled(points.len());
    let diameter = diameter(points);
    // Bracket: more than `target` kept at `lo` (with that count), at most at `hi`.
    let (mut lo, mut lo_count) = (0.0_f64, points.len());
    let mut hi = diameter;
    let mut best: Vec<usize> = Vec::new();
    // A first guess as for points spread over a surface.
    let mut r = diameter / (target.max(1) as f64).sqrt();
    for _ in 0..MOST_PASSES {
        let kept = greedy(points, &order, r);
        if kept.len() > target {
            (lo, lo_count) = (r, kept.len());
        } else {
            hi = r;
            let done = kept.len() as f64 >= CLOSE_ENOUGH * target as f64;
            // The count is not monotone in the radius: the largest within the target is kept.
            if kept.len() >= best.len() {
                best = kept;
            }
            if done {
                break;
            }
        }
        if hi <= PINNED * lo {
            break;
        }
        r = next_radius(lo, lo_count, hi, best.len(), target);
    }
    if best.is_empty() {
        // Any subset of an evenly spread set is spread at least as far.
        best = greedy(points, &order, hi);
        best.truncate(target);
    }
    best.sort_unstable();
    best
}

/// Passes of the greedy elimination at most.
const MOST_PASSES: usize = 40;

/// A count this share of the target is close enough.
const CLOSE_ENOUGH: f64 = 0.998;

/// A bracket this narrow (the ratio of its ends) pins the radius.
const PINNED: f64 = 1.0005;

/// The next radius to try in the bracket (lo, hi): where log count meets log target on the line
/// through the bracket's ends, kept a tenth of the bracket from either end (so that it always
/// shrinks); halved or doubled while an end is not known yet (`hi_count` 0: not tried).
fn next_radius(lo: f64, lo_count: usize, hi: f64, hi_count: usize, target: usize) -> f64 {
    let margin = 0.1 * (hi - lo);
    if lo <= 0.0 {
        return 0.5 * hi;
    }
    if hi_count == 0 {
        // `hi` not tried yet (the diameter): double.
        return (2.0 * lo).min(0.5 * (lo + hi));
    }
    if lo_count <= hi_count {
        return 0.5 * (lo + hi);
    }
    let slope = (lo_count as f64 / hi_count as f64).ln() / (hi / lo).ln();
    let r = lo * (lo_count as f64 / target as f64).powf(1.0 / slope);
    if r.is_finite() {
        r.clamp(lo + margin, hi - margin)
    } else {
        0.5 * (lo + hi)
    }
}

fn diameter(points: &[[f64; 3]]) -> f64 {
    let (lo, hi) = bounds(points);
    ((0..3).map(|d| (hi[d] - lo[d]).powi(2)).sum::<f64>())
        .sqrt()
        .max(f64::MIN_POSITIVE)
}

/// The corners of the points' bounding box (infinite for no points).
pub(crate) fn bounds(points: &[[f64; 3]]) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for d in 0..3 {
            lo[d] = lo[d].min(p[d]);
            hi[d] = hi[d].max(p[d]);
        }
    }
    (lo, hi)
}

/// `spread` (indices into `points`) and those of `more` with no point of `spread`, nor one
/// added before them, within `r`: a finer spread laid over a coarser one where it is wanted.
/// `more` is visited in the same fixed pseudo-random order as [`poisson_subset`]'s points.
pub(crate) fn spread_adding(
    points: &[[f64; 3]],
    spread: &[usize],
    more: &[usize],
    r: f64,
) -> Vec<usize> {
    let mut order = spread.to_vec();
    order.extend(shuffled(more.len()).into_iter().map(|j| more[j]));
    let mut kept = greedy_after(points, &order, r, spread.len());
    kept.sort_unstable();
    kept
}

/// Keeps each point (in `order`) with no kept point within `r`.
fn greedy(points: &[[f64; 3]], order: &[usize], r: f64) -> Vec<usize> {
    greedy_after(points, order, r, 0)
}

/// Keeps the first `given` points of `order` whatever their distances, then each point with no
/// kept point within `r`.
fn greedy_after(points: &[[f64; 3]], order: &[usize], r: f64, given: usize) -> Vec<usize> {
    let cell = |p: &[f64; 3]| -> [i64; 3] { core::array::from_fn(|d| (p[d] / r).floor() as i64) };
    let mut grid: FxHashMap<[i64; 3], Vec<usize>> = FxHashMap::default();
    let mut kept = Vec::new();
    let taken = |grid: &FxHashMap<[i64; 3], Vec<usize>>, p: &[f64; 3], c: [i64; 3]| {
        (-1..=1).any(|dx| {
            (-1..=1).any(|dy| {
                (-1..=1).any(|dz| {
                    grid.get(&[c[0] + dx, c[1] + dy, c[2] + dz])
                        .is_some_and(|list| {
                            list.iter().any(|&j| {
                                let q = points[j];
                                let d2: f64 = (0..3).map(|d| (p[d] - q[d]).powi(2)).sum();
                                d2 < r * r
                            })
                        })
                })
            })
        })
    };
    for (n, &i) in order.iter().enumerate() {
        let p = points[i];
        let c = cell(&p);
        if n >= given && taken(&grid, &p, c) {
            continue;
        }
        grid.entry(c).or_default().push(i);
        kept.push(i);
    }
    kept
}

/// 0..n in a fixed pseudo-random order (multiplicative hashing of the index): deterministic, and
/// any prefix of it a random subset.
pub(crate) fn shuffled(n: usize) -> Vec<usize> {
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by_key(|&i| {
        (i as u64)
            .wrapping_mul(0x9E37_79B9_7F4A_7C15)
            .rotate_left(17)
    });
    order
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The largest count at most `target` that forty steps of bisection of the radius find.
    fn bisected(points: &[[f64; 3]], target: usize) -> usize {
        let order = shuffled(points.len());
        let (mut lo, mut hi, mut best) = (0.0, diameter(points), 0);
        for _ in 0..40 {
            let r = 0.5 * (lo + hi);
            let kept = greedy(points, &order, r).len();
            if kept > target {
                lo = r;
            } else {
                (hi, best) = (r, kept);
            }
        }
        best
    }

    /// Points on a sphere and along a line: the subset is within the target, and as close to it
    /// as bisection of the radius gets (within 1 %), in fewer passes.
    #[test]
    fn the_subset_comes_as_close_to_the_target_as_bisection() {
        let sphere: Vec<[f64; 3]> = (0..20_000)
            .map(|i| {
                let z = 1.0 - (2 * i + 1) as f64 / 20_000.0;
                let t = 2.399963 * i as f64;
                let s = (1.0 - z * z).sqrt();
                [s * t.cos(), s * t.sin(), z]
            })
            .collect();
        // A curve, at uneven spacing.
        let line: Vec<[f64; 3]> = shuffled(5000)
            .into_iter()
            .enumerate()
            .map(|(i, j)| [i as f64 + 0.9 * (j as f64 / 5000.0), 0.0, 0.0])
            .collect();
        for (points, target) in [(&sphere, 3000), (&sphere, 50), (&line, 400), (&line, 37)] {
            let kept = poisson_subset(points, target);
            let reference = bisected(points, target);
            assert!(kept.len() <= target, "{} > {target}", kept.len());
            assert!(
                kept.len() as f64 >= 0.99 * reference as f64,
                "{} against {reference}",
                kept.len()
            );
            assert!(kept.windows(2).all(|w| w[0] < w[1]));
        }
    }
}
