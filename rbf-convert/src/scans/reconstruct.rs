//! Scans to implicit surfaces: a point cloud, with or without normals, noisy, with holes and a
//! few outliers, becomes a model whose zero set is a closed surface near the points. Outliers
//! are dropped (statistically), normals estimated from local planes where the cloud has none,
//! and all of them oriented consistently and outward (rbf-cloud). An even spread of the points
//! (moved onto their local planes first, on a noisy scan) then carries normal constraints in a
//! smoothing fit (Carr et al. 2001's λ): through the middle of the noise on a noisy scan; on a
//! clean one, a light smoothing that follows the points closely but does not close narrow
//! crevices over. With a tolerance asked for, a subset of the points chosen greedily carries
//! the constraints instead, until the surface passes within the tolerance of every point.
//! Holes close by themselves: the implicit function is defined everywhere.
//!
//! The greedy fit takes the worst-met points first, and on a noisy scan those are the points
//! whose normals are wrong: a few hundred of 2·10⁴ (measured on a simulated bunny scan at 0.2 %
//! noise: 114 of the 120 wrong-signed normals became centres, and the surface came out with
//! genus 21); on a clean one, the points at the bottom of crevices, and the surface closes
//! over the crevices between them. So a noisy scan is smoothed on neighbourhoods as wide as its noise asks, its
//! normals are voted on by fits to the other points ([`super::consensus`]) and checked by lines
//! of sight ([`super::sight`]), normals at odds
//! with their neighbours are left out, and it is fitted by one smoothing fit of an even spread
//! (a greedy fit, when a tolerance is asked for, skips points its surface passes but faces
//! away from: `GreedySettings::skip_contradicted`). The same scan then comes out with genus 0,
//! one piece.

use rbf_cloud::{
    Neighbours, PointTree, clear_offsets_with_tree, distinct_points, estimate_normals,
    estimate_normals_spanning_lines, normal_of, orient_normals, statistical_outliers,
};
use rbf_core::{Constraint, FitSettings, Model, NormalOffset};

use crate::ConvertError;
use crate::poisson::bounds;
use rayon::prelude::*;

/// The fewest points a surface is reconstructed from.
const FEWEST_POINTS: usize = 10;

/// Noise (as a fraction of the box's longest side) above which points are moved onto their
/// local planes before fitting, and the scan is treated as noisy throughout.
const SMOOTH_ABOVE: f64 = 1e-3;

/// Noise, as a share of the median distance from a point to the farthest of its neighbours,
/// above which a scan is noisy too, however small its noise beside the box. Measured so on
/// simulated scans: clean ones 0.0005–0.018 (the 20 corpus meshes' at 10⁵ points, scans in
/// lines, seen from above, and a clean cow of 10⁴ points, the highest), noisy ones from 0.075
/// (Gaussian noise of 0.05 % of the diagonal on the bunny; 0.084 on the cow). Treated as
/// clean, those scans of noise 0.05 % came out with handles (the bunny genus 11, F-score at
/// 0.5 % 0.9569, the cow 4, the hand 5; at 0.1 % the boat, measured just under
/// [`SMOOTH_ABOVE`], 17, F-score 0.8557): the clean path (normals from the raw points, the
/// finer spread at close sheets, no votes or lines of sight) is built for noise far below the
/// spacing.
const NOISE_OF_REACH: f64 = 0.04;

/// Points the greedy fit chooses from, at most (an even spread of a denser scan).
const THINNED: usize = 20_000;

/// The smallest default tolerance, as a fraction of the box's longest side: what a budget of
/// a few thousand centres can meet on a detailed scan.
const MIN_TOLERANCE: f64 = 2.5e-3;

/// Settings of [`reconstruct`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReconstructSettings {
    /// Neighbours of each point for its normal and its noise: 16 (doubled, up to 128, while
    /// more than a fifth of the neighbourhoods lie along lines: a cloud scanned in slices or
    /// profiles; see [`ReconstructReport::neighbours`]).
    pub neighbours: usize,
    /// Drop points whose mean distance to their 20 nearest neighbours exceeds the cloud's mean
    /// by this many standard deviations: 2.5; `None` keeps every point.
    pub outlier_ratio: Option<f64>,
    /// `Some`: fit greedily until the surface passes within this of every point, as a
    /// fraction of the box's longest side (λ and the smoothing spreads are then not used).
    /// `None` (the default): one smoothing fit, whose misses are counted against three times
    /// the noise measured about the local planes, and at least 2.5e-3.
    pub tolerance: Option<f64>,
    /// The most points that carry constraints in a greedy fit (when a tolerance is given):
    /// 8000 (the clean knot, falcon statue and boot scans of the benchmark need 5380, 6474
    /// and 8244 to meet a tolerance of 2.5e-3; 8000 keeps the boot within 1.5× of Open3D's
    /// time).
    pub max_centres: usize,
    /// Offset of the normal constraints: 1% of the box's longest side, and at least four
    /// times the measured noise; each constraint's own is shortened (halved up to five times)
    /// until its inside point stays nearest its own point, so that a part thinner than the
    /// offset is not pierced (on a clean simulated cow scan, whose walls are thinner than
    /// 1 %: genus 17 → 11, F-score at 0.5 % 0.988 → 0.995).
    pub offset: NormalOffset,
    /// The most points a scan is worked on: 10⁵. A denser one is taken as a random subset of
    /// this many (after its outliers are dropped), which has its noise and the density of a
    /// scan this size. Its fit takes at most an even spread of 1.5·10⁴ of them anyway (2·10⁴
    /// for a greedy fit), and its neighbourhoods, a
    /// fixed count of points, shrink as it grows denser while its noise does not: on a
    /// simulated bunny scan of 10⁶ points with noise of 0.2 % of the diagonal, taken whole, a
    /// third of the normals came out flipped and the surface with genus 215; 10⁵ of them,
    /// genus 3; an even spread of 2·10⁵ (Poisson-disk, which spreads the points through the
    /// noise's thickness too), genus 52.
    pub working: usize,
    /// λ of the smoothing fit a scan gets (when no tolerance is given), in the units of
    /// a box whose longest side is 2 (the fit's own; λ scales with the cube of the size for
    /// r³). Smaller follows the points (and their noise) more closely, larger is smoother.
    /// `None` (the default): chosen from the measured noise by [`smoothing_for_noise`].
    pub smoothing: Option<f64>,
    /// Points of a noisy scan that carry constraints in its smoothing fit: an even spread of
    /// 10⁴ (2·10⁴ measured no better on a noisy koala scan, at twice the time).
    pub smoothed_centres: usize,
    /// Points of a clean scan that carry constraints in its smoothing fit: an even spread of
    /// 1.5·10⁴. A clean scan keeps detail that noise would blur, and the spread is all it
    /// has: 10⁴ lost F-score at 0.5 % on detailed meshes (Nefertiti 0.9994 → 0.9983, the boot
    /// 0.9922 → 0.9891, the goat head 0.9935 → 0.9928); 2·10⁴ took twice the time of 10⁴.
    pub clean_centres: usize,
    /// Make a clean scan's spread twice as fine where two of its sheets face each other
    /// within three of its spacings, so that its fit does not bridge them (see
    /// [`super::close_sheets`]): on by default; [`Self::with_max_centres`] turns it off, its
    /// count being a cap.
    pub finer_at_close_sheets: bool,
    /// Check a clean scan's normals by lines of sight too, as a noisy scan's always are
    /// ([`super::sight`]). Off by default: on the clean scans of the corpus its turns changed
    /// little but the genus of a boat and a sword, and the clean sword took 45 s instead of 20.
    /// [`reconstruct`] turns it on for a second attempt when a clean scan's probes still stray
    /// after a round of outside constraints (a quarter of them), and [`scan_surface`] when
    /// the first mesh comes out open.
    pub sight: bool,
}

impl Default for ReconstructSettings {
    fn default() -> Self {
        Self {
            neighbours: 16,
            outlier_ratio: Some(2.5),
            tolerance: None,
            max_centres: 8000,
            offset: NormalOffset::Relative(0.01),
            working: 100_000,
            smoothing: None,
            smoothed_centres: 10_000,
            clean_centres: 15_000,
            finer_at_close_sheets: true,
            sight: false,
        }
    }
}

impl ReconstructSettings {
    /// These settings with at most `count` points carrying constraints, in whichever fit the
    /// scan gets: the greedy fit's budget, and the smoothing fits' spreads where they are
    /// larger (and not made finer where sheets run close).
    ///
    /// ```
    /// use rbf_convert::ReconstructSettings;
    /// let few = ReconstructSettings::default().with_max_centres(5000);
    /// assert_eq!((few.max_centres, few.smoothed_centres, few.clean_centres), (5000, 5000, 5000));
    /// let many = ReconstructSettings::default().with_max_centres(12_000);
    /// assert_eq!((many.max_centres, many.smoothed_centres, many.clean_centres), (12_000, 10_000, 12_000));
    /// assert!(ReconstructSettings::default().finer_at_close_sheets && !many.finer_at_close_sheets);
    /// ```
    pub fn with_max_centres(self, count: usize) -> Self {
        Self {
            max_centres: count,
            smoothed_centres: self.smoothed_centres.min(count),
            clean_centres: self.clean_centres.min(count),
            finer_at_close_sheets: false,
            ..self
        }
    }
}

