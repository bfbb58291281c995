//! Whole patches of normals turned by the winding number of the rest of the scan. Propagated
//! orientation goes wrong in regions: one wrong edge (across a thin part, through noise at a
//! crease) and everything behind it follows, a fifth of a noisy bunny scan's head and ears
//! (measured: 1802 of 9219 points, one region). Judged point by point, such a region agrees
//! with itself: near its points its own dipoles outweigh the rest (see [`super::dipoles`]).
//!
//! So the scan is cut into patches where neighbouring normals turn sharply or reverse (a
//! wrong region's rim is such a cut: its normals are reversed against the right ones beside
//! it), and each patch is judged by the field of the others only. For patches P and Q, A(P, Q)
//! sums over P's points the winding number of Q's dipoles at the inward probe minus that at
//! the outward one: positive when Q's field says P points out. With signs s (±1 per patch),
//! Σ s(P) s(Q) A(P, Q) over P ≠ Q is the scan's consistency; patches are flipped one at a time,
//! the one that gains most first, while any gains. The consistency does not change when every
//! sign does: the scan as a whole then points out by its flux (as after the propagation).
//!
//! A patch turns only where its own points, judged by the others' field (its row of A), say
//! it points the wrong way. Its column alone (how its dipoles sit with the others' probes)
//! does not turn it: a patch too close to the rest to have clear probes of its own (a nose
//! tip, a boot's eyelet rims) has an empty row, and its column is swayed by the probes of
//! neighbouring walls that pass near it (measured, clean spot and boot scans at the finer cut:
//! 11 and 173 right normals turned so, each patch's row 0).
//!
//! A wrong region glued to a right one across a sharp fin (the clean falcon statue: 139 points
//! in a groove between two ridges, where some of its neighbours sit over a ridge on the other
//! side and share its wrong sign) is one patch with it at 35°: on a clean scan, a second pass
//! cuts at 26° ([`FINE_CUT`]). Not on a noisy one, where normals scatter by more than that and
//! the finer patches mix right and wrong points (koala at 0.2 %: 1365 normals turned wrong).

use rayon::prelude::*;
use rbf_cloud::Neighbours;

use rbf_mesh::DipoleTree;

use super::dipoles::{moments, probes_along_normals};
use super::reconstruct::unit;

/// Neighbouring normals further apart than this (cosine of the angle, 35°) cut the patches.
pub(crate) const CUT: f64 = 0.82;

/// The finer cut (26°), for clean scans only.
pub(crate) const FINE_CUT: f64 = 0.9;

/// On a clean scan, a patch turns only where its own points say it points in by at least this
/// much (its row of the agreement, a difference of winding numbers, over its judged points).
/// A scan seen from one side only (a scanner's views from above: `scan_vs_poisson.py
/// --views`) leaves the field of the rest open below, rising into the body from underneath. On
/// a simulated penguin seen so, the whole body turned on 0.008 a judged point, and the turn of
/// everything back by the flux then left its feet, seen from above only, reversed: 1867 of 9970
/// normals, 12.7 % of the fitted ones wrong; with the floor none. The 40 clean scans of the
/// corpus (seeds 11 and 23) came out the same to the last digit. On noisy scans, whose
/// patches are judged again in later rounds, the same floor held right turns back (a cow at
/// 0.5 %: 2.08 → 2.17 % of its normals wrong), so there it is 0.
pub(crate) const CLEAN_LEAST_SAY: f64 = 0.03;

/// Patches of fewer points than this are left to the point-by-point check
/// ([`super::dipoles::flip_against_winding`]).
const SMALLEST: usize = 10;

