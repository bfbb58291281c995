//! Example shapes: the constraint sets of Turk & O'Brien's first figures and the evenly spread
//! point sets that the demo, the gallery, the benchmarks and the tests fit. One definition
//! each, so that a figure quoted in the README is the figure a test checks.

use alloc::vec::Vec;

use crate::Constraint;
use crate::math::{fract, sin_cos, sqrt};

/// The golden angle π(3 − √5), the turn between successive points of a Fibonacci lattice.
const GOLDEN_ANGLE: f64 = 2.399_963_229_728_653;

/// `n` points spread evenly over the unit sphere (a Fibonacci lattice: equal steps in z, the
/// golden angle between successive azimuths), from the north pole down.
///
/// ```
/// let p = rbf_core::shapes::fibonacci_sphere(500);
/// assert_eq!(p.len(), 500);
/// assert!(p.iter().all(|q| (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] - 1.0).abs() < 1e-12));
/// ```
pub fn fibonacci_sphere(n: usize) -> Vec<[f64; 3]> {
    (0..n)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
            let r = sqrt(1.0 - z * z);
            let (s, c) = sin_cos(i as f64 * GOLDEN_ANGLE);
            [r * c, r * s, z]
        })
        .collect()
}

/// The unit sphere from `n` normal constraints at [`fibonacci_sphere`] points.
///
/// ```
/// let cs = rbf_core::shapes::sphere(100);
/// assert_eq!(cs[7].normal, cs[7].position); // outward unit normals
/// ```
pub fn sphere(n: usize) -> Vec<Constraint<3>> {
    fibonacci_sphere(n)
        .into_iter()
        .map(|p| Constraint::normal(p, p))
        .collect()
}

/// `n` points spread evenly over a torus about the z axis (a circle of radius 1 swept by a
/// tube of radius `tube`), each with its outward unit normal: `(position, normal)`. The angle
/// around the axis advances evenly, the angle around the tube by the golden ratio.
///
/// ```
/// for (p, n) in rbf_core::shapes::torus_points(300, 0.35) {
///     let ring = (p[0] * p[0] + p[1] * p[1]).sqrt() - 1.0;
///     assert!((ring * ring + p[2] * p[2] - 0.35 * 0.35).abs() < 1e-12);
///     assert!((n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1.0).abs() < 1e-12);
/// }
/// ```
pub fn torus_points(n: usize, tube: f64) -> Vec<([f64; 3], [f64; 3])> {
    let golden_ratio = (sqrt(5.0) - 1.0) / 2.0;
    (0..n)
        .map(|i| {
            let u = core::f64::consts::TAU * (i as f64 + 0.5) / n as f64;
            let v = core::f64::consts::TAU * fract(i as f64 * golden_ratio);
            let (su, cu) = sin_cos(u);
            let (sv, cv) = sin_cos(v);
            let ring = 1.0 + tube * cv;
            ([ring * cu, ring * su, tube * sv], [cv * cu, cv * su, sv])
        })
        .collect()
}

/// A torus about the z axis from `n` normal constraints at [`torus_points`] (2n rows): genus 1,
/// the hole outside.
///
/// ```
/// let cs = rbf_core::shapes::torus(1500, 0.35);
/// assert_eq!(cs.iter().map(|c| c.rows()).sum::<usize>(), 3000);
/// ```
pub fn torus(n: usize, tube: f64) -> Vec<Constraint<3>> {
    torus_points(n, tube)
        .into_iter()
        .map(|(p, normal)| Constraint::normal(p, normal))
        .collect()
}

/// The corners of a regular tetrahedron inscribed in the unit sphere.
///
/// ```
/// let t = rbf_core::shapes::tetrahedron();
/// let d: f64 = (0..3).map(|k| (t[0][k] - t[1][k]).powi(2)).sum::<f64>().sqrt();
/// assert!((d - (8.0_f64 / 3.0).sqrt()).abs() < 1e-12); // every edge
/// ```
pub fn tetrahedron() -> [[f64; 3]; 4] {
    let s = 1.0 / sqrt(3.0);
    [[s, s, s], [s, -s, -s], [-s, s, -s], [-s, -s, s]]
}

/// Turk & O'Brien (2002), Figure 2, left: boundary constraints at the [`tetrahedron`]'s
/// corners around an interior constraint (value 1) at its centre. The surface is a near-sphere.
///
/// ```
/// let f = rbf_core::fit(&rbf_core::shapes::tetrahedron_blob(), &Default::default()).unwrap();
/// assert!(f.interpolant.value(&[0.0; 3]) > 0.0);
/// ```
pub fn tetrahedron_blob() -> Vec<Constraint<3>> {
    let mut cs: Vec<Constraint<3>> = tetrahedron().map(Constraint::boundary).to_vec();
    cs.push(Constraint::interior([0.0; 3], 1.0));
    cs
}