/// What [`reconstruct`] did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReconstructReport {
    /// Points given.
    pub points: usize,
    /// Points given again at a position given before, dropped.
    pub duplicates: usize,
    /// Points dropped as outliers.
    pub outliers: usize,
    /// Points the normals, orientation and fit worked on: the points kept, or a random subset
    /// of [`ReconstructSettings::working`] of them in a denser scan.
    pub working: usize,
    /// Whether the normals were estimated (the cloud had none, or only normals of zero length).
    pub normals_estimated: bool,
    /// Given normals of zero length (or not finite) that were estimated instead, among the
    /// points worked on (0 when the normals were estimated throughout).
    pub normals_filled: usize,
    /// Sign reversals by the orientation: the propagation over the points worked on, and on a
    /// noisy scan at the end a lone normal of the spread against neighbours that agree.
    pub flipped: usize,
    /// Sign reversals of a noisy scan's spread because fits to the other points said a normal
    /// points inward (after the orientation; see [`reconstruct`]). Counted at each pass: a
    /// normal reversed twice over the rounds counts twice.
    pub refuted: usize,
    /// Sign reversals of the spread because the winding number of the other points says a
    /// normal points inward (at probes along each normal, whole patches of them and, on a
    /// noisy scan, single points; the patches again after each round of votes). Counted at
    /// each pass, like [`Self::refuted`].
    pub reversed_by_winding: usize,
    /// Sign reversals of a noisy scan's spread because lines of sight say a normal points
    /// inward: the scan stops the rays along it, and the rays against it leave the scan's box
    /// (last, after the other checks; see [`super::sight`]).
    pub reversed_by_sight: usize,
    /// Whether the normals were checked by lines of sight (a noisy scan, or
    /// [`ReconstructSettings::sight`]).
    pub sight: bool,
    /// Whether the normals were oriented again with lines of sight because the first fit
    /// strayed outside nearly everywhere (a clean scan's outside probes still astray by the
    /// quarter after a round of outside constraints) or its mesh came out open
    /// ([`scan_surface`]).
    pub looked_again: bool,
    /// Points left out of the constraints because their normal is more than 60° from the
    /// mean of their neighbours'.
    pub disagreeing: usize,
    /// Points the fitted surface passes but faces the other way from, left out as centres.
    pub contradicted: usize,
    /// Points a smoothing fit passes farther than the tolerance from (0 for a greedy fit,
    /// which meets the tolerance or says it did not in [`Self::within_tolerance`]).
    pub beyond_tolerance: usize,
    /// Connected pieces of the neighbour graph.
    pub pieces: usize,
    /// Neighbours of each point its normal and the neighbour graph were taken from:
    /// [`ReconstructSettings::neighbours`], or more for a cloud scanned in lines (slices,
    /// profiles) farther apart than those reach.
    pub neighbours: usize,
    /// The noise measured: the median over points of the RMS residual of a quadratic height
    /// function fitted to their neighbourhood, as a fraction of the box's longest side.
    pub noise: f64,
    /// Whether the scan counted as noisy (noise above 1e-3 of the box, or above 4 % of the
    /// median distance from a point to its farthest neighbour): its points moved onto their
    /// local planes before the normals were oriented again, the noisy scans' checks of their
    /// signs (votes of fits, lines of sight), an even spread of 10⁴ of them. Its smoothing λ
    /// follows the noise itself ([`smoothing_for_noise`]).
    pub smoothed: bool,
    /// The tolerance used, as a fraction of the box's longest side.
    pub tolerance: f64,
    /// Points that carry constraints.
    pub centres: usize,
    /// Of those, the points a clean scan's even spread gained where two of its sheets run
    /// close (a gap or a thin part a few spread spacings across), so that the fit keeps them
    /// apart.
    pub added_where_sheets_close: usize,
    /// λ of the smoothing fit in the points' units, or 0 when the fit was greedy (a tolerance
    /// given).
    pub lambda: f64,
    /// The largest distance from the surface to any kept point, as a fraction of the box's
    /// longest side, and whether it is within the tolerance.
    pub largest_miss: f64,
    /// Whether every kept point is within the tolerance.
    pub within_tolerance: bool,
    /// Outside constraints added where the surface had strayed beyond the scan (see
    /// [`reconstruct`]).
    pub outside_added: usize,
    /// How far from the scan a piece of the surface may lie and still count as shown by it
    /// (for [`crate::supported_pieces`]): one and a half times the median spacing of the points worked on, or twice
    /// the tolerance if that is more, in the points' units.
    pub support_reach: f64,
}

