//! Direct editing (Turk & O'Brien 2002, §5): a session of constraints and the interpolant through
//! them, changed one edit at a time, each re-solved by updating the factorization, with undo and
//! redo and floaters that follow the surface.

use rbf_core::{Constraint, ConstraintKind, FitSettings, Interpolant, Kernel, Model};
use rbf_render::{Csg, Ray, RenderSettings, first_hits};

use crate::incremental::{IncrementalFit, Row};
use crate::{FloaterSettings, Floaters, SculptError};

/// One thing the user placed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Item {
    /// The surface passes through this point.
    Boundary([f64; 3]),
    /// f takes this positive value here.
    Interior([f64; 3], f64),
    /// f takes this negative value here.
    Exterior([f64; 3], f64),
    /// A normal handle of boundary item `boundary`: f takes `value` at the free end `tip`.
    Normal {
        /// Index of the boundary item it belongs to; deleting that item deletes the handle.
        boundary: usize,
        /// The handle's free end, in model coordinates; moving it tilts the surface.
        tip: [f64; 3],
        /// The value f is held to at `tip`: f's value there when the handle was added.
        value: f64,
    },
}

impl Item {
    fn row(&self) -> Row<3> {
        match *self {
            Item::Boundary(p) => Row {
                position: p,
                value: 0.0,
            },
            Item::Interior(p, v) | Item::Exterior(p, v) => Row {
                position: p,
                value: v,
            },
            Item::Normal { tip, value, .. } => Row {
                position: tip,
                value,
            },
        }
    }

    fn name(&self) -> &'static str {
        match self {
            Item::Boundary(_) => "a boundary constraint",
            Item::Interior(..) => "an interior constraint",
            Item::Exterior(..) => "an exterior constraint",
            Item::Normal { .. } => "a normal constraint",
        }
    }
}

/// A snapshot for undo and redo: the items and their interpolant at one point in the history.
#[derive(Clone, Debug)]
struct State {
    items: Vec<Option<Item>>,
    interpolant: Interpolant<f64, 3>,
}

/// An editing session. Item indices are stable: a deleted item's index is never reused.
///
/// ```
/// use rbf_sculpt::Session;
/// let mut s = Session::new().unwrap();
/// let before = s.interpolant().value(&[0.3, 0.2, 0.1]);
/// // Knot insertion: a boundary constraint where a ray meets the surface leaves f unchanged.
/// let i = s.pick_boundary([0.0, 0.0, 5.0], [0.0, 0.0, -1.0]).unwrap();
/// assert!((s.interpolant().value(&[0.3, 0.2, 0.1]) - before).abs() < 1e-9);
/// s.move_item(i, [0.0, 0.0, 1.5]).unwrap(); // pull the surface out
/// assert!(s.interpolant().value(&[0.0, 0.0, 1.2]) > 0.0);
/// s.undo().unwrap();
/// assert!((s.interpolant().value(&[0.3, 0.2, 0.1]) - before).abs() < 1e-9);
/// ```
pub struct Session {
    items: Vec<Option<(Item, usize)>>,
    fit: IncrementalFit<3>,
    interpolant: Interpolant<f64, 3>,
    undo: Vec<State>,
    redo: Vec<State>,
    floaters: Option<Floaters>,
    /// Length of a new normal handle.
    pub normal_length: f64,
}

impl Session {
    /// The paper's start: boundary constraints at the corners of a regular tetrahedron inscribed
    /// in the unit sphere, exterior constraints (value −1) at the corners of a cube of side 6.
    pub fn new() -> Result<Self, SculptError> {
        let items: Vec<Item> = rbf_core::shapes::sculpt_start()
            .iter()
            .map(|c| match c.kind {
                rbf_core::ConstraintKind::Exterior => Item::Exterior(c.position, c.value),
                _ => Item::Boundary(c.position),
            })
            .collect();
        Self::from_items(&items)
    }

