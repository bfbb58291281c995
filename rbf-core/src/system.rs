//! The linear system of equation (8) in Turk & O'Brien (2002): expansion of constraints into rows,
//! validation, conditioning (centring and scaling) and assembly.

use alloc::vec::Vec;

use crate::kernel::{Radial, with_radial};
use crate::{
    Constraint, ConstraintKind, FitError, FitSettings, Interpolant, Kernel, NormalOffset, RowSource,
};

/// The rows of a fit, checked and ready to assemble.
///
/// Rows live in normalized coordinates x′ = (x − origin) / scale, which puts every point in
/// [−1, 1]ᴰ: the kernel block then has entries of order one whatever the model's units, and
/// [`System::to_interpolant`] maps the solution back exactly.
///
/// ```
/// use rbf_core::{Constraint, FitSettings, System};
/// let cs = [
///     Constraint::boundary([0.0, 0.0]),
///     Constraint::boundary([4.0, 0.0]),
///     Constraint::normal([0.0, 4.0], [0.0, 1.0]),
/// ];
/// let sys = System::new(&cs, &FitSettings::default()).unwrap();
/// assert_eq!(sys.rows(), 4); // the normal constraint takes two
/// assert_eq!(sys.size(), 7); // plus 1 + 2 polynomial coefficients
/// assert_eq!(sys.scale(), 2.0);
/// ```
#[derive(Clone, Debug)]
pub struct System<const D: usize> {
    kernel: Kernel,
    /// Points in the caller's coordinates.
    points: Vec<[f64; D]>,
    /// Points in normalized coordinates.
    normalized: Vec<[f64; D]>,
    values: Vec<f64>,
    /// σ(λ + λᵢ) in the caller's units, σ the kernel's [`Kernel::definiteness`].
    smoothing: Vec<f64>,
    sources: Vec<RowSource>,
    origin: [f64; D],
    scale: f64,
}

impl<const D: usize> System<D> {
    /// Expands and checks constraints: finite input, values consistent with kinds, non-zero
    /// normals, enough rows, no coincident points, points not all on a plane (line in 2D), at
    /// least one non-zero value.
    pub fn new(constraints: &[Constraint<D>], settings: &FitSettings) -> Result<Self, FitError> {
        check_each(constraints, settings)?;
        let rows: usize = constraints.iter().map(Constraint::rows).sum();
        if rows < D + 1 {
            return Err(FitError::TooFewConstraints {
                rows,
                needed: D + 1,
                dim: D,
            });
        }
        let (lo, hi) = bounds(constraints.iter().map(|c| &c.position));
        let longest = (0..D).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
        let default_offset = match settings.normal_offset {
            NormalOffset::Relative(f) => f * longest,
            NormalOffset::Absolute(a) => a,
        };

        let mut points = Vec::with_capacity(rows);
        let mut values = Vec::with_capacity(rows);
        let mut smoothing = Vec::with_capacity(rows);
        let mut sources = Vec::with_capacity(rows);
        // Smoothing makes the kernel block more definite: +λ for r³ and r² log r, −λ for r
        // (scipy's `smoothing` with its kernel −r).
        let sign = settings.kernel_for(D).definiteness();
        for (i, c) in constraints.iter().enumerate() {
            let lambda = sign * (settings.lambda + c.smoothing);
            let here = RowSource {
                constraint: i,
                offset_point: false,
            };
            if c.kind == ConstraintKind::Normal {
                points.push(c.position);
                values.push(0.0);
                smoothing.push(lambda);
                sources.push(here);
                let offset = c.offset.unwrap_or(default_offset);
                let len = norm(&c.normal);
                let mut inside = c.position;
                for d in 0..D {
                    inside[d] -= offset * c.normal[d] / len;
                }
                if !inside.iter().all(|v| v.is_finite()) {
                    return Err(FitError::NonFinite {
                        constraint: i,
                        field: "offset point",
                    });
                }
                points.push(inside);
                values.push(c.value);
                smoothing.push(lambda);
                sources.push(RowSource {
                    offset_point: true,
                    ..here
                });
            } else {
                points.push(c.position);
                values.push(c.value);
                smoothing.push(lambda);
                sources.push(here);
            }
        }

        let (lo, hi) = bounds(points.iter());
        let mut origin = [0.0; D];
        let mut half = 0.0_f64;
        for d in 0..D {
            origin[d] = 0.5 * (lo[d] + hi[d]);
            half = half.max(0.5 * (hi[d] - lo[d]));
        }
        let scale = if half > 0.0 && half.is_finite() {
            half
        } else {
            1.0
        };
        let normalized: Vec<[f64; D]> = points
            .iter()
            .map(|p| core::array::from_fn(|d| (p[d] - origin[d]) / scale))
            .collect();

        let sys = Self {
            kernel: settings.kernel_for(D),
            points,
            normalized,
            values,
            smoothing,
            sources,
            origin,
            scale,
        };
        // In normalized units the bounding box's longest side is 2.
        sys.check_coincident(2.0 * settings.min_separation)?;
        sys.check_affine_rank()?;
        if sys.values.iter().all(|&v| v == 0.0) {
            return Err(FitError::NoNonZeroValue { rows });
        }
        Ok(sys)
    }