/// Reconstructs a closed implicit surface from `points` (and their `normals`, when the scan
/// has them: used after their signs are checked).
///
/// ```
/// use rbf_convert::{ReconstructSettings, reconstruct};
/// // 800 points on a sphere of radius 2, no normals.
/// let points: Vec<[f64; 3]> = (0..800)
///     .map(|i| {
///         let z = 1.0 - (2 * i + 1) as f64 / 800.0;
///         let t = 2.399963 * i as f64;
///         let s = (1.0 - z * z).sqrt();
///         [2.0 * s * t.cos(), 2.0 * s * t.sin(), 2.0 * z]
///     })
///     .collect();
/// let (model, report) = reconstruct(&points, None, &ReconstructSettings::default()).unwrap();
/// assert!(report.normals_estimated && report.within_tolerance);
/// let f = model.interpolant.view();
/// assert!(f.value(&[0.0; 3]) > 0.0 && f.value(&[3.0, 0.0, 0.0]) < 0.0);
/// // The surface crosses the y axis within 0.03 of the sphere (the tolerance: 2.5e-3 of 4).
/// assert!(f.value(&[0.0, 1.97, 0.0]) > 0.0 && f.value(&[0.0, 2.03, 0.0]) < 0.0);
/// ```
pub fn reconstruct(
    points: &[[f64; 3]],
    normals: Option<&[[f64; 3]]>,
    settings: &ReconstructSettings,
) -> Result<(Model<3>, ReconstructReport), ConvertError> {
    if let Some(index) = points
        .iter()
        .position(|p| !p.iter().all(|c| c.abs() <= LARGEST_COORDINATE))
    {
        return Err(ConvertError::PointOutOfRange {
            index,
            point: points[index],
        });
    }
    if points.len() < FEWEST_POINTS {
        return Err(ConvertError::TooFewPoints {
            points: points.len(),
            needed: FEWEST_POINTS,
        });
    }
    // A point given twice is once too many: it would be its own nearest neighbour.
    let distinct = distinct_points(points);
    let duplicates = points.len() - distinct.len();
    if distinct.len() == 1 {
        return Err(ConvertError::Flat { shape: "point" });
    }
    // Outliers first: they would bend normals and the surface alike.
    let mut keep: Vec<usize> = match settings.outlier_ratio {
        Some(ratio) => {
            let unique: Vec<[f64; 3]> = distinct.iter().map(|&i| points[i]).collect();
            let flags = statistical_outliers(&Neighbours::new(&unique, 20), ratio);
            distinct
                .iter()
                .zip(flags)
                .filter(|&(_, outlier)| !outlier)
                .map(|(&i, _)| i)
                .collect()
        }
        None => distinct.clone(),
    };
    if keep.len() < FEWEST_POINTS {
        return Err(ConvertError::TooFewPoints {
            points: keep.len(),
            needed: FEWEST_POINTS,
        });
    }
    let outliers = distinct.len() - keep.len();
    let mut kept: Vec<[f64; 3]> = keep.iter().map(|&i| points[i]).collect();
    if let Some(shape) = flatness(&kept) {
        return Err(ConvertError::Flat { shape });
    }
    let working = settings.working.max(FEWEST_POINTS);
    if kept.len() > working {
        let mut subset = crate::poisson::shuffled(kept.len());
        subset.truncate(working);
        subset.sort_unstable();
        keep = subset.iter().map(|&j| keep[j]).collect();
        kept = subset.iter().map(|&j| kept[j]).collect();
    }
    // One tree over the kept points serves their neighbourhoods of every size.
    let kept_tree = PointTree::new(&kept);
    let k = neighbourhood_size(&kept, &kept_tree, settings.neighbours.max(3));
    let near = Neighbours::with_tree(&kept_tree, &kept, k);
    // A given normal of zero length (scanners write one where they had none) is estimated as
    // if none had been given; a cloud whose given normals all have zero length has none.
    let given: Option<Vec<[f64; 3]>> = match normals {
        Some(given) if given.len() == points.len() => {
            Some(keep.iter().map(|&i| unit(given[i])).collect())
        }
        _ => None,
    };
    let zero = |n: &[f64; 3]| *n == [0.0; 3];
    let (unoriented, estimated, normals_filled) = match given {
        Some(given) if !given.iter().all(zero) => {
            let filled = given.iter().filter(|n| zero(n)).count();
            let normals = if filled > 0 {
                let estimates = estimate_normals(&kept, &near);
                given
                    .into_iter()
                    .zip(estimates)
                    .map(|(n, e)| if zero(&n) { e } else { n })
                    .collect()
            } else {
                given
            };
            (normals, false, filled)
        }
        // Where neighbourhoods grown for a cloud in lines still lie along one, wider ones.
        _ if k > settings.neighbours => (
            estimate_normals_spanning_lines(&kept, &kept_tree, &near, MOST_LINE_NEIGHBOURS * 2),
            true,
            0,
        ),
        _ => (estimate_normals(&kept, &near), true, 0),
    };
    let longest = longest_side(&kept);
    let (noise, reach, wide) = measure_noise(&kept, &kept_tree, &unoriented, &near, estimated);
    let noisy = counts_as_noisy(noise, reach, longest);
    let noise = noise / longest;
    let tolerance = settings
        .tolerance
        .unwrap_or_else(|| (3.0 * noise).max(MIN_TOLERANCE));
    // The offset points must lie beyond the noise, or the inside and outside constraints of
    // neighbouring points cross.
    let offset = match settings.offset {
        NormalOffset::Relative(r) => NormalOffset::Relative(r.max(4.0 * noise)),
        other => other,
    };
    // Noise above what a clean scan's curvature shows: each point moves onto the plane of its
    // neighbourhood (its centroid and normal), which averages the noise across the plane away
    // (onto a quadric where the neighbourhood spreads wide, in a sparsely scanned region);
    // estimated normals are estimated again from the smoothed points, and the orientation
    // follows their edges (noisy edges mislead its mirrored-normal predictions).
    let (smoothed, oriented, near) = if noisy {
        // Planes through neighbourhoods a few noise deep: wider ones for noisier scans.
        let (wide, planes) = match wide {
            Some((wide, normals)) => (wide, normals),
            None => (near.clone(), unoriented),
        };
        let wide_k = wide.k();
        let smoothed = project_onto_local_surfaces(
            &kept,
            &planes,
            &wide,
            CURVED_REACH * 4.0 * noise * longest,
        );
        let tree = PointTree::new(&smoothed);
        let near = Neighbours::with_tree(&tree, &smoothed, k);
        let normals = if estimated {
            if wide_k > k {
                estimate_normals(&smoothed, &Neighbours::with_tree(&tree, &smoothed, wide_k))
            } else {
                estimate_normals(&smoothed, &near)
            }
        } else {
            planes
        };
        let oriented = orient_normals(&smoothed, &normals, &near);
        (smoothed, oriented, near)
    } else {
        let oriented = orient_normals(&kept, &unoriented, &near);
        (kept.clone(), oriented, near)
    };
    // A scan (without a tolerance asked for) gets a smoothing fit of an even spread of its
    // points. On a noisy scan, the greedy fit would take the points the noise put farthest
    // out first; on a clean one, the points it takes (the worst met: at the bottom of
    // crevices, along creases) pull the surface across the crevices between them, in films
    // that add handles (see [`CLEAN_SMOOTHING`]).
    let smooth_fit = settings.tolerance.is_none();
    // Dense scans are thinned to an even spread first: constraints closer than the scan's
    // detail only make the fits ill-conditioned.
    let spread_size = match (smooth_fit, noisy) {
        (true, true) => settings.smoothed_centres,
        (true, false) => settings.clean_centres,
        (false, _) => THINNED,
    }
    // A cloud scanned in lines is thinned as many times over as its neighbourhoods grew, so
    // that its spread lies about as far apart along the lines as across them.
    .min(smoothed.len() * settings.neighbours.max(3) / k)
    .max(FEWEST_POINTS);
    let spread = crate::poisson_subset(&smoothed, spread_size);
    // A clean scan's spread is made finer where two of its sheets run close, so that the fit
    // keeps them apart (not a noisy one's: not measured there, and its normals at close sheets
    // are the least sure).
    let even = spread.len();
    let spread = if smooth_fit && !noisy && settings.finer_at_close_sheets {
        super::close_sheets::thicken_at_close_sheets(&smoothed, &oriented.normals, spread).0
    } else {
        spread
    };
    let added_where_sheets_close = spread.len() - even;
    // Normals at odds with their neighbourhood (noise near a crease, an isolated wrong sign)
    // would be the worst-met constraints, and so the first chosen: they are left out.
    let thinned = spread.len();
    let spread: Vec<usize> = spread
        .into_iter()
        .filter(|&i| agrees_with_neighbours(&oriented.normals, &near, i))
        .collect();
    let disagreeing = thinned - spread.len();
    let (spread_points, mut spread_normals): (Vec<[f64; 3]>, Vec<[f64; 3]>) = spread
        .iter()
        .map(|&i| (smoothed[i], unit(oriented.normals[i])))
        .filter(|(_, n)| n.iter().any(|&c| c != 0.0))
        .unzip();
    // λ for a box whose longest side is 2, and in the scan's units (it scales as r³ does).
    let smoothing = settings
        .smoothing
        .unwrap_or_else(|| smoothing_for_noise(noise))
        * (0.5 * longest).powi(3);
    let lambda = if smooth_fit { smoothing } else { 0.0 };
    let fit_settings = FitSettings {
        normal_offset: offset,
        ..Default::default()
    };
    let greedy = rbf_solve::GreedySettings {
        tolerance,
        max_constraints: settings.max_centres,
        skip_contradicted: true,
        ..Default::default()
    };
    let distance = match offset {
        NormalOffset::Relative(r) => r * longest,
        NormalOffset::Absolute(a) => a,
    };
    // A noisy scan's orientation goes wrong in patches (where it is thin, where noise hides
    // its edges). The winding number of the rest of the scan turns them back first, whole
    // patches and then single points (a coarse fit through a patch follows it); then fits to
    // its points vote on every point's sign, until few change (in the first round only); then
    // patches again, cut anew where those flips left edges, for a few rounds.
    // One tree over the spread serves its neighbours, offsets and distances.
    let spread_tree = PointTree::new(&spread_points);
    let spread_near = Neighbours::with_tree(&spread_tree, &spread_points, 8);
    let mut reversed_by_winding = 0;
    let mut refuted = 0;
    let cuts: &[f64] = if noisy {
        &[super::patches::CUT]
    } else {
        &[super::patches::CUT, super::patches::FINE_CUT]
    };
    let least_say = if noisy {
        0.0
    } else {
        super::patches::CLEAN_LEAST_SAY
    };
    for &cut in cuts {
        reversed_by_winding += super::patches::flip_patches(
            &spread_points,
            &mut spread_normals,
            &spread_near,
            longest,
            cut,
            least_say,
        );
    }
    let juries = if noisy {
        super::consensus::Juries::new(&spread_points)
    } else {
        None
    };
    let jury_settings = FitSettings {
        normal_offset: settings.offset,
        lambda: JURY_SMOOTHING * smoothing,
        ..fit_settings
    };
    let vote = |normals: &mut [[f64; 3]]| match juries.as_ref() {
        Some(juries) => repeat_passes(
            CONSENSUS_PASSES,
            |now| now * 1000 < spread_points.len(),
            || {
                super::consensus::flip_against_fits(
                    &spread_points,
                    normals,
                    juries,
                    &jury_settings,
                    2.0 * distance,
                )
            },
        ),
        None => Ok(0),
    };
    if noisy {
        for round in 0..SIGN_ROUNDS {
            reversed_by_winding += repeat_passes(
                WINDING_PASSES,
                |now| now == 0,
                || {
                    Ok(super::dipoles::flip_against_winding(
                        &spread_points,
                        &mut spread_normals,
                        &spread_near,
                        longest,
                    ))
                },
            )?;
            if round == 0 {
                refuted += vote(&mut spread_normals)?;
            }
            let now = super::patches::flip_patches(
                &spread_points,
                &mut spread_normals,
                &spread_near,
                longest,
                super::patches::CUT,
                least_say,
            );
            reversed_by_winding += now;
            if now == 0 {
                break;
            }
        }
    }
    // On a noisy scan, a lone normal against neighbours that agree with each other (which the
    // checks above pass over where its probes are not clear) is turned to them. Not on a clean
    // one: where its spread straddles two close walls, a point may find seven of its eight
    // neighbours on the other wall (the clean cow: Hausdorff 1.55 → 1.85 % with it).
    //
    // Then, on a noisy scan, lines of sight: they see a part too thin for the probes above
    // with its two sheets facing the same way, and wrong normals that the winding number
    // passed over (a cat at 0.5 %: genus 1 → 0, F-score 0.959 → 0.976; over the 20 meshes'
    // 40 noisy scans, 16 gained up to 0.19 and two lost up to 0.0017). Not on a clean one,
    // whose propagation and patches leave few wrong: there its turns, right or wrong, changed
    // little but the genus of a boat (3 → 5) and a sword (22 → 23).
    //
    // And a second look: the votes and the patches again, then lone normals and sight. A
    // region reversed as a whole and glued to right ones across a thin part (a stuffed toy's
    // ear at 0.5 % noise, 39 % of its normals; half a hand at 1 %) is one patch with them, and
    // the votes cannot overrule so many; the lines of sight turn most of its points, and what
    // they leave is then few enough for the votes (see [`LOOKS`]).
    let mut lone_turned = 0;
    let mut reversed_by_sight = 0;
    let sight = noisy || settings.sight;
    for look in 0..if sight { LOOKS } else { 0 } {
        if look > 0 {
            refuted += vote(&mut spread_normals)?;
            reversed_by_winding += super::patches::flip_patches(
                &spread_points,
                &mut spread_normals,
                &spread_near,
                longest,
                super::patches::CUT,
                least_say,
            );
        }
        let lone: Vec<usize> = (0..spread_points.len())
            .filter(|&i| opposes_neighbours(&spread_normals, &spread_near, i))
            .collect();
        for &i in &lone {
            spread_normals[i] = spread_normals[i].map(|c| -c);
        }
        lone_turned += lone.len();
        reversed_by_sight += super::sight::flip_against_sight(
            &spread_points,
            &mut spread_normals,
            &spread_tree,
            &spread_near,
        );
    }
    // Each inside point as far in as it stays nearest its own point (Carr et al.'s check),
    // so that it does not cross the other sheet of a part thinner than the offset.
    let inward = clear_offsets_with_tree(&spread_tree, &spread_points, &spread_normals, distance);
    let constraints: Vec<Constraint<3>> = spread_points
        .iter()
        .zip(&spread_normals)
        .zip(&inward)
        .map(|((&p, &n), &[inside, _])| {
            let inside = inside.max(distance / 32.0);
            Constraint::normal(p, n)
                .with_offset(inside)
                .with_value(inside / distance)
        })
        .collect();
    // The surface itself fits with the smoothing its noise asks for (and no more).
    let fit_settings = FitSettings {
        lambda,
        max_residual: if smooth_fit {
            SMOOTHING_RESIDUAL
        } else {
            GREEDY_RESIDUAL
        },
        ..fit_settings
    };
    let (mut fit, report, beyond_tolerance, largest_miss) = if smooth_fit {
        let (fit, report, beyond, largest) =
            smoothing_fit(&constraints, &fit_settings, tolerance * longest)?;
        (fit, report, beyond, largest / longest)
    } else {
        let (fit, report) = rbf_solve::fit_greedy(&constraints, &fit_settings, &greedy, |_| {})?;
        let miss = report.rounds.last().map_or(f64::NAN, |r| r.max_error);
        (fit, report, 0, miss)
    };
    // Normal constraints pin f just inside each chosen point, but nothing holds it negative
    // outside: where data is thin (ears, holes, sparse regions) the surface may bulge out
    // (measured on a simulated bunny scan with holes and uneven density: a bulge over the ears
    // a third of the diagonal wide). Each spread point's outward offset, as far as it stays
    // nearer to that point than to the rest of the scan, is probed; where f is not negative
    // there, an outside constraint goes there (its value at the offset's slope) and the chosen
    // constraints are fitted again. A probe the winding number of the oriented spread puts
    // inside is not used: a wrong normal's probe lies inside the part, and one between two
    // close walls may lie inside the other one (on the cow at 0.5 % noise, 83 of 8894; with
    // them, every stray added at once raised a bulge on its back 9.9 % of the diagonal high;
    // without them, the clean cow's genus went from 11 to 8).
    let mut fitted = report.constraints.clone();
    // Probes beyond where the surface may pass (the tolerance), or they would pin it.
    let probe = distance.max(3.0 * tolerance * longest);
    let mut outside: Vec<Constraint<3>> = outward_probes(
        &spread_tree,
        &spread_points,
        &spread_normals,
        &spread_near,
        probe,
    )
    .into_iter()
    .map(|(q, out)| Constraint::exterior(q, -out / distance))
    .collect();
    // And the 26 points around the box grown by a fifth (corners, edges, faces), where the
    // scan must be closed off too.
    let shell = grown_box_shell(&kept, longest);
    let reach = spread_tree.distances(&shell);
    outside.extend(
        shell
            .iter()
            .zip(reach)
            .map(|(&q, r)| Constraint::exterior(q, -r.max(distance) / distance)),
    );
    // And the points of a lattice over that box that lie away from the scan and outside it by
    // the winding number of the oriented points: a surface can balloon out of a hole or over a
    // sparse region where no point's offset probes (measured: a clean cow scan, a bulge 18.7 %
    // of the diagonal high over 12 % of the surface, out of a hole at the head). Each says it
    // is outside by as much as [`lattice_claim`] allows.
    let lattice: Vec<[f64; 3]> = grown_box_lattice(&kept, longest, LATTICE);
    let reach = spread_tree.distances(&lattice);
    let away: Vec<([f64; 3], f64)> = lattice
        .into_iter()
        .zip(reach)
        .filter(|&(_, r)| r > AWAY * distance)
        .collect();
    let probes: Vec<[f64; 3]> = away.iter().map(|&(q, _)| q).collect();
    let winding =
        super::dipoles::winding_field(&spread_points, &spread_normals, &spread_near, &probes);
    outside.extend(
        away.iter()
            .zip(winding)
            .filter(|&(_, w)| w < OUTSIDE_WINDING)
            .map(|(&(q, r), w)| Constraint::exterior(q, -lattice_claim(r, w, distance) / distance)),
    );
    let at: Vec<[f64; 3]> = outside.iter().map(|c| c.position).collect();
    let mut added = vec![false; outside.len()];
    let mut values = vec![0.0; at.len()];
    // Each refit appends its constraints, so the next (which adds fewer) keeps the
    // preconditioner and factors subdomains for its own only.
    let mut preconditioner = rbf_solve::KeptPreconditioner::default();
    for round in 0..OUTSIDE_ROUNDS {
        // Lengths match by construction.
        let _ = fit.interpolant.view().par_values(&at, &mut values);
        let strayed: Vec<usize> = (0..at.len())
            .filter(|&i| !added[i] && !(values[i] < 0.0))
            .collect();
        // A clean scan whose probes still stray by the quarter after a round of outside
        // constraints has wrong normals, not a bulge: it is fitted again with lines of sight
        // (and where that fails, this fit goes on).
        if round == 1 && !sight && strayed.len() as f64 > STILL_STRAYING * at.len() as f64 {
            let sighted = ReconstructSettings {
                sight: true,
                ..*settings
            };
            if let Ok((model, mut report)) = reconstruct(points, normals, &sighted) {
                report.looked_again = true;
                return Ok((model, report));
            }
        }
        if strayed.is_empty() {
            break;
        }
        // All of them, unless a fit went wrong nearly everywhere: then an even pick, so that
        // one refit does not grow the system several times over before it is judged.
        for &i in strayed
            .iter()
            .step_by(strayed.len().div_ceil(OUTSIDE_PER_ROUND))
        {
            added[i] = true;
            fitted.push(outside[i]);
        }
        fit = rbf_solve::fit_from_keeping(
            &fitted,
            &fit_settings,
            &fit.interpolant,
            &mut preconditioner,
        )?;
    }
    let outside_added = added.iter().filter(|&&a| a).count();
    let spacing = super::dipoles::median_spacing(&near).unwrap_or(0.0);
    let support_reach = (1.5 * spacing).max(2.0 * tolerance * longest);
    // Outside means negative: check the shell around the box.
    let view = fit.interpolant.view();
    for at in shell {
        let value = view.value(&at);
        if !(value < 0.0) {
            return Err(ConvertError::NotClosed { at, value });
        }
    }
    let summary = ReconstructReport {
        points: points.len(),
        duplicates,
        outliers,
        working: kept.len(),
        normals_estimated: estimated,
        normals_filled,
        flipped: oriented.flipped + lone_turned,
        refuted,
        reversed_by_winding,
        reversed_by_sight,
        sight,
        looked_again: false,
        disagreeing,
        contradicted: report.contradicted,
        beyond_tolerance,
        pieces: oriented.components,
        neighbours: k,
        noise,
        smoothed: noisy,
        tolerance,
        centres: report.used.len(),
        added_where_sheets_close,
        lambda,
        largest_miss,
        within_tolerance: report.converged,
        outside_added,
        support_reach,
    };
    let model = Model {
        constraints: fitted,
        settings: fit_settings,
        interpolant: fit.interpolant,
        report: Some(fit.report),
    };
    Ok((model, summary))
}

