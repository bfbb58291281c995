//! Normals checked against the winding number of the oriented points: every point, taken as a
//! small patch of surface (a dipole of its area along its normal), adds the solid angle it
//! subtends, and together they make a field that is 1 inside a closed scan and 0 outside
//! (the generalized winding number, Jacobson et al. 2013; its use to orient points: Metzer et
//! al. 2021, Lin et al. 2024). Each point is judged by the field at two probes along its
//! normal, as far as each stays nearer to it than to any other point (so, inward, near the
//! middle of the part): a normal whose inward probe sees less of the field than its outward one
//! points the wrong way, and so, on a closed scan, does one whose two probes together see a
//! negative field: a closed part reached the wrong way as a whole (a foot through the gap where
//! it touches the body) agrees with itself probe by probe, but its field is −1 inside, where a
//! right one is 1.
//!
//! Propagated orientation (and the coarse fits that vote on it, [`super::consensus`]) go wrong
//! in whole patches: a wrong sign reached through one bad edge spreads to everything behind
//! it, and a fit through a patch follows it. Far from the surface, in the middle of a part, a
//! patch weighs by the solid angle it subtends there, and the rest of the scan outweighs it.

use rbf_cloud::{Neighbours, clear_offsets};

use super::reconstruct::unit;

/// The probes reach at most this fraction of the box's longest side from their point.
const REACH: f64 = 0.1;

/// A point is in a part that points in as a whole where the field at its two probes together
/// is below minus this (about −1 there, 1 where the part points out).
const INSIDE_OUT: f64 = 0.5;

/// The scan counts as closed, for that test, where the median of those sums is above this.
const CLOSED: f64 = 0.5;

/// A probe nearer to its point than this many spacings is too close to judge by.
const CLOSEST: f64 = 2.0;

/// Flips the normals of `points` whose inward probe sees less winding number than their
/// outward one, or (where most points' probes see about 1 together, as around a closed scan)
/// whose two probes see less than −½ together; returns how many. `near` holds the points'
/// eight nearest neighbours (see [`winding_field`]) and `longest` is the box's longest side.
pub(crate) fn flip_against_winding(
    points: &[[f64; 3]],
    normals: &mut [[f64; 3]],
    near: &Neighbours,
    longest: f64,
) -> usize {
    if points.len() < 100 {
        return 0;
    }
    let Some((judged, probes)) = probes_along_normals(points, normals, near, longest) else {
        return 0;
    };
    let field = winding_field(points, normals, near, &probes);
    // The gap inward minus outward: about 1 where a normal is right, −1 where it is wrong. On a
    // simulated torus scan at 0.5 % noise (by direct sums), every one of the 187 gaps below 0
    // belonged to a wrong normal, and 1 of the 9139 above. Where most gaps are not positive, the field says
    // nothing, and nothing is flipped.
    let gaps: Vec<f64> = field.chunks(2).map(|w| w[0] - w[1]).collect();
    if !(median(&gaps) > 0.0) {
        return 0;
    }
    // The two probes together: about 1 + 0 where the part around a point points out, and
    // 0 − 1 where a whole closed part points in (a foot, a body reached the wrong way as a
    // whole). There the gap is right by the part's own field, but the field is negative, and
    // the points of such a part whose probes are clear turn in the same pass. Only where the
    // sums are mostly near 1, as around a closed scan: an open one's are not (a bowl seen from
    // inside sums to about −0.6 everywhere, and is right).
    let sums: Vec<f64> = field.chunks(2).map(|w| w[0] + w[1]).collect();
    let closed = median(&sums) > CLOSED;
    let mut flipped = 0;
    for ((&i, gap), sum) in judged.iter().zip(gaps).zip(sums) {
        if gap < 0.0 || (closed && sum < -INSIDE_OUT) {
            normals[i] = normals[i].map(|c| -c);
            flipped += 1;
        }
    }
    flipped
}

/// The median distance from a point to its nearest neighbour in `near` (`None` for no points).
pub(super) fn median_spacing(near: &Neighbours) -> Option<f64> {
    let nearest: Vec<f64> = (0..near.len())
        .filter_map(|i| near.distances_of(i).first().copied())
        .collect();
    (!nearest.is_empty()).then(|| median(&nearest))
}

/// The median of `values` (NaN when there are none).
pub(super) fn median(values: &[f64]) -> f64 {
    let mut sorted = values.to_vec();
    if sorted.is_empty() {
        return f64::NAN;
    }
    let middle = sorted.len() / 2;
    *sorted.select_nth_unstable_by(middle, f64::total_cmp).1
}

