//! Points given more than once: merged scans and quantized coordinates repeat positions, and a
//! repeated point is its own nearest neighbour at distance 0.

/// The index of the first occurrence of each distinct position in `points`, in order. Positions
/// are compared exactly (−0 and 0 alike); NaN coordinates never match.
///
/// ```
/// let points = [[0.0, 0.0, 1.0], [2.0, 0.0, 0.0], [0.0, 0.0, 1.0], [-0.0, 0.0, 1.0]];
/// assert_eq!(rbf_cloud::distinct_points(&points), vec![0, 1]);
/// ```
pub fn distinct_points<const D: usize>(points: &[[f64; D]]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len()).collect();
    let key = |i: usize| points[i].map(|c| if c == 0.0 { 0.0 } else { c });
    order.sort_unstable_by(|&a, &b| {
        let (ka, kb) = (key(a), key(b));
        (0..D)
            .map(|d| ka[d].total_cmp(&kb[d]))
            .find(|o| o.is_ne())
            .unwrap_or(core::cmp::Ordering::Equal)
            .then(a.cmp(&b))
    });
    let mut first = vec![false; points.len()];
    for (j, &i) in order.iter().enumerate() {
        first[i] = j == 0 || points[order[j - 1]] != points[i];
    }
    (0..points.len()).filter(|&i| first[i]).collect()
}