/// Each point's outward offset along its normal as far as `wanted` (shortened while it stays
/// nearest its own point, and left out where it cannot), with that distance, where the winding
/// number of the oriented points says outside (below [`INSIDE_WINDING`]). `tree` and `near`
/// are over `points`.
fn outward_probes(
    tree: &PointTree,
    points: &[[f64; 3]],
    normals: &[[f64; 3]],
    near: &Neighbours,
    wanted: f64,
) -> Vec<([f64; 3], f64)> {
    let probes: Vec<([f64; 3], f64)> = clear_offsets_with_tree(tree, points, normals, wanted)
        .iter()
        .zip(points.iter().zip(normals))
        .filter(|([_, out], _)| *out > 0.0)
        .map(|([_, out], (p, n))| (core::array::from_fn(|k| p[k] + out * n[k]), *out))
        .collect();
    let at: Vec<[f64; 3]> = probes.iter().map(|&(q, _)| q).collect();
    let winding = super::dipoles::winding_field(points, normals, near, &at);
    probes
        .into_iter()
        .zip(winding)
        .filter(|&(_, w)| w < INSIDE_WINDING)
        .map(|(probe, _)| probe)
        .collect()
}

/// The constraints (normal ones) fitted at once with the settings' λ, reported as a greedy fit
/// that took them all, with the count of points the surface passes farther than `tolerance`
/// from and the largest distance to one.
///
/// Points far from it are not left out and fitted again: on a noisy koala scan the three
/// farthest (1.3–7.8 % of the box) were where the surface bulged over a hole's rim, and
/// without them it bulged more (F-score 0.9988 → 0.9976).
fn smoothing_fit(
    constraints: &[Constraint<3>],
    settings: &FitSettings,
    tolerance: f64,
) -> Result<(rbf_core::Fit<3>, rbf_solve::GreedyReport<3>, usize, f64), ConvertError> {
    let points: Vec<[f64; 3]> = constraints.iter().map(|c| c.position).collect();
    let fit = rbf_solve::fit(constraints, settings)?;
    let misses = distances_to_zero_set(&fit.interpolant, &points);
    let beyond = misses.iter().filter(|&&d| !(d <= tolerance)).count();
    let largest = misses.iter().copied().fold(0.0, f64::max);
    let report = rbf_solve::GreedyReport {
        rounds: Vec::new(),
        used: (0..constraints.len()).collect(),
        constraints: constraints.to_vec(),
        converged: beyond == 0,
        contradicted: 0,
    };
    Ok((fit, report, beyond, largest))
}

