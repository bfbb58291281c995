//! `rbfsurf.Session`: direct editing with the command language of `rbf sculpt -`.

use std::time::Instant;

use pyo3::prelude::*;
use rbf_core::{AnyModel, Kernel};
use rbf_sculpt::{Answer, Session as CoreSession};

use crate::error::bad;
use crate::model::Model;

/// An editing session (Turk & O'Brien 2002, §5): constraints added, moved, deleted and undone
/// one at a time, each edit solved by updating a factorization. It takes the command lines of
/// ``rbf sculpt -`` (``add X Y Z``, ``pick OX OY OZ DX DY DZ``, ``move I X Y Z``, ``normal I``,
/// ``tip I X Y Z``, ``delete I``, ``undo``, ``redo``: ``Session.COMMANDS`` lists them). A
/// model given to it must be cubic and unsmoothed (the session interpolates with r³).
///
/// >>> import rbfsurf
/// >>> s = rbfsurf.Session()          # the paper's start: a sphere of 12 constraints
/// >>> s.run("add 0 0 1.3").startswith("item 12 added")
/// True
/// >>> s.model().dim
/// 3
#[pyclass(module = "rbfsurf")]
pub(crate) struct Session {
    inner: CoreSession,
}

#[pymethods]
impl Session {
    /// The command lines a session takes, one per line with what it does.
    #[classattr]
    const COMMANDS: &'static str = rbf_sculpt::COMMANDS;

    /// A session starting from ``model`` (a 3D ``Model``), or from the paper's starting
    /// sphere.
    #[new]
    #[pyo3(signature = (model=None))]
    fn new(py: Python<'_>, model: Option<&Model>) -> PyResult<Self> {
        let inner = match model.map(|m| &m.inner) {
            None => CoreSession::new(),
            Some(AnyModel::Three(m)) => {
                // The session solves exactly with r³: refuse what it would silently change.
                if m.settings.kernel_for(3) != Kernel::Cubic {
                    return Err(bad(format!(
                        "a session fits with the cubic kernel; this model's is {}",
                        crate::model::kernel_name(m.settings.kernel_for(3))
                    )));
                }
                if m.settings.lambda != 0.0 || m.constraints.iter().any(|c| c.smoothing != 0.0) {
                    return Err(bad(
                        "a session interpolates exactly; this model was fitted with smoothing",
                    ));
                }
                py.detach(|| CoreSession::from_model(m))
            }
            Some(AnyModel::Two(_)) => {
                return Err(bad("a session edits surfaces: give a 3D model"));
            }
        }
        .map_err(bad)?;
        Ok(Self { inner })
    }

    /// Applies one command line and returns the answer ``rbf sculpt -`` prints (``""`` for a
    /// blank line or a comment); a refused command raises ``RbfError`` saying why, and leaves
    /// the session as it was.
    fn run(&mut self, py: Python<'_>, line: &str) -> PyResult<String> {
        let start = Instant::now();
        let inner = &mut self.inner;
        let answer = py.detach(|| inner.run_command(line));
        let ms = start.elapsed().as_secs_f64() * 1e3;
        match answer {
            Answer::Refused(why) => Err(bad(why)),
            other => Ok(other.line(ms)),
        }
    }

    /// Applies every line of a script (``rbf sculpt -``'s input) and returns the answers; stops
    /// at the first refused line with ``RbfError`` naming its line number.
    fn run_script(&mut self, py: Python<'_>, text: &str) -> PyResult<Vec<String>> {
        let mut answers = Vec::new();
        for (i, line) in text.lines().enumerate() {
            let answer = self
                .run(py, line)
                .map_err(|e| bad(format!("line {}: {}", i + 1, e.value(py))))?;
            answers.push(answer);
        }
        Ok(answers)
    }

    /// The current surface as a ``Model`` (constraints, settings, interpolant).
    fn model(&self) -> Model {
        Model::new(self.inner.model())
    }

    /// Live items (constraints and normal handles).
    fn __len__(&self) -> usize {
        self.inner.items().iter().flatten().count()
    }

    fn __repr__(&self) -> String {
        format!("<rbfsurf.Session: {} items>", self.__len__())
    }
}