    /// The kernel φ: the settings' own, or else the default for D (r² log r in 2D, r³ in 3D).
    pub fn kernel(&self) -> Kernel {
        self.kernel
    }
    /// Number of rows K (constraint points; a normal constraint gives two).
    pub fn rows(&self) -> usize {
        self.points.len()
    }
    /// Size K + D + 1 of the whole system, polynomial part included.
    pub fn size(&self) -> usize {
        self.points.len() + D + 1
    }
    /// Row points in the caller's coordinates.
    pub fn points(&self) -> &[[f64; D]] {
        &self.points
    }
    /// Row points in normalized coordinates.
    #[doc(hidden)]
    pub fn normalized_points(&self) -> &[[f64; D]] {
        &self.normalized
    }
    /// Right-hand side hᵢ.
    pub fn values(&self) -> &[f64] {
        &self.values
    }
    /// Which constraint each row came from.
    pub fn sources(&self) -> &[RowSource] {
        &self.sources
    }
    /// The scale of the normalization: half the longest side of the bounding box.
    #[doc(hidden)]
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// λᵢ of row `i` in normalized units (the kernel block scales as scale^β).
    #[doc(hidden)]
    pub fn normalized_smoothing(&self, i: usize) -> f64 {
        self.smoothing[i] / crate::math::powi(self.scale, self.kernel.scale_exponent())
    }

    /// Writes rows `rows` of column `j` of the normalized kernel block Φ + diag(λ) into `out`.
    #[doc(hidden)]
    pub fn kernel_column(&self, j: usize, rows: core::ops::Range<usize>, out: &mut [f64]) {
        let cj = self.normalized[j];
        with_radial!(self.kernel, K => {
            for (o, ci) in out.iter_mut().zip(&self.normalized[rows.clone()]) {
                let mut r2 = 0.0;
                for d in 0..D {
                    let t = ci[d] - cj[d];
                    r2 += t * t;
                }
                *o = K::phi_r2(r2);
            }
        });
        if rows.contains(&j) {
            out[j - rows.start] += self.normalized_smoothing(j);
        }
    }

    /// Writes column `j` (of `size()`) of the whole normalized system
    /// [Φ + Λ, P; Pᵀ, 0] into `out` (length `size()`).
    #[doc(hidden)]
    pub fn system_column(&self, j: usize, out: &mut [f64]) {
        let k = self.rows();
        if j < k {
            self.kernel_column(j, 0..k, &mut out[..k]);
            out[k] = 1.0;
            out[k + 1..].copy_from_slice(&self.normalized[j]);
        } else {
            for (v, p) in out[..k].iter_mut().zip(&self.normalized) {
                *v = if j == k { 1.0 } else { p[j - k - 1] };
            }
            out[k..].fill(0.0);
        }
    }