    /// A session that starts from a model file's constraints (from `rbf fit`, `rbf convert` or
    /// a saved session): boundary, interior and exterior constraints become items as they are;
    /// a normal constraint becomes a boundary item and a normal handle at its offset point. The
    /// session re-fits them with r³ and no smoothing, so a model fitted with λ > 0 or another
    /// kernel comes back interpolating.
    ///
    /// ```
    /// use rbf_core::{FitSettings, Model, shapes};
    /// let constraints = shapes::sphere(20);
    /// let fit = rbf_core::fit(&constraints, &FitSettings::default()).unwrap();
    /// let model = Model { constraints, settings: FitSettings::default(), interpolant: fit.interpolant, report: None };
    /// let s = rbf_sculpt::Session::from_model(&model).unwrap();
    /// assert_eq!(s.items().len(), 40); // 20 boundary items and their 20 normal handles
    /// // Through the model's points, with the normal handles' values at the offset points.
    /// assert!(s.interpolant().value(&model.constraints[3].position).abs() < 1e-9);
    /// assert!(s.interpolant().value(&[0.0; 3]) > 0.0);
    /// ```
    pub fn from_model(model: &Model<3>) -> Result<Self, SculptError> {
        let system = rbf_core::System::new(&model.constraints, &model.settings)?;
        let mut items = Vec::with_capacity(system.rows());
        // The item of each constraint's own row, for the handles of normal constraints.
        let mut own_item = vec![0; model.constraints.len()];
        for ((p, &value), source) in system
            .points()
            .iter()
            .zip(system.values())
            .zip(system.sources())
        {
            let c = source.constraint;
            let item = if source.offset_point {
                Item::Normal {
                    boundary: own_item[c],
                    tip: *p,
                    value,
                }
            } else {
                own_item[c] = items.len();
                match model.constraints[c].kind {
                    ConstraintKind::Interior => Item::Interior(*p, value),
                    ConstraintKind::Exterior => Item::Exterior(*p, value),
                    _ => Item::Boundary(*p),
                }
            };
            items.push(item);
        }
        Self::from_items(&items)
    }

    /// A session over these items (normal handles refer to earlier indices).
    pub fn from_items(items: &[Item]) -> Result<Self, SculptError> {
        let rows: Vec<Row<3>> = items.iter().map(Item::row).collect();
        let fit = IncrementalFit::new(Kernel::Cubic, &rows)?;
        let interpolant = fit.interpolant()?;
        Ok(Self {
            items: items
                .iter()
                .enumerate()
                .map(|(i, it)| Some((*it, i)))
                .collect(),
            fit,
            interpolant,
            undo: Vec::new(),
            redo: Vec::new(),
            floaters: None,
            normal_length: 0.2,
        })
    }

    /// The interpolant through the current items, re-solved after every edit.
    pub fn interpolant(&self) -> &Interpolant<f64, 3> {
        &self.interpolant
    }

    /// Every item by index (`None` where deleted).
    pub fn items(&self) -> Vec<Option<Item>> {
        self.items.iter().map(|i| i.map(|(it, _)| it)).collect()
    }

    /// The floaters, once started.
    pub fn floaters(&self) -> Option<&Floaters> {
        self.floaters.as_ref()
    }

    /// Stops the floaters: later edits no longer move them (nor pay for it).
    pub fn stop_floaters(&mut self) {
        self.floaters = None;
    }

    /// Starts floaters on the surface (seeded at the boundary constraints); they follow every
    /// later edit.
    pub fn start_floaters(&mut self, settings: FloaterSettings) {
        let seeds: Vec<[f64; 3]> = self
            .items
            .iter()
            .flatten()
            .filter_map(|(it, _)| match it {
                Item::Boundary(p) => Some(*p),
                _ => None,
            })
            .collect();
        let f = self.interpolant.view();
        let mut floaters = Floaters::new(&f, &seeds, settings);
        floaters.settle(&f, 150);
        self.floaters = Some(floaters);
    }

    /// The session as a model (normal handles become interior or exterior constraints at their
    /// tips, by the sign of their value).
    pub fn model(&self) -> Model<3> {
        let constraints = self
            .items
            .iter()
            .flatten()
            .map(|(it, _)| match *it {
                Item::Boundary(p) => Constraint::boundary(p),
                Item::Interior(p, v) => Constraint::interior(p, v),
                Item::Exterior(p, v) => Constraint::exterior(p, v),
                Item::Normal { tip, value, .. } if value > 0.0 => Constraint::interior(tip, value),
                Item::Normal { tip, value, .. } if value < 0.0 => Constraint::exterior(tip, value),
                Item::Normal { tip, .. } => Constraint::boundary(tip),
            })
            .collect();
        Model {
            constraints,
            settings: FitSettings {
                kernel: Some(Kernel::Cubic),
                ..Default::default()
            },
            interpolant: self.interpolant.clone(),
            report: None,
        }
    }

    fn item(&self, index: usize) -> Result<(Item, usize), SculptError> {
        self.items
            .get(index)
            .copied()
            .flatten()
            .ok_or(SculptError::NoSuchItem(index))
    }

    fn state(&self) -> State {
        State {
            items: self.items(),
            interpolant: self.interpolant.clone(),
        }
    }

