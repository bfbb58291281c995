//! Fits: constraints of every kind, given as arrays, to a `Model`.

use pyo3::prelude::*;
use rbf_core::{Constraint, FitSettings, Kernel, Model as CoreModel, NormalOffset};
use rbf_solve::{FitOptions, IterativeOptions};

use crate::arrays::{Floats, point_dimension};
use crate::error::bad;
use crate::model::{IntoAnyModel, Model};

/// Kind codes of `_fit`'s `kinds` (the Python layer assembles them).
const BOUNDARY: u8 = 0;
const INTERIOR: u8 = 1;
const EXTERIOR: u8 = 2;
const NORMAL: u8 = 3;

/// A kernel from scipy's name (or rbf's).
pub(crate) fn kernel(name: Option<&str>) -> PyResult<Option<Kernel>> {
    Ok(match name {
        None => None,
        Some("cubic") => Some(Kernel::Cubic),
        Some("linear") => Some(Kernel::Linear),
        Some("thin_plate_spline" | "thin-plate") => Some(Kernel::ThinPlate),
        Some(other) => {
            return Err(bad(format!(
                "kernel must be \"cubic\", \"linear\" or \"thin_plate_spline\", not {other:?}"
            )));
        }
    })
}

/// What `_fit` was given, read and checked, in either dimension.
struct Rows<'py> {
    positions: Floats<'py>,
    kinds: Vec<u8>,
    values: Vec<f64>,
    normals: Option<Floats<'py>>,
    smoothing: Vec<f64>,
    settings: FitSettings,
    method: rbf_solve::Method,
    allow_unconverged: bool,
    /// Whether the caller set `max_residual`: then it is kept, neither raised to the far
    /// field's limit nor relaxed to a rounding floor (as `rbf fit --max-residual`).
    explicit_limit: bool,
}

/// The whole fit of D-dimensional constraints, without the GIL.
fn fit_in<const D: usize>(py: Python<'_>, rows: &Rows<'_>) -> PyResult<Model>
where
    CoreModel<D>: IntoAnyModel,
{
    let (settings, values, kinds) = (rows.settings, &rows.values, &rows.kinds);
    let points = rows.positions.points::<D>("points")?;
    let normals = rows
        .normals
        .as_ref()
        .map(|n| n.points::<D>("normals"))
        .transpose()?;
    if let Some(n) = &normals
        && n.len() != points.len()
    {
        return Err(bad(format!(
            "normals has {} rows for {} points",
            n.len(),
            points.len()
        )));
    }
    if let Some(i) = values.iter().position(|v| !v.is_finite()) {
        return Err(bad(format!(
            "constraint {i}: the value {} is not a finite number",
            values[i]
        )));
    }
    let mut constraints = Vec::with_capacity(points.len());
    for (i, p) in points.iter().enumerate() {
        let c = match kinds[i] {
            BOUNDARY => Constraint::boundary(*p),
            INTERIOR => Constraint::interior(*p, values[i]),
            EXTERIOR => Constraint::exterior(*p, values[i]),
            NORMAL => match &normals {
                Some(n) => Constraint::normal(*p, n[i]).with_value(values[i]),
                None => return Err(bad("normal constraints need normals")),
            },
            k => return Err(bad(format!("constraint {i}: unknown kind code {k}"))),
        };
        constraints.push(c.with_smoothing(rows.smoothing[i]));
    }
    let options = FitOptions {
        method: rows.method,
        iterative: IterativeOptions {
            allow_unconverged: rows.allow_unconverged,
            ..Default::default()
        }
        .with_limit_given(rows.explicit_limit),
        ..FitOptions::default()
    };
    let fit = py.detach(|| rbf_solve::fit_with(&constraints, &settings, &options, |_| {}));
    let fit = fit.map_err(bad)?;
    Ok(Model::new(CoreModel {
        constraints,
        settings,
        interpolant: fit.interpolant,
        report: Some(fit.report),
    }))
}

/// The native fit behind ``rbfsurf.fit`` and ``RBFInterpolator``: one row of ``points`` per
/// constraint, ``kinds`` 0 boundary, 1 interior, 2 exterior, 3 normal (then ``values`` is the
/// value at the offset point and ``normals`` has the outward normal), ``smoothing`` λᵢ per
/// constraint on top of the global ``lam``.
#[pyfunction]
#[pyo3(signature = (points, kinds, values, normals, smoothing, *, kernel=None, lam=0.0, offset=None, method="auto", max_residual=None, allow_unconverged=false))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn _fit(
    py: Python<'_>,
    points: &Bound<'_, PyAny>,
    kinds: &Bound<'_, PyAny>,
    values: &Bound<'_, PyAny>,
    normals: Option<&Bound<'_, PyAny>>,
    smoothing: &Bound<'_, PyAny>,
    kernel: Option<&str>,
    lam: f64,
    offset: Option<f64>,
    method: &str,
    max_residual: Option<f64>,
    allow_unconverged: bool,
) -> PyResult<Model> {
    let positions = Floats::new(points, "points")?;
    let dim = point_dimension(&positions, "points")?;
    let n = positions.shape()[0];
    let kinds: Vec<u8> = Floats::new(kinds, "kinds")?
        .per_row(n, "kinds")?
        .iter()
        .map(|&k| {
            if (0.0..=3.0).contains(&k) {
                k as u8
            } else {
                u8::MAX
            }
        })
        .collect();
    let values = Floats::new(values, "values")?.per_row(n, "values")?;
    let smoothing = Floats::new(smoothing, "smoothing")?.per_row(n, "smoothing")?;
    let normals = normals.map(|n| Floats::new(n, "normals")).transpose()?;
    let method = match method {
        "auto" => rbf_solve::Method::Auto,
        "dense" => rbf_solve::Method::Dense,
        "fast" => rbf_solve::Method::Iterative,
        other => {
            return Err(bad(format!(
                "method must be \"auto\", \"dense\" or \"fast\", not {other:?}"
            )));
        }
    };
    if let Some(o) = offset
        && !(o > 0.0 && o.is_finite())
    {
        return Err(bad(format!(
            "offset must be a finite distance > 0, not {o}"
        )));
    }
    if let Some(r) = max_residual
        && !FitSettings::max_residual_is_valid(r)
    {
        return Err(bad(format!(
            "max_residual must be a finite fraction of max|h| ≥ 1e-15 (double precision cannot certify less), not {r}"
        )));
    }
    let settings = FitSettings {
        kernel: self::kernel(kernel)?,
        lambda: lam,
        normal_offset: offset.map_or(NormalOffset::default(), NormalOffset::Absolute),
        max_residual: max_residual.unwrap_or(FitSettings::default().max_residual),
        ..Default::default()
    };
    let rows = Rows {
        positions,
        kinds,
        values,
        normals,
        smoothing,
        settings,
        method,
        allow_unconverged,
        explicit_limit: max_residual.is_some(),
    };
    if dim == 2 {
        fit_in::<2>(py, &rows)
    } else {
        fit_in::<3>(py, &rows)
    }
}