    /// Row `i` of the normalized polynomial block: (1, x′ᵢ).
    #[doc(hidden)]
    pub fn polynomial_row(&self, i: usize) -> [f64; D] {
        self.normalized[i]
    }

    /// The interpolant of normalized weights `w` and polynomial `p` = (a, b₁…b_D), in
    /// normalized coordinates.
    #[doc(hidden)]
    pub fn normalized_interpolant(&self, w: &[f64], p: &[f64]) -> Interpolant<f64, D> {
        let linear = core::array::from_fn(|d| p.get(d + 1).copied().unwrap_or(0.0));
        Interpolant::from_parts(
            self.kernel,
            self.normalized.clone(),
            w.to_vec(),
            p.first().copied().unwrap_or(0.0),
            linear,
        )
    }

    /// Maps normalized weights `w` and polynomial `p` = (a, b₁…b_D) back to the caller's
    /// coordinates: the returned interpolant has the row points as centres.
    pub(crate) fn to_interpolant(&self, w: &[f64], p: &[f64]) -> Interpolant<f64, D> {
        let s = self.scale;
        let ws = crate::math::powi(s, self.kernel.scale_exponent());
        let weights: Vec<f64> = w.iter().map(|&x| x / ws).collect();
        let b: [f64; D] = core::array::from_fn(|d| p.get(d + 1).copied().unwrap_or(0.0));
        let mut constant = p.first().copied().unwrap_or(0.0);
        let mut linear = [0.0; D];
        for d in 0..D {
            linear[d] = b[d] / s;
            constant -= b[d] * self.origin[d] / s;
        }
        if self.kernel == Kernel::ThinPlate {
            // φ(r/s) = φ(r)/s² − ln s · |x′ − c′|²; the second sum is the constant Σ w′ⱼ|c′ⱼ|²
            // because the weights are orthogonal to the linear polynomials.
            let q: f64 = w
                .iter()
                .zip(&self.normalized)
                .map(|(wj, c)| wj * c.iter().map(|v| v * v).sum::<f64>())
                .sum();
            constant -= crate::math::ln(s) * q;
        }
        Interpolant::from_parts(self.kernel, self.points.clone(), weights, constant, linear)
    }

    /// The normalized unknowns (weights, then the polynomial a, b₁…b_D) that give back `f`
    /// as far as these rows allow: the inverse of the map to an interpolant. A row whose point
    /// is one of `f`'s centres (the very same coordinates) takes its weight, every other row 0;
    /// the polynomial is `f`'s. A starting point for an iterative solve of rows added to those
    /// `f` was fitted to, which then has only the new rows' misses to reduce.
    ///
    /// ```
    /// use rbf_core::{Constraint, FitSettings, System, shapes};
    /// let settings = FitSettings::default();
    /// let cs = shapes::sphere(40);
    /// let fit = rbf_core::fit(&cs, &settings).unwrap();
    /// // The same rows and one more, outside the sphere but within its box.
    /// let mut more = cs.clone();
    /// more.push(Constraint::exterior([0.9, 0.9, 0.0], -0.5));
    /// let sys = System::new(&more, &settings).unwrap();
    /// let x = sys.normalized_unknowns(&fit.interpolant);
    /// assert_eq!(x.len(), sys.size());
    /// let k = sys.rows();
    /// assert!(x[..k - 1].iter().all(|&w| w != 0.0)); // the fitted rows keep their weights
    /// assert_eq!(x[k - 1], 0.0); // the new row starts at 0
    /// ```
    pub fn normalized_unknowns(&self, f: &Interpolant<f64, D>) -> Vec<f64> {
        let bits = |p: &[f64; D]| p.map(f64::to_bits);
        let weight_of: alloc::collections::BTreeMap<[u64; D], f64> = (f.centres().iter())
            .zip(f.weights())
            .map(|(c, &w)| (bits(c), w))
            .collect();
        let s = self.scale;
        let ws = crate::math::powi(s, self.kernel.scale_exponent());
        let mut x: Vec<f64> = (self.points.iter())
            .map(|p| weight_of.get(&bits(p)).map_or(0.0, |&w| w * ws))
            .collect();
        let linear = f.linear();
        let mut constant = f.constant();
        for d in 0..D {
            constant += linear[d] * self.origin[d];
        }
        if self.kernel == Kernel::ThinPlate {
            let q: f64 = (x.iter().zip(&self.normalized))
                .map(|(wj, c)| wj * c.iter().map(|v| v * v).sum::<f64>())
                .sum();
            constant += crate::math::ln(s) * q;
        }
        x.push(constant);
        x.extend(linear.iter().map(|b| b * s));
        x
    }

