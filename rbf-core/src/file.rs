//! Versioned JSON for constraint files and model files (feature `serde`).
//!
//! Both hold constraints as records; a model file adds the interpolant. Documented for users
//! in the README; the version changes whenever a field changes meaning.

use alloc::format;
use alloc::string::{String, ToString};
use alloc::vec::Vec;

use serde::{Deserialize, Serialize};

use crate::{
    Constraint, ConstraintKind, FitError, FitReport, FitSettings, Interpolant, Kernel, Model,
    NormalOffset, System,
};

/// The `format` field of a model file.
pub const MODEL_FORMAT: &str = "rbf-model";
/// The model file version written by this library (and the only one read).
pub const MODEL_VERSION: u32 = 1;

/// One constraint as stored in JSON.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConstraintRecord {
    /// `boundary`, `interior`, `exterior` or `normal`.
    pub kind: ConstraintKind,
    /// D coordinates.
    pub position: Vec<f64>,
    /// The value (interior: default 1; exterior: default −1; normal: default 1 at the offset
    /// point; boundary: 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub value: Option<f64>,
    /// The outward normal of a normal constraint.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normal: Option<Vec<f64>>,
    /// The absolute offset of a normal constraint.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub offset: Option<f64>,
    /// This constraint's own λᵢ.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub smoothing: Option<f64>,
}

/// A constraint file: constraints plus optional fit settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConstraintFile {
    /// 2 or 3; when absent, the length of the first position.
    #[serde(default)]
    pub dim: Option<usize>,
    /// The kernel; default r² log r in 2D, r³ in 3D.
    #[serde(default)]
    pub kernel: Option<Kernel>,
    /// Global λ; default 0.
    #[serde(default)]
    pub lambda: Option<f64>,
    /// Default offset of normal constraints; default `{"relative": 0.01}`.
    #[serde(default)]
    pub normal_offset: Option<NormalOffset>,
    /// The constraints to fit, in file order.
    pub constraints: Vec<ConstraintRecord>,
}

/// The JSON of a model file, version 1.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct ModelFile {
    format: String,
    version: u32,
    dim: usize,
    kernel: Kernel,
    lambda: f64,
    normal_offset: NormalOffset,
    constraints: Vec<ConstraintRecord>,
    centres: Vec<Vec<f64>>,
    weights: Vec<f64>,
    constant: f64,
    linear: Vec<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    report: Option<FitReport>,
}

/// Why a constraint or model file could not be read.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum FileError {
    /// Not JSON of the expected shape.
    #[error("line {line}, column {column}: {message}")]
    Json {
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// serde's message.
        message: String,
    },
    /// Not a model file, or one of a version this library cannot read.
    #[error("{0}")]
    Format(String),
    /// A dimension other than 2 or 3.
    #[error("dimension {0} is not supported (2 or 3)")]
    Dimension(usize),
    /// A field is present but wrong: its length, a value, or its agreement with other fields.
    #[error("{0}")]
    Invalid(String),
    /// The constraints themselves are invalid.
    #[error(transparent)]
    Constraint(#[from] FitError),
}

fn json_error(e: serde_json::Error) -> FileError {
    FileError::Json {
        line: e.line(),
        column: e.column(),
        message: e.to_string(),
    }
}

fn array<const D: usize>(v: &[f64], what: &str) -> Result<[f64; D], FileError> {
    let a: [f64; D] = v.try_into().map_err(|_| {
        FileError::Invalid(format!(
            "{what} has {} coordinates where {D} were expected",
            v.len()
        ))
    })?;
    if !a.iter().all(|x| x.is_finite()) {
        return Err(FileError::Invalid(format!("{what} is not finite")));
    }
    Ok(a)
}

impl ConstraintRecord {
    /// The file record of `c`: `value` only for non-boundary kinds, `normal` only for normal
    /// constraints.
    pub(crate) fn from_constraint<const D: usize>(c: &Constraint<D>) -> Self {
        Self {
            kind: c.kind,
            position: c.position.to_vec(),
            value: (c.kind != ConstraintKind::Boundary).then_some(c.value),
            normal: (c.kind == ConstraintKind::Normal).then(|| c.normal.to_vec()),
            offset: c.offset,
            smoothing: (c.smoothing != 0.0).then_some(c.smoothing),
        }
    }