/// Flips the normals of whole patches of `points` (cut where neighbouring normals in `near`,
/// eight nearest, are further apart than `cut`, a cosine: [`CUT`] or [`FINE_CUT`]) that the
/// winding number of the other patches says point inward, by at least `least_say` a judged
/// point ([`CLEAN_LEAST_SAY`] or 0); returns how many normals it flipped. `longest` is the
/// box's longest side.
pub(crate) fn flip_patches(
    points: &[[f64; 3]],
    normals: &mut [[f64; 3]],
    near: &Neighbours,
    longest: f64,
    cut: f64,
    least_say: f64,
) -> usize {
    if points.len() < 100 {
        return 0;
    }
    let (labels, count) = patches(normals, near, cut);
    // The last label gathers the small patches, which keep their signs.
    let fixed = count - 1;
    if count < 3 {
        return 0;
    }
    let Some((judged, probes)) = probes_along_normals(points, normals, near, longest) else {
        return 0;
    };
    let agreement = agreement(points, normals, near, &labels, count, &judged, &probes);
    let mut judged_in = vec![0.0; count];
    for &i in &judged {
        judged_in[labels[i]] += 1.0;
    }
    let least: Vec<f64> = judged_in.iter().map(|j| least_say * j).collect();
    let signs = patch_signs(&agreement, count, fixed, &least);
    let mut sign_of_point: Vec<f64> = labels.iter().map(|&l| signs[l]).collect();
    // Outward as a whole: Σ (p − c)·n > 0.
    let n = points.len() as f64;
    let centre: [f64; 3] = core::array::from_fn(|d| points.iter().map(|p| p[d]).sum::<f64>() / n);
    let flux: f64 = points
        .iter()
        .zip(normals.iter())
        .zip(&sign_of_point)
        .map(|((p, m), s)| s * (0..3).map(|d| (p[d] - centre[d]) * m[d]).sum::<f64>())
        .sum();
    if flux < 0.0 {
        sign_of_point.iter_mut().for_each(|s| *s = -*s);
    }
    let mut flipped = 0;
    for (m, s) in normals.iter_mut().zip(sign_of_point) {
        if s < 0.0 {
            *m = m.map(|c| -c);
            flipped += 1;
        }
    }
    flipped
}

/// The sign of each of `count` patches (±1) from their agreement matrix (row-major, see
/// [`agreement`]): from all +1, the patch whose flip gains the consistency most is flipped,
/// one at a time while any gains, but only patches whose own row gains by more than their
/// `least`, and never the patch `fixed`.
fn patch_signs(agreement: &[f64], count: usize, fixed: usize, least: &[f64]) -> Vec<f64> {
    // Symmetric: flipping P changes the terms of P's row and of P's column alike.
    let mut signs = vec![1.0_f64; count];
    let mut pull: Vec<f64> = (0..count)
        .map(|p| {
            (0..count)
                .filter(|&q| q != p)
                .map(|q| agreement[p * count + q] + agreement[q * count + p])
                .sum()
        })
        .collect();
    // What P's own points say: the others' field at P's probes (its row, Σ s(Q) A(P, Q)),
    // which turning P gains when it is against P's sign.
    let mut row: Vec<f64> = (0..count)
        .map(|p| {
            (0..count)
                .filter(|&q| q != p)
                .map(|q| agreement[p * count + q])
                .sum()
        })
        .collect();
    // Each flip gains 2 |pull|; at most one flip per patch and round, and few rounds.
    for _ in 0..4 * count {
        let Some((worst, gain)) = (0..count)
            .filter(|&p| p != fixed && -signs[p] * row[p] > least[p])
            .map(|p| (p, -signs[p] * pull[p]))
            .max_by(|a, b| a.1.total_cmp(&b.1))
        else {
            break;
        };
        if !(gain > 0.0) {
            break;
        }
        signs[worst] = -signs[worst];
        for q in 0..count {
            if q != worst {
                let b = agreement[worst * count + q] + agreement[q * count + worst];
                pull[q] += 2.0 * signs[worst] * b;
                row[q] += 2.0 * signs[worst] * agreement[q * count + worst];
            }
        }
    }
    signs
}