    /// The relative residual of an interpolant with these centres:
    /// max |f(cᵢ) + λᵢ wᵢ − hᵢ| / max |hᵢ|, with f, c and λ in the caller's units.
    pub fn relative_residual(&self, f: &Interpolant<f64, D>) -> f64 {
        let mut fx = alloc::vec![0.0; self.points.len()];
        if f.values(&self.points, &mut fx).is_err() {
            return f64::NAN;
        }
        self.residual_from_values(f, &fx)
    }

    /// [`System::relative_residual`] given `fx[i]` = f(cᵢ), computed by the caller (perhaps in
    /// parallel).
    pub(crate) fn residual_from_values(&self, f: &Interpolant<f64, D>, fx: &[f64]) -> f64 {
        let mut worst = 0.0_f64;
        for (i, (&v, &w)) in fx.iter().zip(f.weights()).enumerate() {
            let r = v + self.smoothing[i] * w - self.values[i];
            if r.is_nan() {
                return f64::NAN;
            }
            worst = worst.max(r.abs());
        }
        worst / self.max_abs_value()
    }

    /// max |f(cᵢ) + λᵢwᵢ − hᵢ| / max|hᵢ| over the given rows only, `fx[k]` = f(c at `rows[k]`):
    /// the residual an iterative solver certifies by direct sums at sampled rows.
    #[doc(hidden)]
    pub fn residual_at_rows(&self, f: &Interpolant<f64, D>, rows: &[usize], fx: &[f64]) -> f64 {
        let mut worst = 0.0_f64;
        for (&i, &v) in rows.iter().zip(fx) {
            let r = v + self.smoothing[i] * f.weights()[i] - self.values[i];
            if r.is_nan() {
                return f64::NAN;
            }
            worst = worst.max(r.abs());
        }
        worst / self.max_abs_value()
    }

    /// max |hᵢ| (positive, since some value is non-zero).
    pub(crate) fn max_abs_value(&self) -> f64 {
        self.values.iter().fold(0.0, |m, v| m.max(v.abs()))
    }

    fn check_coincident(&self, tolerance: f64) -> Result<(), FitError> {
        let cell = tolerance.max(1e-12);
        let key = |p: &[f64; D]| -> [i64; D] { core::array::from_fn(|d| (p[d] / cell) as i64) };
        let mut order: Vec<([i64; D], usize)> = self
            .normalized
            .iter()
            .enumerate()
            .map(|(i, p)| (key(p), i))
            .collect();
        order.sort_unstable();
        let mut worst: Option<(usize, usize, f64)> = None;
        for (i, p) in self.normalized.iter().enumerate() {
            let k = key(p);
            for n in 0..3_usize.pow(D as u32) {
                let mut probe = k;
                let mut m = n;
                for v in probe.iter_mut() {
                    *v += (m % 3) as i64 - 1;
                    m /= 3;
                }
                let start = order.partition_point(|(q, _)| *q < probe);
                for &(q, j) in &order[start..] {
                    if q != probe {
                        break;
                    }
                    if j <= i {
                        continue;
                    }
                    let dist = norm(&core::array::from_fn::<f64, D, _>(|d| {
                        p[d] - self.normalized[j][d]
                    }));
                    if dist <= tolerance && worst.is_none_or(|(a, b, _)| (i, j) < (a, b)) {
                        worst = Some((i, j, dist));
                    }
                }
            }
        }
        match worst {
            Some((i, j, dist)) => Err(FitError::Coincident {
                first: self.sources[i],
                second: self.sources[j],
                distance: dist * self.scale,
                minimum: tolerance * self.scale,
            }),
            None => Ok(()),
        }
    }