/// The distance from the zero set of `f` to each of `points`, to first order (|f| / |∇f|).
fn distances_to_zero_set(f: &rbf_core::Interpolant<f64, 3>, points: &[[f64; 3]]) -> Vec<f64> {
    let mut values = vec![0.0; points.len()];
    let mut gradients = vec![[0.0; 3]; points.len()];
    // Lengths match by construction.
    let _ = f
        .view()
        .par_values_and_gradients(points, &mut values, &mut gradients);
    values
        .iter()
        .zip(&gradients)
        .map(|(v, g): (&f64, _)| v.abs() / dot(*g, *g).sqrt().max(f64::MIN_POSITIVE))
        .collect()
}

/// The residual a smoothing fit is solved to, relative to the largest value asked for (the far
/// probes' −r / offset: about 15 on the cow scan at 0.5 % noise, at most about 70, with r up to
/// 0.7 of the box and the offset at least 1 % of it). Near the surface f rises by one per
/// offset, so the surface moves by at most 0.07 of the offset at a constraint: a quarter of the
/// noise at worst (the offset is at least four times the noise), a fiftieth on that cow. Solved
/// to the iterative solver's usual 1e-5, the fit and its refits took 6–12 iterations each on
/// that scan; 5–8 at this. On a clean scan the offset is 1 % of the box, so the surface may
/// move by up to 7e-4 of it, under a third of the smallest tolerance (2.5e-3); the clean
/// scans' figures of the benchmark were measured so. The model keeps this limit in its
/// settings.
const SMOOTHING_RESIDUAL: f64 = 1e-3;

/// The residual a greedy fit (a tolerance asked for) is solved to, relative to the largest
/// value asked for:
/// the iterative solver's usual limit, which its fits above 5000 rows meet already; the dense
/// solver's own (1e-6) is stricter than a scan needs (the surface moves by at most 1e-5 of the
/// largest value times the offset: under 10⁻⁵ of the box). A clean cow scan whose one half was
/// scanned at a twelfth of the density stopped with an error at 3.4e-6 (condition 6.9e12).
const GREEDY_RESIDUAL: f64 = 1e-5;

/// The largest coordinate a scan's point may have: beyond about 1e150, squared distances
/// overflow (a cloud at 1e300 was taken for a single point).
pub const LARGEST_COORDINATE: f64 = 1e100;

/// The λ a scan's smoothing fit takes by default (for a box whose longest side is 2) for its
/// `noise` (as a fraction of that side): a clean scan's (noise up to 1e-3) 3e-5 (see
/// [`CLEAN_SMOOTHING`]); a noisy one's 1e-4 up to a noise of 6e-3 (a scan with Gaussian noise
/// of 0.5 % of the diagonal measures 5.1e-3 to 6.3e-3), and above it growing as the noise's
/// power 1.5.
///
/// Why it grows with the noise: the normal constraints ask f = ±1 an offset in from and out
/// of each point, and the offset grows with the noise (four times it), so f is distance over
/// the offset, and the fit's balance between the misses and λ times f's roughness is the same
/// in distance units whatever the offset: one λ keeps one smoothing length at every noise
/// level. A smoothing spline's best λ grows as the noise's variance to a power below one (σ²
/// to the power 2m/(2m + d): 3/4 for a roughness of order m = 3 over a surface, d = 2).
/// Measured at noise 1 % of the diagonal (measured 7.7e-3 to 1.1e-2), λ 2.8e-4 against 1e-4:
/// F-score at 0.5 % the bunny 0.9275 → 0.9476, the cat 0.6561 → 0.7070 (genus 84 → 23), the
/// boot 0.7634 → 0.7774 (genus 33 → 4), the cow 0.8283 → 0.8238.
///
/// Why not below 1e-4: at 0.2 % noise (measured 2.2e-3 to 2.8e-3), the same rule's λ of about
/// 3e-5 raised the F-score of detailed meshes (the boot 0.9695 → 0.9794, the falcon statue
/// 0.9799 → 0.9887) but gave the falcon statue and the sword at 0.2 and 0.5 % a handle each
/// and the boot a second piece, and lowered the wingnut 0.9987 → 0.9967 and the torus 0.9999 →
/// 0.9996 (one sitting over 20 meshes): a thinner smoothing trades topology for detail.
///
/// ```
/// use rbf_convert::smoothing_for_noise;
/// assert_eq!(smoothing_for_noise(4e-5), 3e-5);
/// assert_eq!(smoothing_for_noise(2.5e-3), 1e-4);
/// assert_eq!(smoothing_for_noise(6e-3), 1e-4);
/// assert!((smoothing_for_noise(1.2e-2) - 2.83e-4).abs() < 1e-6);
/// ```
pub fn smoothing_for_noise(noise: f64) -> f64 {
    if noise > SMOOTH_ABOVE {
        REFERENCE_SMOOTHING * (noise / REFERENCE_NOISE).max(1.0).powf(1.5)
    } else {
        CLEAN_SMOOTHING
    }
}

/// The smoothing of a clean scan's fit (noise up to [`SMOOTH_ABOVE`]), for a box whose longest
/// side is 2: 3e-5. It does not smooth noise away (there is none to speak of) but keeps the
/// surface from bending between its constraints across the narrow crevices of a detailed
/// object, where an exact fit closes them over with films that add handles. Measured on the
/// clean simulated scans of the 20 closed meshes, each at 10⁵ points: exact, on greedily
/// chosen points (up to 8000 of an even spread of 2·10⁴), the true genus on 12 (the cow 8
/// against 1, the boot 17 against 12, the sword 17 in two pieces); with λ 1e-6 or 1e-5 on an
/// even spread of 10⁴, the cow 7 and 4; 3e-5, 16 (18 on 1.5·10⁴ points); 1e-4, thin parts came
/// off (the cow in three pieces) and detail was lost (F-score at 0.5 % the boot 0.9969 →
/// 0.9847, the falcon statue 0.9941 → 0.9872).
const CLEAN_SMOOTHING: f64 = 3e-5;

/// The noise (a fraction of the box's longest side) above which [`smoothing_for_noise`] grows.
const REFERENCE_NOISE: f64 = 6e-3;

/// The smoothing up to [`REFERENCE_NOISE`]: 1e-4 (at 0.2 % noise, 1e-5 kept bumps over sparse
/// regions and 1e-3 rounded details off; at 0.5 %, 3e-5 lost F-score on 8 of 12 meshes and
/// 1e-5 on 9).
const REFERENCE_SMOOTHING: f64 = 1e-4;

/// Points per side of the lattice of outside probes.
const LATTICE: usize = 24;

/// Lattice probes count as away from the scan beyond this many normal offsets.
const AWAY: f64 = 2.0;

/// Offset probes count as inside, and are not used, where the winding number is at least this.
const INSIDE_WINDING: f64 = 0.5;

/// Lattice probes count as outside where the winding number is below this.
const OUTSIDE_WINDING: f64 = 0.25;

/// How far outside the surface a lattice probe says it lies, given its distance `reach` to the
/// nearest point of the scan, its winding number `w` (below [`OUTSIDE_WINDING`]) and the normal
/// offset `offset`: `reach` where the winding number says plainly outside (0), shrinking to one
/// offset (what the outward probes say) as it nears [`OUTSIDE_WINDING`]. The nearest point
/// bounds the distance to the surface only from above: near a hole the winding number leaks
/// through it, and the surface across the hole may pass much nearer than any point. Measured on
/// a clean cow scan (benchmark seed 23) with a hole right across a leg: two lattice probes in
/// the hole beside the leg, winding numbers 0.18, said to be 3.2 and 2.6 offsets outside though
/// the leg passed about one offset away, pinched the leg off (f −0.25 on its axis in the hole,
/// the mesh in three pieces); claimed so, the leg kept whole. Over clean scans of the 20 meshes
/// at two seeds: 10 F-scores at 0.5 % rose, 8 by more than 5e-4 (the hammer 0.9926 → 0.9976,
/// the goat head 0.9935 → 0.9961, the cat 0.9946 → 0.9975), 3 fell (the penguin 0.9969 →
/// 0.9958, the sword 0.7208 → 0.7053 and by 7e-4 at the other seed), no genus changed. Every
/// probe near a hole (winding number above 0.01) said one offset instead cost the boat (0.9921 → 0.9829) and the sword (F-score 0.16: it ballooned, its
/// blade's normals flipped and its winding numbers astray); probes 4 offsets from the scan
/// instead of 2 cost the fish (0.9890 → 0.9814).
fn lattice_claim(reach: f64, w: f64, offset: f64) -> f64 {
    (reach * (1.0 - w.max(0.0) / OUTSIDE_WINDING)).max(offset)
}