/// The patch of each point and the number of patches: the pieces of the neighbour graph
/// keeping only edges whose normals' cosine is above `cut`, but those of fewer than
/// [`SMALLEST`] points, which share the last label.
fn patches(normals: &[[f64; 3]], near: &Neighbours, cut: f64) -> (Vec<usize>, usize) {
    let mut parent: Vec<usize> = (0..normals.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for i in 0..normals.len() {
        let a = unit(normals[i]);
        for &j in near.of(i) {
            let b = unit(normals[j as usize]);
            if a[0] * b[0] + a[1] * b[1] + a[2] * b[2] > cut {
                let (ri, rj) = (root(&mut parent, i), root(&mut parent, j as usize));
                parent[ri.max(rj)] = ri.min(rj);
            }
        }
    }
    let roots: Vec<usize> = (0..normals.len()).map(|i| root(&mut parent, i)).collect();
    let mut size = vec![0usize; normals.len()];
    roots.iter().for_each(|&r| size[r] += 1);
    let mut label = vec![usize::MAX; normals.len()];
    let mut count = 0;
    for &r in &roots {
        if size[r] >= SMALLEST && label[r] == usize::MAX {
            label[r] = count;
            count += 1;
        }
    }
    let labels = roots
        .iter()
        .map(|&r| if size[r] >= SMALLEST { label[r] } else { count })
        .collect();
    (labels, count + 1)
}

/// A(P, Q) (row-major, `count` × `count`): over the `judged` points of P, the winding number
/// of Q's dipoles at the inward probe minus that at the outward one (`probes` in pairs). Each
/// patch's dipoles are summed through a hierarchy of their own ([`rbf_mesh::DipoleTree`]).
fn agreement(
    points: &[[f64; 3]],
    normals: &[[f64; 3]],
    near: &Neighbours,
    labels: &[usize],
    count: usize,
    judged: &[usize],
    probes: &[[f64; 3]],
) -> Vec<f64> {
    let moments = moments(points, normals, near);
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); count];
    for (i, &label) in labels.iter().enumerate() {
        members[label].push(i);
    }
    let trees: Vec<DipoleTree> = members
        .iter()
        .map(|of| {
            let at: Vec<[f64; 3]> = of.iter().map(|&i| points[i]).collect();
            let moment: Vec<[f64; 3]> = of.iter().map(|&i| moments[i]).collect();
            DipoleTree::new(&at, &moment)
        })
        .collect();
    // Runs of judged points summed on every core, then added in order: the same sums whatever
    // the threads did. A patch is not judged by its own field (A(P, P) is never read).
    let runs: Vec<Vec<f64>> = (0..judged.len())
        .collect::<Vec<usize>>()
        .par_chunks(64)
        .map(|run| {
            let mut a = vec![0.0; count * count];
            for &k in run {
                let p = labels[judged[k]];
                let (inward, outward) = (probes[2 * k], probes[2 * k + 1]);
                let row = &mut a[p * count..][..count];
                for (q, (v, tree)) in row.iter_mut().zip(&trees).enumerate() {
                    if q != p {
                        *v += tree.winding_number(inward) - tree.winding_number(outward);
                    }
                }
            }
            a
        })
        .collect();
    let mut a = vec![0.0; count * count];
    for run in runs {
        a.iter_mut().zip(run).for_each(|(x, y)| *x += y);
    }
    a
}

#[cfg(test)]
mod tests {
    use super::{CUT, flip_patches, patch_signs};
    use crate::scans::dipoles::flip_against_winding;
    use crate::scans::dipoles::tests::torus;

    /// Patch 1's points see the others' field say they point in (its row), and its dipoles
    /// disagree at theirs (its column): it turns. Patch 2 has no probes of its own (an empty
    /// row), only a column against it, larger than the gain would need: it keeps its sign.
    /// Patch 3 gathers the small patches and never turns.
    #[test]
    fn a_patch_turns_only_where_its_own_probes_say_so() {
        let count = 4;
        let mut agreement = vec![0.0; count * count];
        let mut set = |p: usize, q: usize, v: f64| agreement[p * count + q] = v;
        set(0, 1, -5.0);
        set(1, 0, -5.0);
        set(0, 2, -3.0);
        set(1, 2, -1.0);
        set(3, 0, 2.0);
        set(0, 3, 2.0);
        assert_eq!(
            patch_signs(&agreement, count, 3, &[0.0; 4]),
            [1.0, -1.0, 1.0, 1.0]
        );
        // Given a row of its own that agrees, patch 2 turns by the same matrix.
        agreement[2 * count] = -0.5;
        assert_eq!(
            patch_signs(&agreement, count, 3, &[0.0; 4]),
            [1.0, -1.0, -1.0, 1.0]
        );
        // Unless its row says less than its floor (a clean scan's, over its judged points).
        assert_eq!(
            patch_signs(&agreement, count, 3, &[0.0, 0.0, 0.5, 0.0]),
            [1.0, -1.0, 1.0, 1.0]
        );
    }

    /// A third of a torus reversed, as propagation leaves a region behind one wrong edge: point
    /// by point its normals agree with their own side's field, and only those whose probes see
    /// a negative field in all are turned (1274 of 2000), not the whole of it; as a patch
    /// judged by the rest of the scan, all of it is, and nothing else.
    #[test]
    fn a_third_of_a_torus_reversed_is_turned_back_whole() {
        let n = 6000;
        let (points, truth) = torus(n);
        let near = rbf_cloud::Neighbours::new(&points, 8);
        // The torus's points go once around z with their index.
        let wrong = n / 3;
        let reversed: Vec<[f64; 3]> = (0..n)
            .map(|i| {
                if i < wrong {
                    truth[i].map(|c| -c)
                } else {
                    truth[i]
                }
            })
            .collect();

        let mut by_points = reversed.clone();
        let turned = flip_against_winding(&points, &mut by_points, &near, 2.8);
        assert!(turned < wrong, "point by point: {turned} of {wrong}");
        assert_ne!(by_points, truth);

        let mut normals = reversed;
        assert_eq!(
            flip_patches(&points, &mut normals, &near, 2.8, CUT, 0.0),
            wrong
        );
        assert_eq!(normals, truth);
        assert_eq!(flip_patches(&points, &mut normals, &near, 2.8, CUT, 0.0), 0);
    }
}
