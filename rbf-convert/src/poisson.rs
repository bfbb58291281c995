//! Evenly spread subsets of points: Poisson-disk sampling by greedy elimination on a grid.

use rustc_hash::FxHashMap;

/// Indices of at most about `target` of `points`, no two closer than a radius chosen (by
/// bisection) so that the count is as close to `target` as it gets from below. Points are
/// visited in a fixed pseudo-random order, so the result is deterministic.
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
    let order = shuffled(points.len());
    let (mut lo, mut hi) = (0.0_f64, diameter(points));
    let mut best: Vec<usize> = Vec::new();
    for _ in 0..40 {
        let r = 0.5 * (lo + hi);
        let kept = greedy(points, &order, r);
        if kept.len() > target {
            lo = r;
        } else {
            hi = r;
            best = kept;
        }
    }
    if best.is_empty() {
        best = greedy(points, &order, hi);
    }
    best.sort_unstable();
    best
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

/// Keeps each point (in `order`) with no kept point within `r`.
fn greedy(points: &[[f64; 3]], order: &[usize], r: f64) -> Vec<usize> {
    let cell = |p: &[f64; 3]| -> [i64; 3] { core::array::from_fn(|d| (p[d] / r).floor() as i64) };
    let mut grid: FxHashMap<[i64; 3], Vec<usize>> = FxHashMap::default();
    let mut kept = Vec::new();
    for &i in order {
        let p = points[i];
        let c = cell(&p);
        let mut free = true;
        'search: for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    if let Some(list) = grid.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) {
                        for &j in list {
                            let q = points[j];
                            let d2: f64 = (0..3).map(|d| (p[d] - q[d]).powi(2)).sum();
                            if d2 < r * r {
                                free = false;
                                break 'search;
                            }
                        }
                    }
                }
            }
        }
        if free {
            grid.entry(c).or_default().push(i);
            kept.push(i);
        }
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