/// The points far enough from the rest of the scan along their normal, both ways, to be
/// judged by the winding number there (their clear offsets, up to [`REACH`] of `longest`, at
/// least [`CLOSEST`] median spacings), and their probes: the inward one, then the outward one,
/// of each. `None` when the points have no spacing.
pub(crate) fn probes_along_normals(
    points: &[[f64; 3]],
    normals: &[[f64; 3]],
    near: &Neighbours,
    longest: f64,
) -> Option<(Vec<usize>, Vec<[f64; 3]>)> {
    let spacing = median_spacing(near)?;
    let offsets = clear_offsets(points, normals, REACH * longest);
    let judged: Vec<usize> = (0..points.len())
        .filter(|&i| offsets[i].iter().all(|&t| t >= CLOSEST * spacing))
        .collect();
    let probes: Vec<[f64; 3]> = judged
        .iter()
        .flat_map(|&i| {
            let (p, n, [inward, outward]) = (points[i], unit(normals[i]), offsets[i]);
            [
                core::array::from_fn(|d| p[d] - inward * n[d]),
                core::array::from_fn(|d| p[d] + outward * n[d]),
            ]
        })
        .collect();
    Some((judged, probes))
}

/// The winding number of the oriented `points` at each probe (about 1 inside a closed scan, 0
/// outside), `near` their eight nearest neighbours: each point stands for the area of a disc
/// reaching its eighth neighbour, shared by nine. Summed through rbf-mesh's cluster hierarchy
/// ([`rbf_mesh::DipoleTree`]).
pub(crate) fn winding_field(
    points: &[[f64; 3]],
    normals: &[[f64; 3]],
    near: &Neighbours,
    probes: &[[f64; 3]],
) -> Vec<f64> {
    let moments = moments(points, normals, near);
    rbf_mesh::dipole_winding_numbers(points, &moments, probes)
}

/// Each point's dipole moment: its normal times the area it stands for, a disc reaching its
/// eighth neighbour (`near`) shared by nine.
pub(crate) fn moments(
    points: &[[f64; 3]],
    normals: &[[f64; 3]],
    near: &Neighbours,
) -> Vec<[f64; 3]> {
    (0..points.len())
        .map(|i| {
            let r = near.distances_of(i).last().copied().unwrap_or(0.0);
            let area = core::f64::consts::PI * r * r / 9.0;
            unit(normals[i]).map(|c| area * c)
        })
        .collect()
}

#[cfg(test)]
pub(super) mod tests {
    use super::flip_against_winding;
    use crate::scans::reconstruct::unit;

