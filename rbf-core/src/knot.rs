//! Knot insertion (Turk & O'Brien 2002, §5): a new boundary constraint on the surface
//! leaves it unchanged.

use alloc::vec::Vec;

use crate::system::norm;
use crate::{Constraint, InterpolantView};

/// Why a knot could not be inserted.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum KnotError {
    /// Newton's method did not reach the surface from the given point.
    #[error(
        "no surface point found near the given point (|f|/|∇f| = {distance:e} after {steps} steps)"
    )]
    NotOnSurface {
        /// The last first-order distance estimate |f|/|∇f|.
        distance: f64,
        /// Newton steps taken.
        steps: usize,
    },
}

/// Moves `start` onto the zero set of f by Newton steps along the gradient,
/// x ← x − f(x) ∇f(x) / |∇f(x)|², until |f|/|∇f| is below `tolerance`.
///
/// ```
/// use rbf_core::{InterpolantView, Kernel, project_to_surface};
/// let f = InterpolantView::new(Kernel::Cubic, &[[0.0, 0.0, 0.0]], &[-1.0], 1.0, [0.0; 3]).unwrap();
/// let p = project_to_surface(&f, [0.5, 0.5, 0.0], 1e-13).unwrap();
/// let r = (p[0] * p[0] + p[1] * p[1]).sqrt();
/// assert!((r - 1.0).abs() < 1e-12);
/// ```
pub fn project_to_surface<const D: usize>(
    f: &InterpolantView<'_, f64, D>,
    start: [f64; D],
    tolerance: f64,
) -> Result<[f64; D], KnotError> {
    let mut x = start;
    let mut distance = f64::INFINITY;
    const STEPS: usize = 50;
    for step in 0..STEPS {
        let (v, g) = f.value_and_gradient(&x);
        let g2: f64 = g.iter().map(|c| c * c).sum();
        let gn = norm(&g);
        if !(gn > 0.0) || !v.is_finite() {
            return Err(KnotError::NotOnSurface {
                distance,
                steps: step,
            });
        }
        distance = v.abs() / gn;
        if distance <= tolerance {
            return Ok(x);
        }
        for d in 0..D {
            x[d] -= v * g[d] / g2;
        }
    }
    Err(KnotError::NotOnSurface {
        distance,
        steps: STEPS,
    })
}

/// Inserts a boundary constraint where the surface is: `near` is first projected onto the zero
/// set of `f` (the interpolant fitted to `constraints`), so that refitting leaves f unchanged.
/// Returns the point inserted.
///
/// ```
/// use rbf_core::{Constraint, FitSettings, fit, insert_knot};
/// let mut cs = vec![
///     Constraint::boundary([1.0, 0.0]),
///     Constraint::boundary([-1.0, 0.0]),
///     Constraint::boundary([0.0, 1.0]),
///     Constraint::interior([0.0, 0.0], 1.0),
/// ];
/// let before = fit(&cs, &FitSettings::default()).unwrap().interpolant;
/// insert_knot(&mut cs, &before.view(), [0.3, -0.8]).unwrap();
/// let after = fit(&cs, &FitSettings::default()).unwrap().interpolant;
/// let x = [0.2, 0.4];
/// assert!((before.value(&x) - after.value(&x)).abs() < 1e-9);
/// ```
pub fn insert_knot<const D: usize>(
    constraints: &mut Vec<Constraint<D>>,
    f: &InterpolantView<'_, f64, D>,
    near: [f64; D],
) -> Result<[f64; D], KnotError> {
    let size = f
        .centres()
        .iter()
        .flat_map(|c| c.iter())
        .fold(0.0_f64, |m, v| m.max(v.abs()))
        .max(norm(&near));
    let p = project_to_surface(f, near, 1e-14 * size.max(1e-300))?;
    constraints.push(Constraint::boundary(p));
    Ok(p)
}
