//! Why a conversion, a comparison or a blend failed.

use rbf_core::{FitError, Kernel};
use rbf_mesh::MeshError;

/// Why a mesh could not be converted (by either method), compared with a model, or models
/// blended. Each variant names what was wrong; the CLI prints them as they are.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ConvertError {
    /// Too few points to reconstruct a surface from.
    #[error(
        "{points} point(s) after dropping repeated points and outliers: a surface needs at least {needed}"
    )]
    TooFewPoints {
        /// Points left.
        points: usize,
        /// The least accepted.
        needed: usize,
    },
    /// A point of a scan is not finite or lies beyond ±[`crate::LARGEST_COORDINATE`].
    #[error(
        "point {index} = {point:?} is not finite or lies beyond ±1e100, where squared distances overflow: give finite coordinates, scaled to the object's size"
    )]
    PointOutOfRange {
        /// 0-based index of the point.
        index: usize,
        /// The point.
        point: [f64; 3],
    },
    /// The points span no volume: they lie on a plane, a line or one point.
    #[error(
        "the points lie on a {shape}: a closed surface needs points around a volume (an open scan of one side of an object cannot be closed from them)"
    )]
    Flat {
        /// "plane", "line" or "point".
        shape: &'static str,
    },
    /// The function fitted to a scan is not negative all around it, so its zero set does not
    /// close around the points (seen on scans noisier than about 0.3% of their size).
    #[error(
        "the surface fitted to the scan does not close around it (f = {value:.3e} ≥ 0 outside, at {at:?}): the scan is too noisy or too sparse for this fit; try a larger --tolerance"
    )]
    NotClosed {
        /// Where f was found non-negative.
        at: [f64; 3],
        /// f there.
        value: f64,
    },
    /// No vertex has a usable normal.
    #[error("no vertex of the mesh has a usable normal (all faces degenerate?)")]
    NoNormals,
    /// The fit of the chosen constraints failed; the error names the constraint or the cause.
    #[error(transparent)]
    Fit(#[from] FitError),
    /// The mesh could not be voxelized or polygonized (too large, too small, invalid).
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// No voxel centre lies inside the goal: the mesh is flat or open, or the resolution is too
    /// coarse to hold its interior.
    #[error(
        "no voxel is inside the mesh or region: it is flat or open, or the resolution is too coarse to hold its interior"
    )]
    EmptyGoal,
    /// The box of a 2D conversion has no area or is not finite, or its resolution is 0.
    #[error(
        "the box {lo:?} – {hi:?} at resolution {resolution} has no pixels: give a box of positive, finite size and a resolution of at least 1"
    )]
    Box {
        /// The lower corner given.
        lo: [f64; 2],
        /// The upper corner given.
        hi: [f64; 2],
        /// Pixels along the longer side, as given.
        resolution: usize,
    },
    /// The settings allow no iteration (`max_iterations` is 0).
    #[error("no iteration ran: max_iterations must be at least 1")]
    NoIteration,
    /// The mesh to compare with has no area to sample.
    #[error("the mesh has no area to measure from")]
    NoArea,
    /// The model to compare has no surface near its constraints.
    #[error("the model has no surface (f does not change sign near its constraints)")]
    NoSurface,
    /// `blend` was given no model.
    #[error("nothing to blend: give at least one model")]
    NothingToBlend,
    /// Models of different kernels cannot be blended (1-based model number).
    #[error(
        "model {model} has kernel {}, model 1 has {}: blend models of one kernel",
        found.name(),
        expected.name()
    )]
    KernelMismatch {
        /// 1-based number of the first model whose kernel differs from model 1's.
        model: usize,
        /// Model 1's kernel.
        expected: Kernel,
        /// That model's kernel.
        found: Kernel,
    },
}