    /// Runs an edit: remembers the state for undo, re-solves, moves the floaters; on failure
    /// puts everything back.
    fn edit<T>(
        &mut self,
        change: impl FnOnce(&mut Self) -> Result<T, SculptError>,
    ) -> Result<T, SculptError> {
        let before = self.state();
        match change(self).and_then(|t| Ok((t, self.fit.interpolant()?))) {
            Ok((t, interpolant)) => {
                self.interpolant = interpolant;
                self.undo.push(before);
                self.redo.clear();
                self.follow();
                Ok(t)
            }
            Err(e) => {
                self.restore(before)?;
                Err(e)
            }
        }
    }

    fn follow(&mut self) {
        if let Some(floaters) = &mut self.floaters {
            floaters.settle(&self.interpolant.view(), 20);
        }
    }

    /// Puts back a state: the items (refactored) and the interpolant exactly as it was.
    fn restore(&mut self, state: State) -> Result<(), SculptError> {
        let live: Vec<(usize, Item)> = state
            .items
            .iter()
            .enumerate()
            .filter_map(|(i, it)| it.map(|it| (i, it)))
            .collect();
        let rows: Vec<Row<3>> = live.iter().map(|(_, it)| it.row()).collect();
        self.fit = IncrementalFit::new(Kernel::Cubic, &rows)?;
        self.items = vec![None; state.items.len()];
        for (row, (i, it)) in live.into_iter().enumerate() {
            self.items[i] = Some((it, row));
        }
        self.interpolant = state.interpolant;
        Ok(())
    }

    fn add(&mut self, item: Item) -> Result<usize, SculptError> {
        self.edit(|s| {
            let row = s.fit.push(item.row())?;
            s.items.push(Some((item, row)));
            Ok(s.items.len() - 1)
        })
    }

    /// A boundary constraint at p: the surface will pass through it.
    pub fn add_boundary(&mut self, p: [f64; 3]) -> Result<usize, SculptError> {
        self.add(Item::Boundary(p))
    }

    /// An interior constraint (value > 0).
    pub fn add_interior(&mut self, p: [f64; 3], value: f64) -> Result<usize, SculptError> {
        self.add(Item::Interior(p, value.abs()))
    }

    /// An exterior constraint (value < 0).
    pub fn add_exterior(&mut self, p: [f64; 3], value: f64) -> Result<usize, SculptError> {
        self.add(Item::Exterior(p, -value.abs()))
    }

    /// Where the ray first meets the surface.
    pub fn pick(&self, origin: [f64; 3], direction: [f64; 3]) -> Result<[f64; 3], SculptError> {
        let n = (direction.iter().map(|v| v * v).sum::<f64>()).sqrt();
        if !(n > 0.0) || !origin.iter().all(|v| v.is_finite()) {
            return Err(SculptError::NotFinite);
        }
        let ray = Ray {
            origin,
            direction: direction.map(|v| v / n),
        };
        let settings = RenderSettings::default();
        let view = [self.interpolant.view()];
        let hits = first_hits(&view, &Csg::Model(0), &[ray], &settings)
            .map_err(|e| SculptError::Singular(e.to_string()))?;
        let t = hits[0].ok_or(SculptError::Missed { origin, direction })?;
        Ok(core::array::from_fn(|d| {
            ray.origin[d] + t * ray.direction[d]
        }))
    }

    /// A boundary constraint where the ray meets the surface (knot insertion: the surface
    /// does not move).
    pub fn pick_boundary(
        &mut self,
        origin: [f64; 3],
        direction: [f64; 3],
    ) -> Result<usize, SculptError> {
        let p = self.pick(origin, direction)?;
        self.add_boundary(p)
    }

    /// Moves a boundary, interior or exterior constraint (its normal handles move with it).
    pub fn move_item(&mut self, index: usize, to: [f64; 3]) -> Result<(), SculptError> {
        let (item, _) = self.item(index)?;
        let from = match item {
            Item::Boundary(p) | Item::Interior(p, _) | Item::Exterior(p, _) => p,
            Item::Normal { .. } => {
                return Err(SculptError::WrongKind {
                    index,
                    is: item.name(),
                    wanted: "a point constraint (move a normal's tip with move_normal)",
                });
            }
        };
        let shift: [f64; 3] = core::array::from_fn(|d| to[d] - from[d]);
        self.edit(|s| {
            let handles: Vec<usize> = (0..s.items.len())
                .filter(|&j| matches!(s.items[j], Some((Item::Normal { boundary, .. }, _)) if boundary == index))
                .collect();
            let moved = match item {
                Item::Boundary(_) => Item::Boundary(to),
                Item::Interior(_, v) => Item::Interior(to, v),
                Item::Exterior(_, v) => Item::Exterior(to, v),
                n => n,
            };
            s.set(index, moved)?;
            for j in handles {
                if let Some((Item::Normal { boundary, tip, value }, _)) = s.items[j] {
                    let tip = core::array::from_fn(|d| tip[d] + shift[d]);
                    s.set(j, Item::Normal { boundary, tip, value })?;
                }
            }
            Ok(())
        })
    }