    /// Rank of [1 x′] from the eigenvalues of the points' covariance.
    fn check_affine_rank(&self) -> Result<(), FitError> {
        let n = self.normalized.len() as f64;
        let mean: [f64; D] =
            core::array::from_fn(|d| self.normalized.iter().map(|p| p[d]).sum::<f64>() / n);
        let mut cov = nalgebra::DMatrix::<f64>::zeros(D, D);
        for p in &self.normalized {
            for a in 0..D {
                for b in 0..D {
                    cov[(a, b)] += (p[a] - mean[a]) * (p[b] - mean[b]) / n;
                }
            }
        }
        let eig = cov.symmetric_eigenvalues();
        let largest = eig.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        // Standard deviations below 1e-10 of the largest count as flat.
        let rank = 1 + eig.iter().filter(|v| **v > 1e-20 * largest).count();
        if rank < D + 1 {
            return Err(FitError::AffinelyDependent {
                rows: self.normalized.len(),
                rank,
            });
        }
        Ok(())
    }
}

fn check_each<const D: usize>(
    constraints: &[Constraint<D>],
    settings: &FitSettings,
) -> Result<(), FitError> {
    if !settings.lambda.is_finite() || settings.lambda < 0.0 {
        return Err(FitError::InvalidSetting {
            name: "lambda",
            value: settings.lambda,
            rule: "λ must be finite and ≥ 0",
        });
    }
    if !FitSettings::max_residual_is_valid(settings.max_residual) {
        return Err(FitError::InvalidSetting {
            name: "max_residual",
            value: settings.max_residual,
            rule: "the largest accepted residual must be finite and ≥ 1e-15 (double precision cannot certify less)",
        });
    }
    for (i, c) in constraints.iter().enumerate() {
        let bad = |field, rule| FitError::InvalidValue {
            constraint: i,
            kind: c.kind,
            field,
            value: match field {
                "smoothing" => c.smoothing,
                "offset" => c.offset.unwrap_or(0.0),
                _ => c.value,
            },
            rule,
        };
        let nonfinite = |field| FitError::NonFinite {
            constraint: i,
            field,
        };
        if !c.position.iter().all(|v| v.is_finite()) {
            return Err(nonfinite("position"));
        }
        if !c.value.is_finite() {
            return Err(nonfinite("value"));
        }
        if !c.smoothing.is_finite() {
            return Err(nonfinite("smoothing"));
        }
        if c.smoothing < 0.0 {
            return Err(bad("smoothing", "smoothing must be ≥ 0"));
        }
        match c.kind {
            ConstraintKind::Boundary if c.value != 0.0 => {
                return Err(bad("value", "a boundary constraint has value 0"));
            }
            ConstraintKind::Interior if c.value <= 0.0 => {
                return Err(bad(
                    "value",
                    "an interior constraint needs a positive value",
                ));
            }
            ConstraintKind::Exterior if c.value >= 0.0 => {
                return Err(bad(
                    "value",
                    "an exterior constraint needs a negative value",
                ));
            }
            ConstraintKind::Normal => {
                if !c.normal.iter().all(|v| v.is_finite()) {
                    return Err(nonfinite("normal"));
                }
                if norm(&c.normal) == 0.0 {
                    return Err(FitError::ZeroNormal { constraint: i });
                }
                if c.value <= 0.0 {
                    return Err(bad(
                        "value",
                        "a normal constraint's offset point is inside: its value must be positive",
                    ));
                }
                if let Some(o) = c.offset {
                    if !o.is_finite() {
                        return Err(nonfinite("offset"));
                    }
                    if o <= 0.0 {
                        return Err(bad("offset", "the offset must be positive"));
                    }
                }
            }
            _ => {}
        }
    }
    let (NormalOffset::Relative(offset) | NormalOffset::Absolute(offset)) = settings.normal_offset;
    if !(offset.is_finite() && offset > 0.0) {
        return Err(FitError::InvalidSetting {
            name: "normal offset",
            value: offset,
            rule: "the offset must be finite and > 0",
        });
    }
    Ok(())
}