    /// The constraint of a record; `index` names it in errors.
    pub(crate) fn to_constraint<const D: usize>(
        &self,
        index: usize,
    ) -> Result<Constraint<D>, FileError> {
        let what = format!("constraint {index}");
        let position = array::<D>(&self.position, &format!("the position of {what}"))?;
        let mut c = match self.kind {
            ConstraintKind::Boundary => Constraint::boundary(position),
            ConstraintKind::Interior => Constraint::interior(position, 1.0),
            ConstraintKind::Exterior => Constraint::exterior(position, -1.0),
            ConstraintKind::Normal => {
                let Some(n) = &self.normal else {
                    return Err(FileError::Invalid(format!(
                        "{what} is a normal constraint without a `normal`"
                    )));
                };
                Constraint::normal(position, array::<D>(n, &format!("the normal of {what}"))?)
            }
        };
        if self.kind != ConstraintKind::Normal && self.normal.is_some() {
            return Err(FileError::Invalid(format!(
                "{what} is a {} constraint and cannot have a `normal`",
                self.kind.name()
            )));
        }
        if let Some(v) = self.value {
            c.value = v;
        }
        c.offset = self.offset;
        c.smoothing = self.smoothing.unwrap_or(0.0);
        Ok(c)
    }
}

impl ConstraintFile {
    /// Parses a constraint file from JSON.
    ///
    /// ```
    /// let json = r#"{"dim": 2, "constraints": [
    ///     {"kind": "boundary", "position": [1, 0]},
    ///     {"kind": "interior", "position": [0, 0], "value": 2},
    ///     {"kind": "normal", "position": [0, 1], "normal": [0, 1]}
    /// ]}"#;
    /// let file = rbf_core::ConstraintFile::from_json(json).unwrap();
    /// assert_eq!(file.dimension().unwrap(), 2);
    /// let cs = file.constraints::<2>().unwrap();
    /// assert_eq!(cs[1].value, 2.0);
    /// ```
    pub fn from_json(text: &str) -> Result<Self, FileError> {
        serde_json::from_str(text).map_err(json_error)
    }

    /// The dimension: `dim`, or the length of the first position.
    pub fn dimension(&self) -> Result<usize, FileError> {
        let dim = match (self.dim, self.constraints.first()) {
            (Some(d), _) => d,
            (None, Some(c)) => c.position.len(),
            (None, None) => return Err(FileError::Invalid("no constraints and no `dim`".into())),
        };
        if dim == 2 || dim == 3 {
            Ok(dim)
        } else {
            Err(FileError::Dimension(dim))
        }
    }

    /// The constraints, each checked to have D coordinates.
    pub fn constraints<const D: usize>(&self) -> Result<Vec<Constraint<D>>, FileError> {
        self.constraints
            .iter()
            .enumerate()
            .map(|(i, r)| r.to_constraint(i))
            .collect()
    }

    /// Fit settings from the file's fields over `base`.
    pub fn settings(&self, base: FitSettings) -> FitSettings {
        FitSettings {
            kernel: self.kernel.or(base.kernel),
            lambda: self.lambda.unwrap_or(base.lambda),
            normal_offset: self.normal_offset.unwrap_or(base.normal_offset),
            ..base
        }
    }
}

impl<const D: usize> Model<D> {
    /// The model as JSON (format `rbf-model`, version 1).
    ///
    /// ```
    /// use rbf_core::{AnyModel, Constraint, FitSettings, Model, fit};
    /// let cs = vec![
    ///     Constraint::boundary([1.0, 0.0]),
    ///     Constraint::boundary([0.0, 1.0]),
    ///     Constraint::boundary([-1.0, 0.0]),
    ///     Constraint::interior([0.0, 0.0], 1.0),
    /// ];
    /// let settings = FitSettings::default();
    /// let f = fit(&cs, &settings).unwrap();
    /// let model = Model { constraints: cs, settings, interpolant: f.interpolant, report: Some(f.report) };
    /// let json = model.to_json();
    /// let AnyModel::Two(back) = AnyModel::from_json(&json).unwrap() else { panic!() };
    /// assert_eq!(back.interpolant, model.interpolant);
    /// ```
    pub fn to_json(&self) -> String {
        let f = &self.interpolant;
        let file = ModelFile {
            format: MODEL_FORMAT.into(),
            version: MODEL_VERSION,
            dim: D,
            kernel: f.kernel(),
            lambda: self.settings.lambda,
            normal_offset: self.settings.normal_offset,
            constraints: self
                .constraints
                .iter()
                .map(ConstraintRecord::from_constraint)
                .collect(),
            centres: f.centres().iter().map(|c| c.to_vec()).collect(),
            weights: f.weights().to_vec(),
            constant: f.constant(),
            linear: f.linear().to_vec(),
            report: self.report,
        };
        // Serializing plain numbers, strings and vectors cannot fail; non-finite numbers
        // (which a checked fit never produces) would be written as null.
        serde_json::to_string_pretty(&file).unwrap_or_default()
    }

