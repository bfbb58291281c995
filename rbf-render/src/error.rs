//! What can go wrong when rendering.

/// A render that cannot be made: each variant names the setting or the part at fault.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RenderError {
    /// Image sides must be 1 to [`crate::MAX_SIDE`] pixels.
    #[error("an image of {width} × {height} pixels: each side must be 1 to 16384")]
    Size {
        /// Requested width.
        width: u32,
        /// Requested height.
        height: u32,
    },
    /// Nothing to render.
    #[error("nothing to render: give at least one object")]
    NoObjects,
    /// A CSG expression names a model that is not there.
    #[error("model {index} does not exist: there are {models} models")]
    NoSuchModel {
        /// The 0-based model index in the `Csg::Model` leaf, ≥ `models`.
        index: usize,
        /// How many model views were passed to the render.
        models: usize,
    },
    /// A union or intersection of nothing.
    #[error("a union or intersection needs at least one part")]
    EmptyCsg,
    /// Anti-aliasing takes 1 to 16 rays per pixel along each axis.
    #[error("samples must be 1 to 16 per axis, not {0}")]
    Samples(u32),
    /// A plot's box has no area or is not finite.
    #[error("the plot's bounds {lo:?} – {hi:?} are empty or not finite")]
    PlotBounds {
        /// The lower corner asked for.
        lo: [f64; 2],
        /// The upper corner asked for.
        hi: [f64; 2],
    },
    /// No object's surface crosses its box: there is nothing to aim a camera at.
    #[error("no object has a surface to show")]
    NoSurface,
    /// The PNG encoder failed.
    #[error("PNG encoding failed: {0}")]
    Png(#[from] png::EncodingError),
}