    /// Points on a torus around z (radii 1 and 0.4) by a golden-ratio lattice, with their
    /// outward normals.
    pub(in crate::scans) fn torus(n: usize) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
        let golden = 0.5 * (5f64.sqrt() - 1.0);
        (0..n)
            .map(|i| {
                let u = core::f64::consts::TAU * i as f64 / n as f64;
                let v = core::f64::consts::TAU * (i as f64 * golden).fract();
                let r = 1.0 + 0.4 * v.cos();
                (
                    [r * u.cos(), r * u.sin(), 0.4 * v.sin()],
                    [v.cos() * u.cos(), v.cos() * u.sin(), v.sin()],
                )
            })
            .unzip()
    }

    /// The winding field is about 1 inside and 0 outside, with the areas each point stands for
    /// taken from its neighbours: also where one half of the scan is four times as dense as the
    /// other (the lattice probes count a point as outside below 0.25).
    #[test]
    fn the_winding_field_is_one_inside_and_zero_outside_of_an_uneven_scan() {
        let n = 8000;
        let (points, normals): (Vec<[f64; 3]>, Vec<[f64; 3]>) = (0..n)
            .map(|i| {
                let z = 1.0 - (2 * i + 1) as f64 / n as f64;
                let t = 2.399963 * i as f64;
                let s = (1.0 - z * z).sqrt();
                [s * t.cos(), s * t.sin(), z]
            })
            .enumerate()
            .filter(|&(i, p)| p[0] > 0.0 || i % 4 == 0)
            .map(|(_, p)| (p, p))
            .unzip();
        let probes: Vec<[f64; 3]> = (0..200)
            .map(|i| {
                let r = if i % 2 == 0 { 0.6 } else { 1.6 };
                let (a, b) = (0.7 * i as f64, 1.3 * i as f64);
                [r * a.cos() * b.sin(), r * a.sin() * b.sin(), r * b.cos()]
            })
            .collect();
        let near = rbf_cloud::Neighbours::new(&points, 8);
        let w = super::winding_field(&points, &normals, &near, &probes);
        for (i, w) in w.iter().enumerate() {
            if i % 2 == 0 {
                assert!((0.85..1.15).contains(w), "inside {:?}: {w}", probes[i]);
            } else {
                assert!(w.abs() < 0.1, "outside {:?}: {w}", probes[i]);
            }
        }
    }

    #[test]
    fn a_flipped_patch_is_turned_back_and_right_normals_are_left_alone() {
        let (points, truth) = torus(6000);
        let mut normals = truth.clone();
        let near = rbf_cloud::Neighbours::new(&points, 8);
        assert_eq!(flip_against_winding(&points, &mut normals, &near, 2.8), 0);
        assert_eq!(normals, truth);
        // A patch as propagation leaves them: every normal within 0.45 of a point on the
        // tube's outer equator reversed (3 % of them, a coherent region a coarse fit
        // through it would follow).
        let centre = [1.4, 0.0, 0.0];
        let patch: Vec<usize> = (0..points.len())
            .filter(|&i| {
                (0..3)
                    .map(|d| (points[i][d] - centre[d]).powi(2))
                    .sum::<f64>()
                    < 0.45f64.powi(2)
            })
            .collect();
        assert!(patch.len() > 150, "{}", patch.len());
        for &i in &patch {
            normals[i] = normals[i].map(|c| -c);
        }
        let flipped = flip_against_winding(&points, &mut normals, &near, 2.8);
        assert_eq!(flipped, patch.len());
        assert_eq!(normals, truth);
    }

    /// A foot that points in as a whole, as propagation leaves one reached through the gap
    /// where it touches the body (here handed to the check so, 0.4 from the body, so that
    /// every point of it has probes clear of the body; where it touches, the points beside
    /// the contact have probes too short to judge and are left to the later rounds): by its
    /// own field every one of its normals is right (the gap between its probes is positive),
    /// but the field of the whole scan is −1 inside it. Nearly all of it turns at once (the
    /// rest, once the foot points out, by the gap between their probes in a second pass, as
    /// the passes repeat in the pipeline), and nothing of the body.
    #[test]
    fn a_closed_part_that_points_in_as_a_whole_is_turned() {
        let body = rbf_core::shapes::fibonacci_sphere(6000);
        let foot: Vec<[f64; 3]> = rbf_core::shapes::fibonacci_sphere(1500)
            .into_iter()
            .map(|p| [1.8 + 0.4 * p[0], 0.4 * p[1], 0.4 * p[2]])
            .collect();
        let points: Vec<[f64; 3]> = body.iter().chain(&foot).copied().collect();
        let truth: Vec<[f64; 3]> = body
            .iter()
            .copied()
            .chain(foot.iter().map(|p| unit([p[0] - 1.8, p[1], p[2]])))
            .collect();
        let mut normals: Vec<[f64; 3]> = (0..points.len())
            .map(|i| {
                if i < body.len() {
                    truth[i]
                } else {
                    truth[i].map(|c| -c)
                }
            })
            .collect();
        let near = rbf_cloud::Neighbours::new(&points, 8);
        let first = flip_against_winding(&points, &mut normals, &near, 3.2);
        assert!(first > foot.len() * 9 / 10, "{first} of {}", foot.len());
        assert_eq!(normals[..body.len()], truth[..body.len()]);
        let second = flip_against_winding(&points, &mut normals, &near, 3.2);
        assert_eq!(first + second, foot.len());
        assert_eq!(normals, truth);
    }

    /// An open bowl seen from inside (its normals towards its centre) is right, though the
    /// field at its probes sums to about −0.6: the sums are mostly far from 1, so the scan
    /// does not count as closed, and nothing is turned by them.
    #[test]
    fn an_open_bowl_seen_from_inside_is_left_alone() {
        let points: Vec<[f64; 3]> = rbf_core::shapes::fibonacci_sphere(3000)
            .into_iter()
            .filter(|p| p[2] < 0.0)
            .collect();
        let truth: Vec<[f64; 3]> = points.iter().map(|p| p.map(|c| -c)).collect();
        let mut normals = truth.clone();
        let near = rbf_cloud::Neighbours::new(&points, 8);
        let flipped = flip_against_winding(&points, &mut normals, &near, 2.0);
        assert!(
            flipped * 100 < points.len(),
            "{flipped} of {}",
            points.len()
        );
    }
}