fn bounds<'a, const D: usize>(points: impl Iterator<Item = &'a [f64; D]>) -> ([f64; D], [f64; D]) {
    let mut lo = [f64::INFINITY; D];
    let mut hi = [f64::NEG_INFINITY; D];
    for p in points {
        for d in 0..D {
            lo[d] = lo[d].min(p[d]);
            hi[d] = hi[d].max(p[d]);
        }
    }
    (lo, hi)
}

pub(crate) fn norm<const D: usize>(v: &[f64; D]) -> f64 {
    // Scaled so that huge or tiny components neither overflow nor underflow.
    let m = v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    m * crate::math::sqrt(v.iter().map(|x| (x / m) * (x / m)).sum::<f64>())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    /// f mapped to the unknowns of a system with one more row (whose box, and so whose
    /// normalization, differs from f's own) and back is f again, for every kernel.
    fn gives_back<const D: usize>(
        cs: &[Constraint<D>],
        extra: Constraint<D>,
        kernel: Kernel,
    ) -> Result<(), FitError> {
        let settings = FitSettings {
            kernel: Some(kernel),
            ..FitSettings::default()
        };
        // Offsets given, as a greedy fit gives them: the box's growth does not move them.
        let cs: Vec<Constraint<D>> = cs
            .iter()
            .map(|c| Constraint {
                offset: Some(0.05),
                ..*c
            })
            .collect();
        let f = crate::fit(&cs, &settings)?.interpolant;
        let mut more = cs.clone();
        more.push(extra);
        let system = System::new(&more, &settings)?;
        assert!(system.scale() > 1.5, "the new row widens the box");
        let x = system.normalized_unknowns(&f);
        let k = system.rows();
        assert_eq!(x[k - 1], 0.0);
        let g = system.to_interpolant(&x[..k], &x[k..]);
        for c in cs.iter().chain([&extra]) {
            let p = c.position.map(|v| 0.7 * v + 0.1);
            let (a, b) = (f.value(&p), g.value(&p));
            assert!((a - b).abs() <= 1e-9 * (1.0 + a.abs()), "{kernel:?}: {a} against {b}");
        }
        Ok(())
    }

    #[test]
    fn normalized_unknowns_give_back_the_interpolant() -> Result<(), FitError> {
        for kernel in [Kernel::Cubic, Kernel::Linear, Kernel::ThinPlate] {
            gives_back(
                &shapes::sphere(30),
                Constraint::exterior([4.0, 1.0, -2.0], -1.0),
                kernel,
            )?;
        }
        let circle: Vec<Constraint<2>> = (0..24)
            .map(|i| {
                let t = core::f64::consts::TAU * i as f64 / 24.0;
                Constraint::normal([t.cos(), t.sin()], [t.cos(), t.sin()])
            })
            .collect();
        gives_back(&circle, Constraint::exterior([3.5, -2.0], -1.0), Kernel::ThinPlate)
    }
}
