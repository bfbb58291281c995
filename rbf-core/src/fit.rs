//! What a fit returns: the interpolant and an honest account of how it was obtained.

use crate::{FitError, FitSettings, Interpolant, System};

/// How the linear system was factored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "kebab-case"))]
#[non_exhaustive]
pub enum SolveMethod {
    /// Partial-pivot LU of the whole system (rbf-core's small dense solver, or the last
    /// fallback of rbf-solve).
    Lu,
    /// Cholesky of the kernel block projected onto polynomial-free weights.
    ProjectedCholesky,
    /// Symmetric-indefinite LBLᵀ (Bunch–Kaufman) of the projected kernel block.
    ProjectedLblt,
    /// Flexible GMRES with a two-level domain-decomposition preconditioner (rbf-solve's
    /// solver for large systems).
    Iterative,
}

/// Figures of a fit.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FitReport {
    /// Rows K of the kernel block (constraint points).
    pub rows: usize,
    /// The factorization that produced the weights.
    pub method: SolveMethod,
    /// max |f(cᵢ) + λᵢwᵢ − hᵢ| / max |hᵢ|, measured on the returned interpolant.
    pub residual: f64,
    /// An estimate of the 1-norm condition number of the (normalized) system; NaN when the
    /// solver made none (the iterative one), written as `null` in a model file.
    #[cfg_attr(feature = "serde", serde(deserialize_with = "nan_if_null"))]
    pub condition: f64,
    /// Steps of iterative refinement taken.
    pub refinements: usize,
    /// Iterations of an iterative solver (0 for a factorization).
    #[cfg_attr(feature = "serde", serde(default))]
    pub iterations: usize,
}

/// A number, or NaN for JSON's `null` (serde_json writes NaN as `null`).
#[cfg(feature = "serde")]
fn nan_if_null<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    use serde::Deserialize;
    Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::NAN))
}

/// An interpolant and the figures of the fit that produced it.
#[derive(Clone, Debug, PartialEq)]
pub struct Fit<const D: usize> {
    /// The interpolant, in the caller's coordinates.
    pub interpolant: Interpolant<f64, D>,
    /// Rows, factorization, residual, condition estimate and refinement steps of the fit.
    pub report: FitReport,
}

/// A solution of a [`System`]'s normalized equations and how it was found: what a solver hands
/// to [`System::accept`].
#[derive(Clone, Copy, Debug)]
#[doc(hidden)]
pub struct Solution<'a> {
    /// Kernel weights, one per row, for the normalized coordinates.
    pub weights: &'a [f64],
    /// The affine part's D + 1 coefficients (constant first), for the normalized coordinates.
    pub polynomial: &'a [f64],
    /// The factorization that produced them.
    pub method: SolveMethod,
    /// The solver's estimate of the 1-norm condition number.
    pub condition: f64,
    /// Rounds of iterative refinement applied.
    pub refinements: usize,
    /// Iterations of an iterative solver (0 for a factorization).
    pub iterations: usize,
}

impl<const D: usize> System<D> {
    /// Maps a normalized solution back to an interpolant in the caller's coordinates, measures
    /// its residual at every row (on every core, with compensated sums, with the `rayon`
    /// feature) and accepts it only
    /// if the residual is within `settings.max_residual`: a fit is an honest one or an error.
    ///
    /// ```
    /// use rbf_core::{FitSettings, Solution, SolveMethod, System, shapes};
    /// let settings = FitSettings::default();
    /// let system = System::new(&shapes::tetrahedron_blob(), &settings).unwrap();
    /// // Zero weights do not meet the interior constraint: refused.
    /// let zeros = Solution {
    ///     weights: &[0.0; 5],
    ///     polynomial: &[0.0; 4],
    ///     method: SolveMethod::Lu,
    ///     condition: 1.0,
    ///     refinements: 0,
    ///     iterations: 0,
    /// };
    /// assert!(system.accept(&settings, &zeros).is_err());
    /// ```
    #[doc(hidden)]
    pub fn accept(&self, settings: &FitSettings, solution: &Solution<'_>) -> Result<Fit<D>, FitError> {
        self.accept_measured(settings, solution, |interpolant| {
            let mut fx = alloc::vec![0.0; self.rows()];
            #[cfg(feature = "rayon")]
            let evaluated = interpolant.view().par_values_at_centres(&mut fx);
            #[cfg(not(feature = "rayon"))]
            let evaluated = interpolant.view().values(self.points(), &mut fx);
            if evaluated.is_err() {
                fx.fill(f64::NAN);
            }
            self.residual_from_values(interpolant, &fx)
        })
    }

    /// [`System::accept`] with the residual measured by the caller (`measure` gets the
    /// interpolant in the caller's coordinates and returns max |f(cᵢ) + λᵢwᵢ − hᵢ| / max|hᵢ|):
    /// for solvers of 10⁵ rows and more, which certify it by direct sums at sampled rows.
    #[doc(hidden)]
    pub fn accept_measured(
        &self,
        settings: &FitSettings,
        solution: &Solution<'_>,
        measure: impl FnOnce(&Interpolant<f64, D>) -> f64,
    ) -> Result<Fit<D>, FitError> {
        let Solution {
            weights,
            polynomial,
            method,
            condition,
            refinements,
            iterations,
        } = *solution;
        if !weights.iter().chain(polynomial).all(|v| v.is_finite()) {
            return Err(FitError::Singular {
                condition: f64::INFINITY,
            });
        }
        let interpolant = self.to_interpolant(weights, polynomial);
        let residual = measure(&interpolant);
        if !(residual <= settings.max_residual) {
            return Err(FitError::IllConditioned {
                residual,
                limit: settings.max_residual,
                condition,
            });
        }
        Ok(Fit {
            interpolant,
            report: FitReport {
                rows: self.rows(),
                method,
                residual,
                condition,
                refinements,
                iterations,
            },
        })
    }
}
