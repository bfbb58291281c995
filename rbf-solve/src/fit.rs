//! Fitting at scale: choose the factorization, refine, estimate the condition, check.

use faer::Par;
use rayon::prelude::*;
use rbf_core::{
    Constraint, Fit, FitError, FitSettings, Solution, SolveMethod, System, estimate_inverse_norm1,
};

use crate::lu::FullLu;
use crate::projected::{Attempt, Projected};

/// Which factorization solves the system; [`Strategy::Auto`] falls back from the fastest.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum Strategy {
    /// Cholesky of the projected block; LBLᵀ if that block is not definite; LU of the whole
    /// system if the residual is still too large. The default.
    #[default]
    Auto,
    /// Cholesky of the projected block only (fails on an indefinite block).
    Cholesky,
    /// Bunch–Kaufman LBLᵀ of the projected block.
    Lblt,
    /// Partial-pivot LU of the whole saddle-point system.
    Lu,
}

/// How rbf-solve solves (what rbf-core's [`FitSettings`] says is what to solve).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SolveOptions {
    /// Which factorization to use, with or without fallbacks; `Auto` by default.
    pub strategy: Strategy,
    /// Most steps of iterative refinement (each costs two triangular solves and one
    /// evaluation of f at every centre). 3 by default.
    pub max_refinements: usize,
}

impl Default for SolveOptions {
    fn default() -> Self {
        Self {
            strategy: Strategy::Auto,
            max_refinements: 3,
        }
    }
}

/// Rows above which [`fit`] solves iteratively ([`crate::solve_iterative`]) instead of by a
/// dense factorization: on two cores the dense solve of 5000 rows takes about 0.4 s and grows
/// as K³, the iterative one about 0.2 s, growing as K² (one direct product per iteration).
pub const DENSE_LIMIT: usize = 5000;

/// Fits an interpolant to constraints with default options: a dense factorization up to
/// [`DENSE_LIMIT`] rows, the iterative solver above.
///
/// ```
/// use rbf_core::{Constraint, FitSettings};
/// // 200 points on the unit sphere with outward normals.
/// let n = 200;
/// let cs: Vec<Constraint<3>> = (0..n)
///     .map(|i| {
///         let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
///         let t = i as f64 * 2.399963;
///         let r = (1.0 - z * z).sqrt();
///         let p = [r * t.cos(), r * t.sin(), z];
///         Constraint::normal(p, p)
///     })
///     .collect();
/// let fit = rbf_solve::fit(&cs, &FitSettings::default()).unwrap();
/// assert!(fit.report.residual < 1e-9);
/// let f = &fit.interpolant;
/// assert!(f.value(&[0.0; 3]) > 0.0 && f.value(&[0.0, 0.0, 1.5]) < 0.0);
/// ```
pub fn fit<const D: usize>(
    constraints: &[Constraint<D>],
    settings: &FitSettings,
) -> Result<Fit<D>, FitError> {
    crate::fit_with(constraints, settings, &crate::FitOptions::default(), |_| {})
}

