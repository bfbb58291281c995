//! One command line applied to a session and answered, as the prompt of `rbf sculpt -` and the
//! studio's command box both do.

use crate::{Session, parse_command};

/// What a command line did.
#[derive(Clone, Debug, PartialEq)]
pub enum Answer {
    /// A blank line or a `#` comment: nothing to do.
    Nothing,
    /// The edit was applied.
    Applied {
        /// The index of the item the edit added, if it added one.
        added: Option<usize>,
        /// Live items after the edit.
        items: usize,
        /// f at the origin after the edit, a quick check that the surface changed.
        value_at_origin: f64,
    },
    /// The line does not parse, or the session refused the edit and is as it was; why.
    Refused(String),
}

impl Answer {
    /// The answer as one line, given how long the solve took: `item 12 added; 13 items; solved
    /// in 1.20 ms; f(0, 0, 0) = +0.0537`, `refused: …`, or empty for [`Answer::Nothing`].
    ///
    /// ```
    /// let mut s = rbf_sculpt::Session::new().unwrap();
    /// let line = s.run_command("add 0 0 1.3").line(1.0);
    /// assert!(line.starts_with("item 12 added; 13 items; solved in 1.00 ms"), "{line}");
    /// assert_eq!(s.run_command("add 0 0").line(0.0), "refused: usage: add X Y Z");
    /// ```
    pub fn line(&self, solve_ms: f64) -> String {
        match self {
            Answer::Nothing => String::new(),
            Answer::Applied {
                added,
                items,
                value_at_origin,
            } => {
                let what = added.map_or("done".to_string(), |i| format!("item {i} added"));
                format!(
                    "{what}; {items} items; solved in {solve_ms:.2} ms; f(0, 0, 0) = {value_at_origin:+.4}"
                )
            }
            Answer::Refused(why) => format!("refused: {why}"),
        }
    }
}

impl Session {
    /// Parses one line of the command language ([`crate::COMMANDS`]) and applies it. A refused
    /// line or edit leaves the session as it was.
    ///
    /// ```
    /// use rbf_sculpt::{Answer, Session};
    /// let mut s = Session::new().unwrap();
    /// assert!(matches!(s.run_command("add 0 0 1.3"), Answer::Applied { added: Some(12), .. }));
    /// assert_eq!(s.run_command("# a comment"), Answer::Nothing);
    /// assert!(matches!(s.run_command("move 99 0 0 0"), Answer::Refused(_)));
    /// ```
    pub fn run_command(&mut self, line: &str) -> Answer {
        let edit = match parse_command(line) {
            Ok(Some(edit)) => edit,
            Ok(None) => return Answer::Nothing,
            Err(e) => return Answer::Refused(e.problem.to_string()),
        };
        let before = self.items().len();
        match self.apply(&edit) {
            Ok(()) => {
                let items = self.items();
                Answer::Applied {
                    added: (items.len() > before).then(|| items.len() - 1),
                    items: items.iter().flatten().count(),
                    value_at_origin: self.interpolant().value(&[0.0; 3]),
                }
            }
            Err(e) => Answer::Refused(e.to_string()),
        }
    }
}