/// The `n` × `n` × `n` lattice inside the points' box grown as for [`grown_box_shell`]: the
/// box cut in `n` + 1 slices along each axis, the points where the inner cuts meet.
fn grown_box_lattice(points: &[[f64; 3]], longest: f64, n: usize) -> Vec<[f64; 3]> {
    let (lo, hi) = grown_box(points, longest);
    let step = |d: usize, i: usize| lo[d] + (hi[d] - lo[d]) * (i + 1) as f64 / (n + 1) as f64;
    (0..n * n * n)
        .map(|i| [step(0, i % n), step(1, i / n % n), step(2, i / (n * n))])
        .collect()
}

/// The points' box grown by a fifth of each side (at least a twenty-fifth of the longest).
fn grown_box(points: &[[f64; 3]], longest: f64) -> ([f64; 3], [f64; 3]) {
    let (lo, hi) = bounds(points);
    let pad: [f64; 3] = core::array::from_fn(|d| 0.2 * (hi[d] - lo[d]).max(0.2 * longest));
    (
        core::array::from_fn(|d| lo[d] - pad[d]),
        core::array::from_fn(|d| hi[d] + pad[d]),
    )
}

/// The 26 points of the 3 × 3 × 3 grid over the points' box grown by a fifth of each side (at
/// least a twenty-fifth of the longest), but its centre.
fn grown_box_shell(points: &[[f64; 3]], longest: f64) -> Vec<[f64; 3]> {
    let (lo, hi) = grown_box(points, longest);
    let mut out = Vec::with_capacity(26);
    for i in 0..27 {
        let steps = [i % 3, i / 3 % 3, i / 9];
        if steps == [1, 1, 1] {
            continue;
        }
        out.push(core::array::from_fn(|d| {
            lo[d] + 0.5 * steps[d] as f64 * (hi[d] - lo[d])
        }));
    }
    out
}

/// Passes of [`super::dipoles::flip_against_winding`] over a noisy scan, at most: the second
/// takes the few that the first's flips made clear (on a torus at 0.5 % noise, by direct sums,
/// 253 then 1).
const WINDING_PASSES: usize = 2;

/// Rounds of the noisy scan's sign checks (winding number point by point, votes in the first,
/// patches), at most; they stop when the patches turn nothing. Each round's flips redraw the
/// patches' edges, so the next finds more of a wrong region whole: on a simulated cow scan at
/// 0.5 % noise (with votes in every round), rounds turned 124, 80 and 49 more normals by patches, and its F-score at 0.5 % went
/// from 0.883 (one round) to 0.916 (two) and 0.924 (three; four: 0.925).
const SIGN_ROUNDS: usize = 3;

/// Passes of [`super::consensus::flip_against_fits`] over a noisy scan, at most; they stop
/// once fewer than one normal in a thousand changes. They run in the first sign round only:
/// what the coarse fits still dispute after it is finer than they see, and the patches turn
/// it back. On a simulated boot scan at 0.5 % noise, the votes of the second and third rounds
/// flipped 90 and 81 normals, 22 and 24 of them to the right side, and the patches after them
/// turned 89 of the first 90 back; over 17 corpus meshes at 0.5 % noise, votes in the first
/// round only left as many wrong normals or fewer on all but the fish (94 → 105) and took up
/// to 4.5 s off a scan (the boot; nothing where the rounds stop after the first anyway).
const CONSENSUS_PASSES: usize = 3;

/// The juries of [`super::consensus`] fit with this many times the smoothing of the scan's own
/// fit, and with the offset asked for (not raised to four times the noise as the scan's own
/// constraints are). A jury of 1500 points cannot follow detail finer than its spacing anyway;
/// exact, with the raised offset, its inside points crossed thin parts and its surface
/// wandered. On a simulated cat scan at 1 % noise, after the patches (7 % of the normals
/// wrong), the outward direction of an exact jury fit disagreed with the true one at 24 % of
/// the scan's points (18 % with the true normals given), and its votes left 41 % of them
/// wrong; smoothed so, at 0.3–2 %, and its votes left 2.7 % wrong. Alone (before the second
/// look, [`LOOKS`]), over the 20 meshes' scans at 1 % noise: genus right on 11 instead of 9 (the summed genus error 183 → 107), F-score
/// summed +0.77 (the cat 0.68 → 0.89, the cow 0.34 → 0.81; the hand 0.91 → 0.62); at 0.2 and 0.5 %
/// it changed the genus of four scans (three right where they were wrong; the stuffed toy at
/// 0.5 %, 4 → 14: its thin ear glues a wrong region, 39 % of its normals, to the right one,
/// and the exact jury's scattered votes had cut it loose by chance).
const JURY_SMOOTHING: f64 = 10.0;

/// Looks a noisy scan's normals get from the lines of sight (see [`reconstruct`]): the second
/// after the votes and the patches again. Measured with the smoothed juries: the hand at 1 %
/// noise, normals wrong 17.7 % → 0.81 %, F-score 0.62 → 0.91, genus 33 → 3; the stuffed toy
/// at 0.5 %, 7.5 % → 0.82 %, 0.84 → 0.97, genus 14 → 2. It costs about 1.1 s a noisy scan
/// (three passes of votes): the sword at 0.2 % took 1.61× Open3D's time, its votes and sight
/// undoing each other's 860 turns on its blade. Tried and rejected in one sitting: a second
/// look only where sight had turned 1 % of the spread, with one pass of votes, and the
/// smoothed points' normals from their wide neighbourhoods as found before smoothing (0.5 s
/// saved): 10 % faster over the 20 meshes, the sword at 0.2 % 10.1 s, but the knot at 1 %
/// came out with genus 54 (9.9 % of its normals wrong, 0 before) and the fish at 0.5 % with
/// 3.2 % wrong (0.53 %).
const LOOKS: usize = 2;

/// The share of the outside probes (offsets, box and lattice) that, still on the wrong side
/// after one round of outside constraints on a clean scan, says its normals are wrong rather
/// than that its surface bulged: the scan is then fitted again with lines of sight. Measured
/// on the clean scans (seed 11) of the corpus's 20 closed meshes, the second round finds at
/// most 3 probes of ~2.5·10⁴ astray (the boot; the sword, whose first round has 39 % astray,
/// 0.8 %); on a plate 2.7 point spacings thick whose two sides came out facing the same way,
/// 36 %. Caught there, that plate's scan took 29.5 s instead of 56.5 s (the first fit's four
/// more rounds added 9020 constraints before its mesh came out open and was retried).
const STILL_STRAYING: f64 = 0.25;

/// Rounds of outside constraints, at most. Each adds every probe where f strayed (up to
/// [`OUTSIDE_PER_ROUND`]): on the cow
/// scan at 0.5 % noise, adding every other one of 624 (at most 400 a round) left 84 of the
/// rest beside them for a second round and one for a third; all at once, one round.
const OUTSIDE_ROUNDS: usize = 8;

/// The most outside constraints added in one round (up to about 3.4·10⁴ probes could stray: a
/// spread of 2·10⁴, the 26 shell points and the 24³ lattice); the benchmark's scans stray at
/// 1795 at most (the bunny at 0.5 %).
const OUTSIDE_PER_ROUND: usize = 4000;

pub(super) fn unit(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if l > 0.0 && l.is_finite() {
        [v[0] / l, v[1] / l, v[2] / l]
    } else {
        [0.0; 3]
    }
}

pub(super) fn longest_side(points: &[[f64; 3]]) -> f64 {
    let (lo, hi) = bounds(points);
    (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max)
}

/// "plane", "line" or "point" when the points' spread across some direction is below 1e-9 of
/// their spread along the widest one.
fn flatness(points: &[[f64; 3]]) -> Option<&'static str> {
    if points.iter().all(|p| *p == points[0]) {
        return Some("point");
    }
    let n = points.len() as f64;
    let mut c = [0.0; 3];
    for p in points {
        (0..3).for_each(|d| c[d] += p[d] / n);
    }
    let mut m = nalgebra::Matrix3::<f64>::zeros();
    for p in points {
        let q = [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
        for r in 0..3 {
            for s in 0..3 {
                m[(r, s)] += q[r] * q[s];
            }
        }
    }
    let mut e: Vec<f64> = m
        .symmetric_eigenvalues()
        .iter()
        .map(|v| v.max(0.0))
        .collect();
    e.sort_by(f64::total_cmp);
    let widest = e[2];
    // Thinner than a millionth of the widest extent: the eigenvalues' own rounding is about
    // 1e-16 of the widest, so a line's second one is not exactly zero.
    let flat = |v: f64| v <= 1e-12 * widest;
    if !(widest > 0.0) {
        Some("point")
    } else if flat(e[1]) {
        Some("line")
    } else if flat(e[0]) {
        Some("plane")
    } else {
        None
    }
}