/// The start of interactive sculpting (Turk & O'Brien 2002, §5): boundary constraints at the
/// [`tetrahedron`]'s corners (items 0–3) and exterior constraints of value −1 at the corners of
/// a cube of side 6 (items 4–11, corner k at ±3 by the bits of k: x, y, z).
///
/// ```
/// let cs = rbf_core::shapes::sculpt_start();
/// assert_eq!(cs.len(), 12);
/// assert_eq!(cs[11].position, [3.0, 3.0, 3.0]);
/// ```
pub fn sculpt_start() -> Vec<Constraint<3>> {
    let mut cs: Vec<Constraint<3>> = tetrahedron().map(Constraint::boundary).to_vec();
    for k in 0..8 {
        let corner = [k & 1, (k >> 1) & 1, k >> 2].map(|b| if b == 1 { 3.0 } else { -3.0 });
        cs.push(Constraint::exterior(corner, -1.0));
    }
    cs
}

/// Turk & O'Brien (2002), Figure 2, right: a branching shape. Boundary constraints at the six
/// corners of an upright triangular prism (unit size, along +y) around an interior constraint
/// at its centre, then `depth` times three smaller prisms, tilted outward, on top of each.
///
/// ```
/// let cs = rbf_core::shapes::branching(1);
/// assert_eq!(cs.len(), 7 + 3 * 7);
/// ```
pub fn branching(depth: usize) -> Vec<Constraint<3>> {
    let mut out = Vec::new();
    prism([0.0; 3], 1.0, [0.0, 0.0], depth, &mut out);
    out
}

/// One prism of [`branching`] at `centre` (its base's centre), `size` across, leaning by
/// `tilt` (x and z per unit of height), and its children.
fn prism(centre: [f64; 3], size: f64, tilt: [f64; 2], depth: usize, out: &mut Vec<Constraint<3>>) {
    let height = 1.6 * size;
    for k in 0..3 {
        let (s, c) = sin_cos(core::f64::consts::TAU * k as f64 / 3.0);
        for (level, dy) in [(0.0, 0.0), (1.0, height)] {
            out.push(Constraint::boundary([
                centre[0] + size * c + level * tilt[0] * height,
                centre[1] + dy,
                centre[2] + size * s + level * tilt[1] * height,
            ]));
        }
    }
    out.push(Constraint::interior(
        [
            centre[0] + 0.5 * tilt[0] * height,
            centre[1] + 0.5 * height,
            centre[2] + 0.5 * tilt[1] * height,
        ],
        1.0,
    ));
    if depth == 0 {
        return;
    }
    let top = [
        centre[0] + tilt[0] * height,
        centre[1] + 0.9 * height,
        centre[2] + tilt[1] * height,
    ];
    for k in 0..3 {
        let (s, c) = sin_cos(core::f64::consts::TAU * (k as f64 + 0.5) / 3.0);
        let child = [top[0] + 0.75 * size * c, top[1], top[2] + 0.75 * size * s];
        prism(child, 0.5 * size, [0.6 * c, 0.6 * s], depth - 1, out);
    }
}

/// A teapot in silhouette, the 2D goal of Yngve & Turk (2002), Figure 3: body, lid knob, spout
/// and a ring handle (whose hole makes a second curve). Fits the box [−1.7, 1.9] × [−1.2, 1.2].
///
/// ```
/// use rbf_core::shapes::teapot_silhouette;
/// assert!(teapot_silhouette([0.0, 0.0])); // the body
/// assert!(!teapot_silhouette([-1.05, 0.05])); // the handle's hole
/// assert!(teapot_silhouette([-1.4, 0.05])); // the handle
/// ```
pub fn teapot_silhouette(p: [f64; 2]) -> bool {
    let [x, y] = p;
    let length = |a: f64, b: f64| sqrt(a * a + b * b);
    let body = x * x + (y / 0.7) * (y / 0.7) < 1.0;
    let knob = length(x, y - 0.78) < 0.15;
    // The spout: a band narrowing from 0.28 to 0.16 along (0.8, −0.1) → (1.55, 0.55).
    let (ax, ay, bx, by) = (0.8, -0.1, 1.55, 0.55);
    let along = ((x - ax) * (bx - ax) + (y - ay) * (by - ay)) / ((bx - ax) * (bx - ax) + (by - ay) * (by - ay));
    let t = along.clamp(0.0, 1.0);
    let spout = length(x - ax - t * (bx - ax), y - ay - t * (by - ay)) < 0.08 + 0.06 * (1.0 - t);
    let r = length(x + 1.05, y - 0.05);
    let handle = (0.28..0.42).contains(&r) && x < -0.85;
    body || knob || spout || handle
}
