//! Where two sheets of a clean scan run close (a boot's lace beside its upper, a gap under a
//! statue's wing, a thin ear), an even spread of the scan has few points across the gap or
//! the part, and a smoothing fit through them bridges the gap with a film or pulls the part's
//! two faces together. There the spread is made finer: the points of the scan near spread
//! points that face another sheet are added at half the spread's spacing.

use rayon::prelude::*;
use rbf_cloud::{Neighbours, PointTree};

use super::reconstruct::{dot, unit};

/// How far across, in spread spacings, a sheet faces another closely: three (on the clean
/// boot scan, five flagged twice the points for no better F-score, and gave the cow scan a
/// second piece and the falcon statue's genus 0 → 6).
const REACH: f64 = 3.0;

/// How much finer the spread is made where sheets run close: its spacing over two (three
/// added half as many points again on the boot scan for 0.0002 of F-score).
const FINER: f64 = 2.0;

/// The share of the spread that may face another sheet closely for the spread to be made
/// finer there: a quarter. Where more does, the close sheets are the object itself (a blade
/// thinner than three spacings: 53–57 % of the sword scans' spread, 8 % at most of the other
/// 19 corpus meshes' scans), and refining it would double the fit.
const MOST_SHARE: f64 = 0.25;

/// Whether two oriented points face each other across a gap or a thin part: normals more
/// than 120° apart, and the second within about 45° of the first's normal line (not beside it
/// on a fold or a crease).
fn facing(p: [f64; 3], n: [f64; 3], q: [f64; 3], m: [f64; 3]) -> bool {
    let d = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
    dot(n, m) < -0.5 && dot(d, n).abs() > 0.7 * dot(d, d).sqrt()
}

/// `spread` (indices into `points`, whose oriented `normals` are given) with those of `points`
/// nearest a spread point that faces another sheet within [`REACH`] spread spacings added, no
/// two closer than the spread's median spacing over [`FINER`]; with the count of spread points
/// that face another sheet. The spread is returned as it is where more than [`MOST_SHARE`] of
/// it does. Its indices come sorted.
pub(super) fn thicken_at_close_sheets(
    points: &[[f64; 3]],
    normals: &[[f64; 3]],
    spread: Vec<usize>,
) -> (Vec<usize>, usize) {
    let at: Vec<[f64; 3]> = spread.iter().map(|&i| points[i]).collect();
    let tree = PointTree::new(&at);
    let spacing = super::dipoles::median_spacing(&Neighbours::with_tree(&tree, &at, 1));
    let Some(spacing) = spacing.filter(|&s| s > 0.0) else {
        return (spread, 0);
    };
    let close: Vec<bool> = (0..at.len())
        .into_par_iter()
        .map(|a| {
            let n = unit(normals[spread[a]]);
            tree.within(&at[a], REACH * spacing)
                .iter()
                .any(|&(b, _)| facing(at[a], n, at[b], unit(normals[spread[b]])))
        })
        .collect();
    let count = close.iter().filter(|&&c| c).count();
    if count == 0 || count as f64 > MOST_SHARE * at.len() as f64 {
        return (spread, count);
    }
    let more: Vec<usize> = (0..points.len())
        .into_par_iter()
        .filter(|&i| tree.nearest(&points[i]).is_some_and(|(a, _)| close[a]))
        .collect();
    let finer = crate::poisson::spread_adding(points, &spread, &more, spacing / FINER);
    (finer, count)
}

#[cfg(test)]
mod tests {
    use super::thicken_at_close_sheets;

    /// Points on a square grid of `n` × `n` at spacing 0.1 in the plane z = `z`, with normal
    /// (0, 0, `up`), and those of them on every fourth row and column (a spread of spacing
    /// 0.4).
    fn sheets(sheets: &[(usize, f64, f64)]) -> (Vec<[f64; 3]>, Vec<[f64; 3]>, Vec<usize>) {
        let (mut points, mut normals, mut spread) = (Vec::new(), Vec::new(), Vec::new());
        for &(n, z, up) in sheets {
            for i in 0..n * n {
                if (i % n) % 4 == 0 && (i / n) % 4 == 0 {
                    spread.push(points.len());
                }
                points.push([(i % n) as f64 * 0.1, (i / n) as f64 * 0.1, z]);
                normals.push([0.0, 0.0, up]);
            }
        }
        (points, normals, spread)
    }

    /// A slab two spread spacings thin, whose faces face away from each other, gets a finer
    /// spread; a lone sheet far from it gets none.
    #[test]
    fn only_sheets_facing_each_other_closely_are_spread_finer() {
        let (points, normals, spread) = sheets(&[(20, 0.0, -1.0), (20, 0.8, 1.0), (80, 20.0, 1.0)]);
        let (finer, close) = thicken_at_close_sheets(&points, &normals, spread.clone());
        // The slab's 2 × 25 spread points face the other face, 0.8 away; the far sheet's 400
        // do not.
        assert_eq!(close, 50);
        assert!(spread.iter().all(|i| finer.contains(i)));
        let added: Vec<usize> = finer
            .iter()
            .copied()
            .filter(|i| !spread.contains(i))
            .collect();
        // At half the spacing, the slab's spread at least three times as dense.
        assert!(added.len() >= 100, "{} added", added.len());
        assert!(added.iter().all(|&i| points[i][2] < 1.0));
        // No two points of the finer spread closer than half the spacing.
        for (k, &i) in added.iter().enumerate() {
            for &j in finer.iter().filter(|&&j| j != i).chain(&added[..k]) {
                let d: f64 = (0..3).map(|c| (points[i][c] - points[j][c]).powi(2)).sum();
                assert!(d.sqrt() >= 0.2 - 1e-9);
            }
        }
    }

    /// Two sheets facing each other across a gap of a spacing count too; a slab thicker than
    /// the reach does not; and a spread that faces another sheet nearly everywhere (a blade)
    /// is left as it is.
    #[test]
    fn a_narrow_gap_counts_a_thick_slab_does_not_and_a_blade_is_left() {
        let (points, normals, spread) = sheets(&[(40, 0.0, 1.0), (40, 0.4, -1.0)]);
        let (finer, close) = thicken_at_close_sheets(&points, &normals, spread.clone());
        assert_eq!((finer, close), (spread, 200));
        let (points, normals, spread) = sheets(&[(40, 0.0, -1.0), (40, 1.6, 1.0)]);
        let (finer, close) = thicken_at_close_sheets(&points, &normals, spread.clone());
        assert_eq!((finer, close), (spread, 0));
    }
}
