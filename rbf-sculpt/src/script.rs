//! Replayable sessions: a JSON list of edits.

use serde::Deserialize;

use crate::{ParseError, ParseProblem, SculptError, Session};

/// One edit of a script, as JSON: `{"add_boundary": {"position": [x, y, z]}}`, `"undo"`, …
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Edit {
    /// A boundary constraint at a point (the surface moves to pass through it).
    AddBoundary {
        /// The point the surface must pass through, in model coordinates.
        position: [f64; 3],
    },
    /// A boundary constraint where a ray meets the surface (the surface does not move).
    PickBoundary {
        /// Start of the pick ray, in model coordinates.
        origin: [f64; 3],
        /// Direction of the pick ray (any length).
        direction: [f64; 3],
    },
    /// An interior constraint: f takes a positive value at a point inside.
    AddInterior {
        /// The constrained point, in model coordinates.
        position: [f64; 3],
        /// f there (> 0).
        value: f64,
    },
    /// An exterior constraint: f takes a negative value at a point outside.
    AddExterior {
        /// The constrained point, in model coordinates.
        position: [f64; 3],
        /// f there (< 0).
        value: f64,
    },
    /// Move a point constraint.
    Move {
        /// Item index.
        item: usize,
        /// New position.
        to: [f64; 3],
    },
    /// A normal handle at a boundary constraint.
    AddNormal {
        /// Index of the boundary item that gets the handle.
        item: usize,
    },
    /// Move a normal handle's free end.
    MoveNormal {
        /// Index of the normal item (the handle, not its boundary item).
        item: usize,
        /// New tip.
        to: [f64; 3],
    },
    /// Delete an item.
    Delete {
        /// Item index.
        item: usize,
    },
    /// Undo the last edit.
    Undo,
    /// Redo the last undone edit.
    Redo,
}

/// Parses a script: a JSON array of edits.
///
/// ```
/// let edits = rbf_sculpt::parse_script(r#"[{"add_boundary": {"position": [0, 0, 1.5]}}, "undo"]"#).unwrap();
/// assert_eq!(edits.len(), 2);
/// ```
pub fn parse_script(text: &str) -> Result<Vec<Edit>, ParseError> {
    serde_json::from_str(text).map_err(|e| {
        // serde_json's message ends with its own " at line L column C": said once, by ParseError.
        let message = e.to_string();
        let position = format!(" at line {} column {}", e.line(), e.column());
        ParseError {
            line: e.line(),
            column: e.column(),
            problem: ParseProblem::Json(message.trim_end_matches(&position).into()),
        }
    })
}

impl Session {
    /// Applies one edit.
    pub fn apply(&mut self, edit: &Edit) -> Result<(), SculptError> {
        match *edit {
            Edit::AddBoundary { position } => self.add_boundary(position).map(drop),
            Edit::PickBoundary { origin, direction } => {
                self.pick_boundary(origin, direction).map(drop)
            }
            Edit::AddInterior { position, value } => self.add_interior(position, value).map(drop),
            Edit::AddExterior { position, value } => self.add_exterior(position, value).map(drop),
            Edit::Move { item, to } => self.move_item(item, to),
            Edit::AddNormal { item } => self.add_normal(item).map(drop),
            Edit::MoveNormal { item, to } => self.move_normal(item, to),
            Edit::Delete { item } => self.delete(item),
            Edit::Undo => self.undo(),
            Edit::Redo => self.redo(),
        }
    }
}
