//! Winding numbers of oriented points: each point taken as a small patch of surface, a dipole
//! whose moment is its area times its outward normal, subtends m·(p − q) / |p − q|³ at q; over
//! a closed scan their sum over 4π is about 1 inside and 0 outside (Jacobson et al. 2013's
//! generalized winding number for point clouds; Barill et al. 2018). Summed through the
//! cluster hierarchy, as a mesh's are.

use rayon::prelude::*;
use rbf_core::vec3::{dot, norm, sub};

use super::clusters::{Clusters, Elements, Reach};

/// A cluster counts as far from three of its radii, and every far one gets the second-order
/// term: the winding number is then within 0.03 of direct sums at the probes a scan's normals
/// are judged by (measured on simulated boot and cow scans at 0.5 % noise, 1.4·10⁴–1.7·10⁴
/// probes, 9·10³ points; at 1.5 radii, as for a mesh's triangles, within 0.13), at a tenth of
/// their time.
const REACH: Reach = Reach {
    far: 3.0,
    second_order: f64::INFINITY,
};

/// Oriented points (dipoles) prepared for fast winding-number queries.
pub struct DipoleTree {
    points: Vec<[f64; 3]>,
    moments: Vec<[f64; 3]>,
    clusters: Clusters,
}

impl DipoleTree {
    /// The hierarchy over dipoles at `points` with `moments` (area times outward normal);
    /// a point without a moment (beyond the last) has none, and moments beyond the last point
    /// are ignored.
    pub fn new(points: &[[f64; 3]], moments: &[[f64; 3]]) -> Self {
        let points = points.to_vec();
        let moments: Vec<[f64; 3]> = (0..points.len())
            .map(|i| moments.get(i).copied().unwrap_or([0.0; 3]))
            .collect();
        let area = |i: usize| moments[i];
        let centroid = |i: usize| points[i];
        let reach = |i: usize, from: [f64; 3]| norm(sub(points[i], from));
        let elements = Elements {
            area: &area,
            centroid: &centroid,
            reach: &reach,
        };
        let clusters = Clusters::new(points.len(), &elements);
        Self {
            points,
            moments,
            clusters,
        }
    }

    /// The winding number at q: exact sums for near dipoles, expansions for far clusters (the
    /// expansions err by a few hundredths or less; compare with a threshold, not exactly).
    ///
    /// ```
    /// use rbf_mesh::DipoleTree;
    /// // 4000 points over the unit sphere, each with its share of the area along its normal.
    /// let n = 4000;
    /// let points: Vec<[f64; 3]> = (0..n)
    ///     .map(|i| {
    ///         let z = 1.0 - (2 * i + 1) as f64 / n as f64;
    ///         let (s, t) = ((1.0 - z * z).sqrt(), 2.399963 * i as f64);
    ///         [s * t.cos(), s * t.sin(), z]
    ///     })
    ///     .collect();
    /// let share = 4.0 * std::f64::consts::PI / n as f64;
    /// let moments: Vec<[f64; 3]> = points.iter().map(|p| p.map(|c| share * c)).collect();
    /// let tree = DipoleTree::new(&points, &moments);
    /// assert!((tree.winding_number([0.1, 0.2, 0.0]) - 1.0).abs() < 0.05);
    /// assert!(tree.winding_number([0.0, 0.0, 2.0]).abs() < 0.05);
    /// ```
    pub fn winding_number(&self, q: [f64; 3]) -> f64 {
        let sum = self.clusters.solid_angle(q, REACH, |i| {
            let r = sub(self.points[i], q);
            let r2 = dot(r, r);
            if r2 > 0.0 {
                dot(self.moments[i], r) / (r2 * r2.sqrt())
            } else {
                0.0
            }
        });
        sum / (4.0 * std::f64::consts::PI)
    }
}

/// The winding number of the dipoles at `points` with `moments` at each probe (hierarchical,
/// in parallel).
///
/// ```
/// use rbf_mesh::dipole_winding_numbers;
/// // One dipole of unit moment along z (a small patch facing +z), seen from 1 below (behind
/// // it, inside) and from 1 above.
/// let probes = [[0.0, 0.0, -1.0], [0.0, 0.0, 1.0]];
/// let w = dipole_winding_numbers(&[[0.0; 3]], &[[0.0, 0.0, 1.0]], &probes);
/// let quarter_pi = 1.0 / (4.0 * std::f64::consts::PI);
/// assert!((w[0] - quarter_pi).abs() < 1e-12 && (w[1] + quarter_pi).abs() < 1e-12);
/// ```
pub fn dipole_winding_numbers(
    points: &[[f64; 3]],
    moments: &[[f64; 3]],
    probes: &[[f64; 3]],
) -> Vec<f64> {
    let tree = DipoleTree::new(points, moments);
    probes.par_iter().map(|&q| tree.winding_number(q)).collect()
}
