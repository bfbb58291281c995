//! Blending implicit surfaces by constraint selection (Turk & O'Brien 2002, §6): keep each model's
//! constraints that lie outside every other model, and fit one interpolant through them all.
//! Where the models overlap their constraints are dropped, so the new surface is free to bridge
//! the crease smoothly; elsewhere it passes through the same constraints as before.

use rbf_core::{Constraint, Model};

use crate::ConvertError;

/// How many constraints each model kept.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BlendReport {
    /// Per model, in order: constraints kept.
    pub kept: Vec<usize>,
    /// Per model: constraints it had.
    pub total: Vec<usize>,
}

/// Blends models: each constraint of model A (a normal constraint with its point) is kept when
/// f_B < 0 at its position for every other model B. The models must share a kernel; the fit
/// takes the first model's settings.
///
/// ```
/// use rbf_convert::blend;
/// use rbf_core::{Constraint, FitSettings, Model};
/// // Two spheres of radius 1, centres 1.5 apart, from six oriented points each.
/// let sphere = |cx: f64| {
///     let dirs = [[1., 0., 0.], [-1., 0., 0.], [0., 1., 0.], [0., -1., 0.], [0., 0., 1.], [0., 0., -1.]];
///     let cs: Vec<Constraint<3>> = dirs.iter()
///         .map(|d| Constraint::normal([cx + d[0], d[1], d[2]], *d))
///         .collect();
///     let fit = rbf_solve::fit(&cs, &FitSettings::default()).unwrap();
///     Model { constraints: cs, settings: FitSettings::default(), interpolant: fit.interpolant, report: None }
/// };
/// let (a, b) = (sphere(0.0), sphere(1.5));
/// let (blended, report) = blend(&[&a, &b]).unwrap();
/// // Each sphere loses the point that lies inside the other.
/// assert_eq!(report.kept, vec![5, 5]);
/// assert!(blended.interpolant.value(&[0.75, 0.0, 0.0]) > 0.0); // one solid
/// ```
pub fn blend<const D: usize>(
    models: &[&Model<D>],
) -> Result<(Model<D>, BlendReport), ConvertError> {
    let Some(first) = models.first() else {
        return Err(ConvertError::NothingToBlend);
    };
    let kernel = first.interpolant.kernel();
    if let Some(i) = models.iter().position(|m| m.interpolant.kernel() != kernel) {
        return Err(ConvertError::KernelMismatch {
            model: i + 1,
            expected: kernel,
            found: models[i].interpolant.kernel(),
        });
    }
    let mut constraints: Vec<Constraint<D>> = Vec::new();
    let mut report = BlendReport {
        kept: Vec::new(),
        total: Vec::new(),
    };
    for (a, model) in models.iter().enumerate() {
        let before = constraints.len();
        constraints.extend(model.constraints.iter().filter(|c| {
            models
                .iter()
                .enumerate()
                .all(|(b, other)| b == a || other.interpolant.value(&c.position) < 0.0)
        }));
        report.kept.push(constraints.len() - before);
        report.total.push(model.constraints.len());
    }
    let settings = first.settings;
    let fit = rbf_solve::fit(&constraints, &settings)?;
    Ok((
        Model {
            constraints,
            settings,
            interpolant: fit.interpolant,
            report: Some(fit.report),
        },
        report,
    ))
}