    fn from_file(file: ModelFile) -> Result<Self, FileError> {
        let constraints = file
            .constraints
            .iter()
            .enumerate()
            .map(|(i, r)| r.to_constraint::<D>(i))
            .collect::<Result<Vec<_>, _>>()?;
        let centres = file
            .centres
            .iter()
            .enumerate()
            .map(|(i, c)| array::<D>(c, &format!("centre {i}")))
            .collect::<Result<Vec<_>, _>>()?;
        if !file.weights.iter().all(|w| w.is_finite()) || !file.constant.is_finite() {
            return Err(FileError::Invalid(
                "a weight or the constant is not finite".into(),
            ));
        }
        let linear = array::<D>(&file.linear, "`linear`")?;
        let interpolant =
            Interpolant::new(file.kernel, centres, file.weights, file.constant, linear)
                .map_err(|e| FileError::Invalid(e.to_string()))?;
        let settings = FitSettings {
            kernel: Some(file.kernel),
            lambda: file.lambda,
            normal_offset: file.normal_offset,
            ..FitSettings::default()
        };
        if !constraints.is_empty() {
            let system = System::new(&constraints, &settings)?;
            if system.rows() != interpolant.centres().len() {
                return Err(FileError::Invalid(format!(
                    "the constraints give {} centres but the file has {}",
                    system.rows(),
                    interpolant.centres().len()
                )));
            }
            for (i, (a, b)) in system
                .points()
                .iter()
                .zip(interpolant.centres())
                .enumerate()
            {
                let tol = 1e-9 * system.scale();
                if a.iter().zip(b).any(|(x, y)| (x - y).abs() > tol) {
                    return Err(FileError::Invalid(format!(
                        "centre {i} is not where {} puts it",
                        system.sources()[i]
                    )));
                }
            }
        }
        Ok(Model {
            constraints,
            settings,
            interpolant,
            report: file.report,
        })
    }
}

/// The fields of a model file that say whether it can be read at all.
#[derive(Deserialize)]
struct Header {
    format: Option<serde_json::Value>,
    version: Option<serde_json::Value>,
}

/// A model of either dimension, as read from a file.
#[derive(Clone, Debug, PartialEq)]
pub enum AnyModel {
    /// A 2D model (curves).
    Two(Model<2>),
    /// A 3D model (surfaces).
    Three(Model<3>),
}

impl AnyModel {
    /// Reads a model file, checking its format, version, lengths, finiteness, and that its
    /// centres are where its constraints put them.
    pub fn from_json(text: &str) -> Result<Self, FileError> {
        // Only the two fields, everything else skipped unstored (a tree of the whole file's
        // values took a third of reading a 10⁵-centre model).
        let header: Header = serde_json::from_str(text).map_err(json_error)?;
        match header.format.as_ref().and_then(|f| f.as_str()) {
            Some(MODEL_FORMAT) => {}
            Some(other) => {
                return Err(FileError::Format(format!(
                    "format `{other}` is not `{MODEL_FORMAT}`"
                )));
            }
            None => {
                return Err(FileError::Format(format!(
                    "no `format` field: not an {MODEL_FORMAT} file"
                )));
            }
        }
        match header.version.as_ref().and_then(|v| v.as_u64()) {
            Some(v) if v == MODEL_VERSION as u64 => {}
            Some(v) => {
                return Err(FileError::Format(format!(
                    "version {v} cannot be read; this library reads version {MODEL_VERSION}"
                )));
            }
            None => {
                return Err(FileError::Format(format!(
                    "the `version` field is missing or not a whole number; this library reads version {MODEL_VERSION}"
                )));
            }
        }
        let file: ModelFile = serde_json::from_str(text).map_err(json_error)?;
        match file.dim {
            2 => Ok(AnyModel::Two(Model::from_file(file)?)),
            3 => Ok(AnyModel::Three(Model::from_file(file)?)),
            d => Err(FileError::Dimension(d)),
        }
    }

    /// The dimension, 2 or 3.
    pub fn dimension(&self) -> usize {
        match self {
            AnyModel::Two(_) => 2,
            AnyModel::Three(_) => 3,
        }
    }
}