/// The noise of a scan in the points' units (see [`median_quadric_residual`]), measured on
/// neighbourhoods grown until they reach four times the noise they measure (up to 128
/// neighbours); with the median distance from a point to the farthest of its neighbours in
/// `near`'s neighbourhoods (before they grew: the scan's own spacing, for [`counts_as_noisy`]),
/// and the grown neighbourhoods and the normals estimated on them, when they grew.
/// A neighbourhood not much wider than the noise fits the noise itself and measures too little.
/// `tree` is built over `points`.
fn measure_noise(
    points: &[[f64; 3]],
    tree: &PointTree,
    normals: &[[f64; 3]],
    near: &Neighbours,
    estimated: bool,
) -> (f64, f64, Option<Grown>) {
    // A median needs no more than a few thousand points: the neighbourhoods grow on a sample,
    // and only the last size is found for every point.
    let sample: Vec<usize> = (0..points.len())
        .step_by((points.len() / NOISE_SAMPLE).max(1))
        .collect();
    let mut rows = Neighbours::of_some(tree, points, &sample, near.k());
    let mut noise = median_quadric_residual(
        points,
        sample
            .iter()
            .enumerate()
            .map(|(r, &i)| (i, normals[i], rows.of(r))),
    );
    let spacing = median_reach(&rows);
    let mut reach = spacing;
    let mut grown_to = None;
    for _ in 0..6 {
        let k = rows.k();
        let Some(median) = reach else {
            break;
        };
        let grown = k as f64 * (4.0 * noise / median.max(f64::MIN_POSITIVE)).powi(2);
        if !(grown > 1.25 * k as f64) || k >= MOST_NEIGHBOURS {
            break;
        }
        let grown_k = (grown.ceil() as usize).min(MOST_NEIGHBOURS);
        rows = Neighbours::of_some(tree, points, &sample, grown_k);
        let sampled_normals: Vec<[f64; 3]> = if estimated {
            (sample.iter().enumerate())
                .map(|(r, &i)| normal_of(points, i, rows.of(r)))
                .collect()
        } else {
            sample.iter().map(|&i| normals[i]).collect()
        };
        noise = median_quadric_residual(
            points,
            (sample.iter().enumerate()).map(|(r, &i)| (i, sampled_normals[r], rows.of(r))),
        );
        grown_to = Some(grown_k);
        reach = median_reach(&rows);
    }
    let wide = grown_to.map(|k| {
        let neighbours = Neighbours::with_tree(tree, points, k);
        let normals = if estimated {
            estimate_normals(points, &neighbours)
        } else {
            normals.to_vec()
        };
        (neighbours, normals)
    });
    (noise, spacing.unwrap_or(0.0), wide)
}

/// Whether a scan of `noise` counts as noisy: above [`SMOOTH_ABOVE`] of the box's `longest`
/// side, or above [`NOISE_OF_REACH`] of the median `reach` of its neighbourhoods (all in the
/// points' units): noise small beside the box but not beside the points' own spacing (a finely
/// scanned object's fraction of a millimetre, or views registered a little apart).
fn counts_as_noisy(noise: f64, reach: f64, longest: f64) -> bool {
    noise > SMOOTH_ABOVE * longest || noise > NOISE_OF_REACH * reach
}

/// The median distance from a point of `rows` to the farthest of its neighbours.
fn median_reach(rows: &Neighbours) -> Option<f64> {
    let reach: Vec<f64> = (0..rows.len())
        .filter_map(|r| rows.distances_of(r).last().copied())
        .collect();
    (!reach.is_empty()).then(|| super::dipoles::median(&reach))
}

/// The neighbours each point's plane and the orientation's graph are taken from: `k`, or,
/// where more than [`LINES_SHARE`] of the neighbourhoods lie along lines (points scanned in
/// slices or profiles farther apart than `k` neighbours reach), `k` doubled until they span
/// several lines (at most [`MOST_LINE_NEIGHBOURS`]).
fn neighbourhood_size(points: &[[f64; 3]], tree: &PointTree, k: usize) -> usize {
    let sample: Vec<usize> = (0..points.len())
        .step_by((points.len() / NOISE_SAMPLE).max(1))
        .collect();
    let mut k = k;
    while k < MOST_LINE_NEIGHBOURS {
        let rows = Neighbours::of_some(tree, points, &sample, k);
        if rbf_cloud::line_share(points, &sample, &rows) <= LINES_SHARE {
            break;
        }
        k *= 2;
    }
    k
}

/// The share of neighbourhoods along lines above which the cloud counts as scanned in lines.
const LINES_SHARE: f64 = 0.2;

/// The most neighbours a cloud scanned in lines is given.
const MOST_LINE_NEIGHBOURS: usize = 128;

/// A noisy point whose neighbourhood reaches beyond this many times the reach the
/// neighbourhoods were grown to (four times the noise, at the median) is smoothed onto a
/// quadric instead of a plane ([`project_onto_local_surfaces`]). On simulated scans whose one
/// half kept 8 % of its points, at 0.5 % noise: F-score 0.832 → 0.979 (bunny), 0.773 → 0.977
/// (spot), 0.740 → 0.886 (koala), 0.662 → 0.825 (cow). On every point, the quadric also cost
/// the six benchmark meshes' noisy scans (bunny at 0.5 %: 0.9948 → 0.9914, cow 0.9479 →
/// 0.9385); beyond twice the reach, their F-scores moved by at most 0.002.
const CURVED_REACH: f64 = 2.0;

/// Points the noise is measured at (a sample of the scan).
const NOISE_SAMPLE: usize = 4000;

/// Grown neighbourhoods and the normals estimated on them.
type Grown = (Neighbours, Vec<[f64; 3]>);

/// The widest neighbourhood noise is measured and smoothed on.
const MOST_NEIGHBOURS: usize = 128;

/// Runs `pass` (which flips normals and says how many) up to `passes` times, stopping after
/// the first whose count is `enough`; returns the flips of all of them.
fn repeat_passes(
    passes: usize,
    enough: impl Fn(usize) -> bool,
    mut pass: impl FnMut() -> Result<usize, ConvertError>,
) -> Result<usize, ConvertError> {
    let mut total = 0;
    for _ in 0..passes {
        let now = pass()?;
        total += now;
        if enough(now) {
            break;
        }
    }
    Ok(total)
}

/// Whether the normal of point `i` is more than 120° from the mean of its neighbours' unit
/// normals, and that mean is at least half a unit long (they agree with each other: not two
/// sheets of a thin part).
fn opposes_neighbours(normals: &[[f64; 3]], near: &Neighbours, i: usize) -> bool {
    let others = near.of(i);
    if others.is_empty() {
        return false;
    }
    let mut mean = [0.0; 3];
    for &j in others {
        let n = unit(normals[j as usize]);
        (0..3).for_each(|d| mean[d] += n[d] / others.len() as f64);
    }
    let length = dot(mean, mean).sqrt();
    length > 0.5 && dot(unit(normals[i]), mean) < -0.5 * length
}

/// Whether the normal of point `i` is within 60° of the mean of its neighbours' normals: a
/// normal that is not (noise near a crease, an isolated flip) says more about the noise than
/// about the surface, and its neighbours say the rest.
fn agrees_with_neighbours(normals: &[[f64; 3]], near: &Neighbours, i: usize) -> bool {
    let mut mean = [0.0; 3];
    for &j in near.of(i) {
        let n = unit(normals[j as usize]);
        (0..3).for_each(|d| mean[d] += n[d]);
    }
    let n = unit(normals[i]);
    dot(n, mean) > 0.5 * dot(mean, mean).sqrt()
}

/// Each point moved along its normal onto the surface of its neighbourhood: the plane through
/// its centroid, which averages the noise across it away, or where the neighbourhood reaches
/// farther than `curved_beyond` (a region scanned more sparsely than the rest, whose fixed
/// count of neighbours spreads wider), the quadric height function fitted to it by least
/// squares in the point's tangent frame, which follows the surface's curvature where a plane
/// through so wide a neighbourhood would cut inside it (by r²/2R at a radius r on a curvature
/// radius R).
fn project_onto_local_surfaces(
    points: &[[f64; 3]],
    normals: &[[f64; 3]],
    near: &Neighbours,
    curved_beyond: f64,
) -> Vec<[f64; 3]> {
    (0..points.len())
        .into_par_iter()
        .map(|i| {
            let (p, n) = (points[i], normals[i]);
            let others = near.of(i);
            let reach = near.distances_of(i).last().copied().unwrap_or(0.0);
            let height = if reach > curved_beyond {
                quadric_height(points, p, n, others)
            } else {
                None
            };
            let height = height.unwrap_or_else(|| {
                let count = (others.len() + 1) as f64;
                let mut c = p;
                for &j in others {
                    (0..3).for_each(|d| c[d] += points[j as usize][d]);
                }
                let c = c.map(|v| v / count);
                -((p[0] - c[0]) * n[0] + (p[1] - c[1]) * n[1] + (p[2] - c[2]) * n[2])
            });
            core::array::from_fn(|d| p[d] + height * n[d])
        })
        .collect()
}

/// The height above `p` along `n` of the quadric h(u, v) fitted by least squares to `p` and
/// the points `others` in the tangent frame of `n`; `None` for fewer than eight points, no
/// normal, or a singular fit.
fn quadric_height(points: &[[f64; 3]], p: [f64; 3], n: [f64; 3], others: &[u32]) -> Option<f64> {
    if others.len() < 8 || n.iter().all(|&c| c == 0.0) {
        return None;
    }
    let (t1, t2) = tangent_frame(n);
    let offsets = || {
        std::iter::once(p)
            .chain(others.iter().map(|&j| points[j as usize]))
            .map(|q| [q[0] - p[0], q[1] - p[1], q[2] - p[2]])
    };
    // u and v scaled to about 1, so that the normal equations stay well conditioned.
    let scale = offsets().map(|d| dot(d, d)).fold(0.0, f64::max).sqrt();
    if !(scale > 0.0) {
        return None;
    }
    let mut ata = nalgebra::Matrix6::<f64>::zeros();
    let mut atb = nalgebra::Vector6::<f64>::zeros();
    for d in offsets() {
        let (u, v) = (dot(d, t1) / scale, dot(d, t2) / scale);
        let row = nalgebra::Vector6::new(1.0, u, v, u * u, u * v, v * v);
        ata += row * row.transpose();
        atb += row * dot(d, n);
    }
    let height = ata.cholesky()?.solve(&atb)[0];
    height.is_finite().then_some(height)
}

