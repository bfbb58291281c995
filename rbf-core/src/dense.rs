//! The small dense solver: the whole saddle-point system, LU with partial pivoting (nalgebra),
//! iterative refinement and a condition estimate. For systems up to a few thousand rows; use
//! rbf-solve beyond.

use alloc::vec::Vec;

use nalgebra::{DMatrix, DVector};

use crate::{
    Constraint, Fit, FitError, FitSettings, Solution, SolveMethod, System, estimate_inverse_norm1,
};

/// Fits an interpolant to constraints with the small dense solver.
///
/// ```
/// use rbf_core::{Constraint, FitSettings, fit};
/// // Turk & O'Brien 2002, Figure 2 (left): a tetrahedron of boundary points around one
/// // interior point.
/// let s = 1.0 / 3f64.sqrt();
/// let cs = [
///     Constraint::boundary([s, s, s]),
///     Constraint::boundary([s, -s, -s]),
///     Constraint::boundary([-s, s, -s]),
///     Constraint::boundary([-s, -s, s]),
///     Constraint::interior([0.0, 0.0, 0.0], 1.0),
/// ];
/// let fit = fit(&cs, &FitSettings::default()).unwrap();
/// let f = &fit.interpolant;
/// assert!(f.value(&[s, s, s]).abs() < 1e-12);
/// assert!(f.value(&[0.0; 3]) > 0.0 && f.value(&[3.0, 0.0, 0.0]) < 0.0);
/// ```
pub fn fit<const D: usize>(
    constraints: &[Constraint<D>],
    settings: &FitSettings,
) -> Result<Fit<D>, FitError> {
    let system = System::new(constraints, settings)?;
    solve_dense(&system, settings)
}

/// Solves a checked system with LU; see [`fit`].
pub fn solve_dense<const D: usize>(
    system: &System<D>,
    settings: &FitSettings,
) -> Result<Fit<D>, FitError> {
    let k = system.rows();
    let n = system.size();
    let matrix = assemble(system)?;
    let norm1 = (0..n)
        .map(|j| matrix.column(j).iter().map(|v| v.abs()).sum::<f64>())
        .fold(0.0, f64::max);
    let lu = matrix.clone().lu();

    let mut rhs = DVector::<f64>::zeros(n);
    rhs.rows_mut(0, k).copy_from_slice(system.values());
    let Some(mut x) = lu.solve(&rhs) else {
        return Err(FitError::Singular {
            condition: f64::INFINITY,
        });
    };
    let residual_norm = |x: &DVector<f64>| (&rhs - &matrix * x).amax();
    let mut refinements = 0;
    let mut r = residual_norm(&x);
    while refinements < 3 && r > 0.0 && r.is_finite() {
        let Some(dx) = lu.solve(&(&rhs - &matrix * &x)) else {
            break;
        };
        let candidate = &x + dx;
        let rc = residual_norm(&candidate);
        if !(rc < r) {
            break;
        }
        x = candidate;
        r = rc;
        refinements += 1;
    }
    let condition = norm1
        * estimate_inverse_norm1(n, |b| {
            let v = DVector::from_column_slice(b);
            match lu.solve(&v) {
                Some(s) => {
                    b.copy_from_slice(s.as_slice());
                    true
                }
                None => false,
            }
        });
    system.accept(
        settings,
        &Solution {
            weights: &x.as_slice()[..k],
            polynomial: &x.as_slice()[k..],
            method: SolveMethod::Lu,
            condition,
            refinements,
            iterations: 0,
        },
    )
}

/// The whole normalized system [Φ + Λ, P; Pᵀ, 0], column-major.
fn assemble<const D: usize>(system: &System<D>) -> Result<DMatrix<f64>, FitError> {
    let n = system.size();
    let too_large = || FitError::TooLarge {
        rows: n,
        bytes: 2 * (n as u64) * (n as u64) * 8,
        available: None,
    };
    let entries = n.checked_mul(n).ok_or_else(too_large)?;
    let mut data: Vec<f64> = Vec::new();
    // Reserve room for the factorization's copy too, so that it cannot abort later.
    data.try_reserve_exact(entries.checked_mul(2).ok_or_else(too_large)?)
        .map_err(|_| too_large())?;
    data.shrink_to(entries);
    data.resize(entries, 0.0);
    for (j, col) in data.chunks_exact_mut(n).enumerate() {
        system.system_column(j, col);
    }
    Ok(DMatrix::from_vec(n, n, data))
}
