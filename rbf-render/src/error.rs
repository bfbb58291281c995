//! What can go wrong when rendering.

/// A render that cannot be made.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
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
    /// A setting out of range (samples per axis, plot bounds), or nothing to show; the message
    /// says which.
    #[error("{0}")]
    Setting(String),
    /// A mesh that cannot be drawn (no triangles, an index out of range, a non-finite vertex).
    #[error("mesh: {0}")]
    Mesh(String),
    /// The PNG encoder failed; its message.
    #[error("PNG encoding failed: {0}")]
    Png(String),
}
