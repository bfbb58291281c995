//! The plain-text constraint format: one constraint per line.

use alloc::vec::Vec;

use crate::Constraint;

/// A line of a text constraint file that could not be read.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("line {line}: {message}")]
pub struct ParseError {
    /// 1-based line number.
    pub line: usize,
    /// What is wrong with the line, as a phrase for the user.
    pub message: alloc::string::String,
}

/// Reads constraints from text, one per line; numbers are separated by spaces, tabs or commas,
/// and lines that are empty or start with `#` are skipped.
///
/// In D dimensions a line holds either D + 1 numbers, a point and its value (0 gives a
/// boundary constraint, a positive value an interior one, a negative value an exterior one),
/// or 2D numbers, an oriented point (a boundary constraint plus a normal constraint against
/// the outward normal).
///
/// ```
/// let text = "# x y z value\n0 0 1 0\n0 0 0 1.5\n1 0 0  1 0 0\n";
/// let cs = rbf_core::parse_constraints::<3>(text).unwrap();
/// assert_eq!(cs.len(), 3);
/// assert_eq!(cs[1].kind, rbf_core::ConstraintKind::Interior);
/// assert_eq!(cs[2].kind, rbf_core::ConstraintKind::Normal);
/// let err = rbf_core::parse_constraints::<3>("0 0 1 0\n0 0 x 1\n").unwrap_err();
/// assert_eq!(err.line, 2);
/// ```
pub fn parse_constraints<const D: usize>(text: &str) -> Result<Vec<Constraint<D>>, ParseError> {
    let mut out = Vec::new();
    let mut numbers = Vec::with_capacity(2 * D);
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        let err = |message: alloc::string::String| ParseError { line, message };
        let body = raw.trim();
        if body.is_empty() || body.starts_with('#') {
            continue;
        }
        numbers.clear();
        for token in body
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|t| !t.is_empty())
        {
            let v: f64 = token
                .parse()
                .map_err(|_| err(alloc::format!("`{token}` is not a number")))?;
            if !v.is_finite() {
                return Err(err(alloc::format!("`{token}` is not a finite number")));
            }
            numbers.push(v);
        }
        let mut position = [0.0; D];
        if numbers.len() == D + 1 || numbers.len() == 2 * D {
            position.copy_from_slice(&numbers[..D]);
        }
        let c = if numbers.len() == D + 1 {
            let value = numbers[D];
            if value > 0.0 {
                Constraint::interior(position, value)
            } else if value < 0.0 {
                Constraint::exterior(position, value)
            } else {
                Constraint::boundary(position)
            }
        } else if numbers.len() == 2 * D {
            let mut normal = [0.0; D];
            normal.copy_from_slice(&numbers[D..]);
            if normal.iter().all(|v| *v == 0.0) {
                return Err(err("the normal has zero length".into()));
            }
            Constraint::normal(position, normal)
        } else {
            return Err(err(alloc::format!(
                "expected {} numbers (a point and its value) or {} (a point and its outward normal) in {D}D, found {}",
                D + 1,
                2 * D,
                numbers.len()
            )));
        };
        out.push(c);
    }
    Ok(out)
}

/// Reads points, one per line: D numbers separated by spaces, tabs or commas; lines that are
/// empty or start with `#` are skipped.
///
/// ```
/// let pts = rbf_core::parse_points::<2>("# x y\n0 1\n2,3\n").unwrap();
/// assert_eq!(pts, vec![[0.0, 1.0], [2.0, 3.0]]);
/// assert_eq!(rbf_core::parse_points::<2>("1 2 3").unwrap_err().line, 1);
/// ```
pub fn parse_points<const D: usize>(text: &str) -> Result<Vec<[f64; D]>, ParseError> {
    let mut out = Vec::new();
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        let body = raw.trim();
        if body.is_empty() || body.starts_with('#') {
            continue;
        }
        let mut p = [0.0; D];
        let mut count = 0;
        for token in body
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|t| !t.is_empty())
        {
            let v: f64 = token.parse().map_err(|_| ParseError {
                line,
                message: alloc::format!("`{token}` is not a number"),
            })?;
            if !v.is_finite() {
                return Err(ParseError {
                    line,
                    message: alloc::format!("`{token}` is not a finite number"),
                });
            }
            if count < D {
                p[count] = v;
            }
            count += 1;
        }
        if count != D {
            return Err(ParseError {
                line,
                message: alloc::format!("expected {D} coordinates, found {count}"),
            });
        }
        out.push(p);
    }
    Ok(out)
}