/// Two unit vectors that make a right-handed orthonormal frame with the unit normal `n`.
pub(super) fn tangent_frame(n: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let helper = if n[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let t1 = normalized(cross(n, helper));
    (t1, cross(n, t1))
}

/// The noise of a scan: the median over the given neighbourhoods (a point's index, its normal,
/// its neighbours) of the RMS residual of a quadratic height function fitted to the
/// neighbourhood over the point's tangent plane (a plane would count the surface's curvature
/// as noise; a quadric takes it out).
fn median_quadric_residual<'a>(
    points: &[[f64; 3]],
    neighbourhoods: impl Iterator<Item = (usize, [f64; 3], &'a [u32])>,
) -> f64 {
    let mut rms: Vec<f64> = neighbourhoods
        .filter_map(|(i, n, others)| {
            let p = points[i];
            if others.len() < 8 || n.iter().all(|&c| c == 0.0) {
                return None;
            }
            let (t1, t2) = tangent_frame(n);
            let rows: Vec<[f64; 3]> = std::iter::once(p)
                .chain(others.iter().map(|&j| points[j as usize]))
                .map(|q| {
                    let d = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
                    [dot(d, t1), dot(d, t2), dot(d, n)]
                })
                .collect();
            let a = nalgebra::DMatrix::from_fn(rows.len(), 6, |r, c| {
                let [u, v, _] = rows[r];
                [1.0, u, v, u * u, u * v, v * v][c]
            });
            let h = nalgebra::DVector::from_fn(rows.len(), |r, _| rows[r][2]);
            let solution = a.clone().svd(true, true).solve(&h, 1e-12).ok()?;
            let residual = h - a * solution;
            let freedom = (rows.len() - 6).max(1) as f64;
            Some((residual.norm_squared() / freedom).sqrt())
        })
        .collect();
    if rms.is_empty() {
        return 0.0;
    }
    let mid = rms.len() / 2;
    rms.select_nth_unstable_by(mid, f64::total_cmp);
    rms[mid]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(super) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn normalized(v: [f64; 3]) -> [f64; 3] {
    let l = dot(v, v).sqrt();
    if l > 0.0 {
        [v[0] / l, v[1] / l, v[2] / l]
    } else {
        v
    }
}

/// The resolution to polygonize a reconstruction at: cubes about one median spacing of the
/// (distinct) points wide (thin parts keep their topology), 96 to 384 across the box's longest side.
///
/// ```
/// let grid: Vec<[f64; 3]> = (0..1000).map(|i| [(i % 10) as f64, ((i / 10) % 10) as f64, (i / 100) as f64 * 20.0]).collect();
/// assert_eq!(rbf_convert::mesh_resolution(&grid), 180);
/// // Points given twice are counted once.
/// assert_eq!(rbf_convert::mesh_resolution(&[grid.clone(), grid].concat()), 180);
/// ```
pub fn mesh_resolution(points: &[[f64; 3]]) -> usize {
    // A repeated point's nearest is itself, at 0.
    let distinct: Vec<[f64; 3]> = distinct_points(points)
        .into_iter()
        .map(|i| points[i])
        .collect();
    let near = Neighbours::new(&distinct, 1);
    let mut spacing: Vec<f64> = (0..near.len()).map(|i| near.distances_of(i)[0]).collect();
    if spacing.is_empty() {
        return 128;
    }
    let mid = spacing.len() / 2;
    spacing.select_nth_unstable_by(mid, f64::total_cmp);
    let longest = longest_side(points);
    let cells = longest / spacing[mid].max(f64::MIN_POSITIVE);
    if cells.is_finite() {
        (cells as usize).clamp(96, 384)
    } else {
        128
    }
}

#[cfg(test)]
mod tests {
    use super::{
        OUTSIDE_WINDING, counts_as_noisy, lattice_claim, opposes_neighbours, outward_probes,
    };

    /// The noise and the neighbourhoods' reach measured on simulated scans (as fractions of
    /// the box's longest side): clean ones count as clean, however sparse or scanned in lines;
    /// noise of 0.05 % of the diagonal counts as noisy though it is under 1e-3 of the box.
    #[test]
    fn noise_counts_beside_the_box_or_beside_the_spacing() {
        // Clean: a cow of 10⁵ points, of 10⁴, a falcon statue scanned in slices.
        for (noise, reach) in [(7.04e-5, 6.98e-3), (3.83e-4, 2.17e-2), (2.0e-4, 1.58e-2)] {
            assert!(!counts_as_noisy(noise, reach, 1.0), "{noise} {reach}");
            assert!(!counts_as_noisy(noise * 40.0, reach * 40.0, 40.0));
        }
        // Noisy: the bunny at 0.05 % of the diagonal, the boat at 0.1 % (measured just under
        // 1e-3 of the box), the bunny at 0.2 %.
        for (noise, reach) in [(7.8e-4, 1.035e-2), (9.85e-4, 5.19e-3), (2.7e-3, 1.1e-2)] {
            assert!(counts_as_noisy(noise, reach, 1.0), "{noise} {reach}");
            assert!(counts_as_noisy(noise * 40.0, reach * 40.0, 40.0));
        }
        // Noise above 1e-3 of the box counts, however wide the neighbourhoods.
        assert!(counts_as_noisy(1.2e-3, 0.5, 1.0));
    }

    /// A lattice probe plainly outside says its distance to the scan; one whose winding number
    /// leaks through a hole says less, down to one offset at the outside threshold, and never
    /// more than its distance or less than the offset.
    #[test]
    fn a_lattice_probe_near_a_hole_claims_less_than_its_distance_to_the_scan() {
        let offset = 0.1;
        assert_eq!(lattice_claim(3.0, 0.0, offset), 3.0);
        // Winding numbers a little below zero (discretization) count as zero.
        assert_eq!(lattice_claim(3.0, -0.02, offset), 3.0);
        assert!((lattice_claim(3.0, 0.5 * OUTSIDE_WINDING, offset) - 1.5).abs() < 1e-12);
        assert_eq!(lattice_claim(3.0, OUTSIDE_WINDING, offset), offset);
        // Far from a hole but near the scan: at least one offset.
        assert_eq!(lattice_claim(0.05, 0.0, offset), offset);
        let mut last = f64::INFINITY;
        for k in 0..=25 {
            let claim = lattice_claim(2.0, k as f64 * 0.01, offset);
            assert!(
                claim <= last && (offset..=2.0).contains(&claim),
                "{k}: {claim}"
            );
            last = claim;
        }
    }
    use rbf_cloud::{Neighbours, PointTree};

    /// A sphere's points with outward normals, one of them reversed: its probe lies inside, by
    /// the winding number of the rest, and is left out; every other one is kept, outside.
    #[test]
    fn a_reversed_normal_probes_inside_and_its_probe_is_not_used() {
        let n = 2000;
        let points = rbf_core::shapes::fibonacci_sphere(n);
        let mut normals = points.clone();
        normals[700] = normals[700].map(|c| -c);
        let tree = PointTree::new(&points);
        let near = Neighbours::with_tree(&tree, &points, 8);
        let probes = outward_probes(&tree, &points, &normals, &near, 0.1);
        assert_eq!(probes.len(), n - 1);
        for (q, out) in probes {
            let r = q.iter().map(|c| c * c).sum::<f64>().sqrt();
            assert!(r > 1.0 && (r - 1.0 - out).abs() < 1e-9, "{r} {out}");
        }
    }

    /// A sheet of points facing +z, one of them reversed; and two sheets of a thin part, two
    /// point spacings apart, facing away from each other.
    #[test]
    fn a_lone_reversed_normal_opposes_its_neighbours_but_a_thin_part_does_not() {
        let mut points = Vec::new();
        let mut normals = Vec::new();
        for i in 0..10 {
            for j in 0..10 {
                points.push([i as f64, j as f64, 0.0]);
                normals.push([0.0, 0.0, if (i, j) == (4, 5) { -1.0 } else { 1.0 }]);
            }
        }
        let near = Neighbours::new(&points, 8);
        let lone: Vec<usize> = (0..points.len())
            .filter(|&i| opposes_neighbours(&normals, &near, i))
            .collect();
        assert_eq!(lone, vec![45]);

        // Each point's eight nearest: the other sheet's point across (1.8 away), four on its own
        // sheet (2) and three of the other's diagonal ones (2.7): their mean is short.
        let mut points = Vec::new();
        let mut normals = Vec::new();
        for i in 0..10 {
            for j in 0..10 {
                for side in [1.0, -1.0] {
                    points.push([i as f64 * 2.0, j as f64 * 2.0, side * 0.9]);
                    normals.push([0.0, 0.0, side]);
                }
            }
        }
        let near = Neighbours::new(&points, 8);
        assert!((0..points.len()).all(|i| !opposes_neighbours(&normals, &near, i)));
    }
}