    fn set(&mut self, index: usize, item: Item) -> Result<(), SculptError> {
        let (_, row) = self.item(index)?;
        self.fit.replace(row, item.row())?;
        self.items[index] = Some((item, row));
        Ok(())
    }

    /// A normal handle at boundary constraint `index`: along the current outward normal, at
    /// `normal_length`, with the current value of f there, so that adding it changes nothing
    /// until its tip is moved (Turk & O'Brien 2002, §5).
    pub fn add_normal(&mut self, index: usize) -> Result<usize, SculptError> {
        let (item, _) = self.item(index)?;
        let Item::Boundary(p) = item else {
            return Err(SculptError::WrongKind {
                index,
                is: item.name(),
                wanted: "a boundary constraint",
            });
        };
        let g = self.interpolant.gradient(&p);
        let n = (g.iter().map(|v| v * v).sum::<f64>()).sqrt();
        if !(n > 0.0) {
            return Err(SculptError::Singular(
                "the gradient vanishes at that point".into(),
            ));
        }
        let tip = core::array::from_fn(|d| p[d] - self.normal_length * g[d] / n);
        let value = self.interpolant.value(&tip);
        self.add(Item::Normal {
            boundary: index,
            tip,
            value,
        })
    }

    /// Moves the free end of a normal handle.
    pub fn move_normal(&mut self, index: usize, to: [f64; 3]) -> Result<(), SculptError> {
        let (item, _) = self.item(index)?;
        let Item::Normal {
            boundary, value, ..
        } = item
        else {
            return Err(SculptError::WrongKind {
                index,
                is: item.name(),
                wanted: "a normal constraint",
            });
        };
        self.edit(|s| {
            s.set(
                index,
                Item::Normal {
                    boundary,
                    tip: to,
                    value,
                },
            )
        })
    }

    /// Deletes an item (a boundary constraint takes its normal handles with it).
    pub fn delete(&mut self, index: usize) -> Result<(), SculptError> {
        self.item(index)?;
        self.edit(|s| {
            let doomed: Vec<usize> = (0..s.items.len())
                .filter(|&j| {
                    j == index
                        || matches!(s.items[j], Some((Item::Normal { boundary, .. }, _)) if boundary == index)
                })
                .collect();
            for j in doomed {
                if let Some((_, row)) = s.items[j] {
                    s.fit.remove(row)?;
                    s.items[j] = None;
                }
            }
            Ok(())
        })
    }

    /// How many edits can be undone: a mark for [`Session::squash_history`].
    pub fn history_len(&self) -> usize {
        self.undo.len()
    }

    /// Makes every edit since the history had `mark` entries one step for undo: a handle
    /// dragged through many positions is one edit to the person who dragged it.
    ///
    /// ```
    /// let mut s = rbf_sculpt::Session::new().unwrap();
    /// let mark = s.history_len();
    /// for z in [1.2, 1.3, 1.4] {
    ///     s.move_item(0, [0.6, 0.6, z]).unwrap();
    /// }
    /// s.squash_history(mark);
    /// s.undo().unwrap(); // one undo: back where the drag started
    /// assert_eq!(s.history_len(), mark);
    /// assert_eq!(s.items()[0], Some(rbf_sculpt::Item::Boundary(rbf_core::shapes::tetrahedron()[0])));
    /// ```
    pub fn squash_history(&mut self, mark: usize) {
        self.undo.truncate(mark + 1);
    }

    /// Undoes the last edit: the previous interpolant, exactly.
    pub fn undo(&mut self) -> Result<(), SculptError> {
        let state = self.undo.pop().ok_or(SculptError::History("undo"))?;
        let now = self.state();
        self.restore(state)?;
        self.redo.push(now);
        self.follow();
        Ok(())
    }

    /// Redoes the last undone edit.
    pub fn redo(&mut self) -> Result<(), SculptError> {
        let state = self.redo.pop().ok_or(SculptError::History("redo"))?;
        let now = self.state();
        self.restore(state)?;
        self.undo.push(now);
        self.follow();
        Ok(())
    }
}
