//! What can go wrong while sculpting.

/// An edit that cannot be made; the session is left as it was.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum SculptError {
    /// No item with this index.
    #[error("there is no item {0}")]
    NoSuchItem(usize),
    /// The item is not of the kind the edit needs.
    #[error("item {index} is {is}, not {wanted}")]
    WrongKind {
        /// Index of the item in the session's item list.
        index: usize,
        /// The item's kind as a phrase ("a boundary constraint", …).
        is: &'static str,
        /// The kind the edit needs, as a phrase.
        wanted: &'static str,
    },
    /// A coordinate or value that is NaN or infinite.
    #[error("a coordinate or value is not finite")]
    NotFinite,
    /// The system would become singular.
    #[error("the edit would make the system singular: {0}")]
    Singular(String),
    /// A pick ray that meets no surface.
    #[error("the ray from {origin:?} along {direction:?} meets no surface")]
    Missed {
        /// Start of the pick ray, in model coordinates.
        origin: [f64; 3],
        /// Direction of the pick ray (any length).
        direction: [f64; 3],
    },
    /// Nothing to undo or redo.
    #[error("nothing to {0}")]
    History(&'static str),
}