/// Solves a checked system (see [`fit`]) with the given options.
pub fn solve<const D: usize>(
    system: &System<D>,
    settings: &FitSettings,
    options: &SolveOptions,
) -> Result<Fit<D>, FitError> {
    // Every core where there are threads; one in a browser.
    #[cfg(not(target_family = "wasm"))]
    let par = Par::rayon(0);
    #[cfg(target_family = "wasm")]
    let par = Par::Seq;
    let projected = |attempt| match Projected::new(system, attempt, par) {
        Ok(p) => Ok(Some(p)),
        Err(None) => Ok(None),
        Err(Some(e)) => Err(e),
    };
    let lu = || -> Result<Fit<D>, FitError> {
        let f = FullLu::new(system)?;
        let solve = |h: &[f64], g: &[f64]| f.solve(h, g);
        run(system, settings, options, &solve, SolveMethod::Lu, f.norm1)
    };
    let with_projected = |p: Projected, method| {
        let solve = |h: &[f64], g: &[f64]| p.solve(h, g, par);
        run(system, settings, options, &solve, method, p.norm1)
    };
    match options.strategy {
        Strategy::Lu => lu(),
        Strategy::Lblt => match projected(Attempt::Lblt)? {
            Some(p) => with_projected(p, SolveMethod::ProjectedLblt),
            None => Err(FitError::Singular {
                condition: f64::INFINITY,
            }),
        },
        Strategy::Cholesky => match projected(Attempt::Cholesky)? {
            Some(p) => with_projected(p, SolveMethod::ProjectedCholesky),
            None => Err(FitError::Singular {
                condition: f64::INFINITY,
            }),
        },
        Strategy::Auto => {
            let first = match projected(Attempt::Cholesky)? {
                Some(p) => with_projected(p, SolveMethod::ProjectedCholesky),
                None => match projected(Attempt::Lblt)? {
                    Some(p) => with_projected(p, SolveMethod::ProjectedLblt),
                    None => Err(FitError::Singular {
                        condition: f64::INFINITY,
                    }),
                },
            };
            match first {
                Err(FitError::IllConditioned { .. } | FitError::Singular { .. }) => {
                    // LU pivots across the whole system; worth one try before giving up.
                    lu().or(first)
                }
                other => other,
            }
        }
    }
}

/// Solves the full normalized system for (h, g), giving (w, p).
type FullSolve<'a> = dyn Fn(&[f64], &[f64]) -> (Vec<f64>, Vec<f64>) + 'a;

/// Solves, refines, estimates the condition and checks, given a solver of the full system.
fn run<const D: usize>(
    system: &System<D>,
    settings: &FitSettings,
    options: &SolveOptions,
    solve: &FullSolve<'_>,
    method: SolveMethod,
    norm1: f64,
) -> Result<Fit<D>, FitError> {
    let k = system.rows();
    let m = D + 1;
    let h = system.values();
    let (mut w, mut p) = solve(h, &vec![0.0; m]);
    let (mut rh, mut rg) = residual(system, &w, &p);
    let mut size = max_abs(&rh).max(max_abs(&rg));
    let mut refinements = 0;
    while refinements < options.max_refinements && size > 0.0 && size.is_finite() {
        let (dw, dp) = solve(&rh, &rg);
        let w2: Vec<f64> = w.iter().zip(&dw).map(|(a, b)| a + b).collect();
        let p2: Vec<f64> = p.iter().zip(&dp).map(|(a, b)| a + b).collect();
        let (rh2, rg2) = residual(system, &w2, &p2);
        let size2 = max_abs(&rh2).max(max_abs(&rg2));
        if !(size2 < size) {
            break;
        }
        (w, p, rh, rg, size) = (w2, p2, rh2, rg2, size2);
        refinements += 1;
    }
    let inverse = estimate_inverse_norm1(k + m, |b| {
        let (x, y) = solve(&b[..k], &b[k..]);
        b[..k].copy_from_slice(&x);
        b[k..].copy_from_slice(&y);
        b.iter().all(|v| v.is_finite())
    });
    system.accept(
        settings,
        &Solution {
            weights: &w,
            polynomial: &p,
            method,
            condition: norm1 * inverse,
            refinements,
            iterations: 0,
        },
    )
}

/// The normalized residual (h − (Φ+Λ)w − Pp, −Pᵀw).
fn residual<const D: usize>(system: &System<D>, w: &[f64], p: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let f = system.normalized_interpolant(w, p);
    let points = system.normalized_points();
    let mut fx = vec![0.0; points.len()];
    if f.view().par_values(points, &mut fx).is_err() {
        fx.fill(f64::NAN);
    }
    let rh: Vec<f64> = (0..points.len())
        .into_par_iter()
        .map(|i| system.values()[i] - fx[i] - system.normalized_smoothing(i) * w[i])
        .collect();
    let mut rg = vec![0.0; D + 1];
    for (wi, x) in w.iter().zip(points) {
        rg[0] -= wi;
        for d in 0..D {
            rg[d + 1] -= wi * x[d];
        }
    }
    (rh, rg)
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(
        0.0_f64,
        |m, x| {
            if x.is_nan() { f64::NAN } else { m.max(x.abs()) }
        },
    )
}
