//! The constraints a user places: boundary, interior, exterior and normal
//! (Turk & O'Brien 2002, §4).

/// What a constraint asks of the surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "kebab-case"))]
pub enum ConstraintKind {
    /// The surface passes through the point: f = 0.
    Boundary,
    /// The point is inside: f = value > 0.
    Interior,
    /// The point is outside: f = value < 0.
    Exterior,
    /// The surface passes through the point with the given outward normal: f = 0 there and
    /// f = value > 0 a small distance inside, against the normal (Turk & O'Brien 2002, §4.3).
    Normal,
}

impl ConstraintKind {
    /// A lowercase name (`boundary`, `interior`, `exterior`, `normal`).
    pub const fn name(self) -> &'static str {
        match self {
            ConstraintKind::Boundary => "boundary",
            ConstraintKind::Interior => "interior",
            ConstraintKind::Exterior => "exterior",
            ConstraintKind::Normal => "normal",
        }
    }
}

/// One constraint in `D` dimensions.
///
/// ```
/// use rbf_core::{Constraint, ConstraintKind};
/// let c = Constraint::normal([0.0, 0.0, 1.0], [0.0, 0.0, 1.0]).with_offset(0.05);
/// assert_eq!(c.kind, ConstraintKind::Normal);
/// assert_eq!(c.value, 1.0); // the value at the offset point, inside
/// assert_eq!(Constraint::exterior([3.0, 3.0, 3.0], -1.0).value, -1.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Constraint<const D: usize> {
    /// Boundary, interior, exterior or normal: decides the sign `value` must have.
    pub kind: ConstraintKind,
    /// The constrained point, in the model's coordinates (for a normal constraint, the point
    /// on the surface).
    pub position: [f64; D],
    /// The value of f: 0 for boundary, positive for interior, negative for exterior; for a
    /// normal constraint, the value at its offset point (the point itself gets 0).
    pub value: f64,
    /// For a normal constraint, the outward normal (any non-zero length); unused otherwise.
    pub normal: [f64; D],
    /// For a normal constraint, the distance from the point to its offset point; `None` takes
    /// [`crate::FitSettings::normal_offset`].
    pub offset: Option<f64>,
    /// Regularization λᵢ ≥ 0 added to the global λ on this constraint's diagonal entries
    /// (Yngve & Turk 2002, §6.3): the larger, the less exactly the surface meets it.
    pub smoothing: f64,
}

impl<const D: usize> Constraint<D> {
    const fn with(kind: ConstraintKind, position: [f64; D], value: f64) -> Self {
        Self {
            kind,
            position,
            value,
            normal: [0.0; D],
            offset: None,
            smoothing: 0.0,
        }
    }

    /// f = 0 at `position`.
    pub const fn boundary(position: [f64; D]) -> Self {
        Self::with(ConstraintKind::Boundary, position, 0.0)
    }

    /// f = `value` (> 0) at `position`, a point inside.
    pub const fn interior(position: [f64; D], value: f64) -> Self {
        Self::with(ConstraintKind::Interior, position, value)
    }

    /// f = `value` (< 0) at `position`, a point outside.
    pub const fn exterior(position: [f64; D], value: f64) -> Self {
        Self::with(ConstraintKind::Exterior, position, value)
    }

    /// f = 0 at `position` and f = 1 a small distance against the outward `normal`.
    pub const fn normal(position: [f64; D], normal: [f64; D]) -> Self {
        let mut c = Self::with(ConstraintKind::Normal, position, 1.0);
        c.normal = normal;
        c
    }

    /// Sets the value (for a normal constraint, the value at the offset point).
    pub const fn with_value(mut self, value: f64) -> Self {
        self.value = value;
        self
    }

    /// Sets the absolute offset of a normal constraint.
    pub const fn with_offset(mut self, offset: f64) -> Self {
        self.offset = Some(offset);
        self
    }

    /// Sets this constraint's own regularization λᵢ.
    pub const fn with_smoothing(mut self, smoothing: f64) -> Self {
        self.smoothing = smoothing;
        self
    }

    /// The number of rows of the linear system this constraint takes: 2 for a normal
    /// constraint, 1 otherwise.
    pub const fn rows(&self) -> usize {
        match self.kind {
            ConstraintKind::Normal => 2,
            _ => 1,
        }
    }
}

/// How far a normal constraint's offset point lies from its boundary point.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "kebab-case"))]
pub enum NormalOffset {
    /// A fraction of the longest side of the constraints' bounding box. The papers used 0.01
    /// for models in a unit cube, which is the default.
    Relative(f64),
    /// A distance in the model's units.
    Absolute(f64),
}

impl Default for NormalOffset {
    fn default() -> Self {
        NormalOffset::Relative(0.01)
    }
}

/// Where a row of the linear system came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RowSource {
    /// The index of the constraint in the caller's list.
    pub constraint: usize,
    /// True for the offset point of a normal constraint.
    pub offset_point: bool,
}

impl core::fmt::Display for RowSource {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        if self.offset_point {
            write!(
                f,
                "the offset point of normal constraint {}",
                self.constraint
            )
        } else {
            write!(f, "constraint {}", self.constraint)
        }
    }
}
