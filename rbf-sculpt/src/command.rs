//! One-line edit commands, for typing edits at a prompt: the same edits as scripts, in words.

use crate::{Edit, ParseError, ParseProblem};

/// The commands [`parse_command`] understands, for a prompt's help.
pub const COMMANDS: &str = "\
add X Y Z                     a boundary constraint: the surface moves to pass through it
pick OX OY OZ DX DY DZ        a boundary constraint where the ray meets the surface
interior X Y Z [VALUE]        f = VALUE (default 1) there
exterior X Y Z [VALUE]        f = VALUE (default -1) there
move ITEM X Y Z               move an item
normal ITEM                   a normal handle on boundary item ITEM
tip ITEM X Y Z                move the free end of normal handle ITEM
delete ITEM                   remove an item
undo | redo";

/// Parses one command line into an edit (see [`COMMANDS`]); `Ok(None)` for a blank line or a
/// `#` comment. An error names the column of the word at fault (and line 1).
///
/// ```
/// use rbf_sculpt::{Edit, parse_command};
/// assert_eq!(parse_command("add 0 0 1.5").unwrap(), Some(Edit::AddBoundary { position: [0.0, 0.0, 1.5] }));
/// assert_eq!(parse_command("move 12 1 2 3").unwrap(), Some(Edit::Move { item: 12, to: [1.0, 2.0, 3.0] }));
/// assert_eq!(parse_command("move twelve 1 2 3").unwrap_err().column, 6);
/// ```
pub fn parse_command(line: &str) -> Result<Option<Edit>, ParseError> {
    let line = line.split('#').next().unwrap_or("");
    // Each word with its 1-based column in characters.
    let words: Vec<(usize, &str)> = line
        .split_whitespace()
        .map(|w| {
            let offset = w.as_ptr() as usize - line.as_ptr() as usize;
            (line[..offset].chars().count() + 1, w)
        })
        .collect();
    let Some(&(verb_column, verb)) = words.first() else {
        return Ok(None);
    };
    let args = &words[1..];
    let at = |column: usize, problem: ParseProblem| ParseError {
        line: 1,
        column,
        problem,
    };
    let number = |i: usize| -> Result<f64, ParseError> {
        let (column, w) = args[i];
        match w.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(at(column, ParseProblem::NotANumber(w.into()))),
        }
    };
    let item = |i: usize| -> Result<usize, ParseError> {
        let (column, w) = args[i];
        w.parse::<usize>()
            .map_err(|_| at(column, ParseProblem::NotAnItem(w.into())))
    };
    let point = |from: usize| -> Result<[f64; 3], ParseError> {
        Ok([number(from)?, number(from + 1)?, number(from + 2)?])
    };
    let arity = |counts: &[usize], usage: &str| -> Result<(), ParseError> {
        if counts.contains(&args.len()) {
            Ok(())
        } else {
            Err(at(verb_column, ParseProblem::Usage(usage.into())))
        }
    };
    let edit = match verb {
        "add" => {
            arity(&[3], "add X Y Z")?;
            Edit::AddBoundary {
                position: point(0)?,
            }
        }
        "pick" => {
            arity(&[6], "pick OX OY OZ DX DY DZ")?;
            Edit::PickBoundary {
                origin: point(0)?,
                direction: point(3)?,
            }
        }
        "interior" | "exterior" => {
            arity(&[3, 4], &format!("{verb} X Y Z [VALUE]"))?;
            let interior = verb == "interior";
            let value = if args.len() == 4 {
                number(3)?
            } else if interior {
                1.0
            } else {
                -1.0
            };
            let position = point(0)?;
            if interior {
                Edit::AddInterior { position, value }
            } else {
                Edit::AddExterior { position, value }
            }
        }
        "move" => {
            arity(&[4], "move ITEM X Y Z")?;
            Edit::Move {
                item: item(0)?,
                to: point(1)?,
            }
        }
        "normal" => {
            arity(&[1], "normal ITEM")?;
            Edit::AddNormal { item: item(0)? }
        }
        "tip" => {
            arity(&[4], "tip ITEM X Y Z")?;
            Edit::MoveNormal {
                item: item(0)?,
                to: point(1)?,
            }
        }
        "delete" => {
            arity(&[1], "delete ITEM")?;
            Edit::Delete { item: item(0)? }
        }
        "undo" => {
            arity(&[0], "undo")?;
            Edit::Undo
        }
        "redo" => {
            arity(&[0], "redo")?;
            Edit::Redo
        }
        other => {
            return Err(at(verb_column, ParseProblem::UnknownCommand(other.into())));
        }
    };
    Ok(Some(edit))
}

/// Parses a text of commands, one a line (see [`parse_command`]); an error names the line and
/// column.
///
/// ```
/// let edits = rbf_sculpt::parse_commands("# a bump\nadd 0 0 1.3\n\nundo\n").unwrap();
/// assert_eq!(edits.len(), 2);
/// assert_eq!(rbf_sculpt::parse_commands("undo\nsmooth 3").unwrap_err().line, 2);
/// ```
pub fn parse_commands(text: &str) -> Result<Vec<Edit>, ParseError> {
    let mut edits = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let edit = parse_command(line).map_err(|e| ParseError { line: n + 1, ..e })?;
        edits.extend(edit);
    }
    Ok(edits)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_edit_has_a_command() {
        let cases = [
            (
                "add 1 2 3",
                Edit::AddBoundary {
                    position: [1.0, 2.0, 3.0],
                },
            ),
            (
                "pick 0 0 5 0 0 -1",
                Edit::PickBoundary {
                    origin: [0.0, 0.0, 5.0],
                    direction: [0.0, 0.0, -1.0],
                },
            ),
            (
                "interior 0 0 0",
                Edit::AddInterior {
                    position: [0.0; 3],
                    value: 1.0,
                },
            ),
            (
                "interior 0 0 0 2.5",
                Edit::AddInterior {
                    position: [0.0; 3],
                    value: 2.5,
                },
            ),
            (
                "exterior 3 3 3",
                Edit::AddExterior {
                    position: [3.0; 3],
                    value: -1.0,
                },
            ),
            (
                "move 4 1 1 1",
                Edit::Move {
                    item: 4,
                    to: [1.0; 3],
                },
            ),
            ("normal 12", Edit::AddNormal { item: 12 }),
            (
                "tip 13 0 0 2",
                Edit::MoveNormal {
                    item: 13,
                    to: [0.0, 0.0, 2.0],
                },
            ),
            ("delete 0", Edit::Delete { item: 0 }),
            ("  undo  # back", Edit::Undo),
            ("redo", Edit::Redo),
        ];
        for (line, edit) in cases {
            assert_eq!(parse_command(line), Ok(Some(edit)), "{line}");
        }
        assert_eq!(parse_command("   # nothing"), Ok(None));
        assert_eq!(parse_command(""), Ok(None));
    }

    #[test]
    fn mistakes_say_what_was_expected() {
        for (line, column, phrase) in [
            ("add 1 2", 1, "usage: add X Y Z"),
            ("add 1 2 nan", 9, "`nan` is not a finite number"),
            ("  move -1 0 0 0", 8, "`-1` is not an item number"),
            ("undo 3", 1, "usage: undo"),
            ("smooth 3", 1, "unknown command `smooth`"),
            (
                "add 1 2 ∞ # the ∞ is one character",
                9,
                "`∞` is not a finite number",
            ),
        ] {
            let e = parse_command(line).unwrap_err();
            assert_eq!((e.line, e.column), (1, column), "{line}");
            assert!(e.problem.to_string().contains(phrase), "{line}: {e}");
        }
    }
}
