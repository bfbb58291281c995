//! What can go wrong while sculpting.

/// An edit that cannot be made; the session is left as it was.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
#[non_exhaustive]
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
    /// A model to start from whose constraints cannot be fitted; the fit's own account.
    #[error("the model's constraints: {0}")]
    Constraints(#[from] rbf_core::FitError),
    /// Nothing to undo or redo.
    #[error("nothing to {0}")]
    History(&'static str),
}

/// A command line or script that does not parse, and where: 1-based line and column (in
/// characters) of the word or JSON token at fault.
///
/// ```
/// let e = rbf_sculpt::parse_commands("add 0 0 1\nmove 4 1 two 3\n").unwrap_err();
/// assert_eq!((e.line, e.column), (2, 10));
/// assert_eq!(e.to_string(), "line 2, column 10: `two` is not a finite number");
/// ```
#[derive(Debug, thiserror::Error, Clone, PartialEq, Eq)]
#[error("line {line}, column {column}: {problem}")]
pub struct ParseError {
    /// 1-based line of the text (1 for a single command).
    pub line: usize,
    /// 1-based column where the word at fault starts, in characters (in a JSON script, serde_json's
    /// column, which counts bytes).
    pub column: usize,
    /// What is wrong there.
    pub problem: ParseProblem,
}

/// What is wrong with a command or script, without its position.
#[derive(Debug, thiserror::Error, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum ParseProblem {
    /// A coordinate or value that is not a finite number.
    #[error("`{0}` is not a finite number")]
    NotANumber(String),
    /// An item index that is not a whole number ≥ 0.
    #[error("`{0}` is not an item number")]
    NotAnItem(String),
    /// A known command with the wrong number of arguments; its usage.
    #[error("usage: {0}")]
    Usage(String),
    /// A word that is no command.
    #[error(
        "unknown command `{0}`: the commands are add, pick, interior, exterior, move, normal, tip, delete, undo and redo"
    )]
    UnknownCommand(String),
    /// A script that is not a JSON array of edits; serde_json's account of it.
    #[error("{0}")]
    Json(String),
}
