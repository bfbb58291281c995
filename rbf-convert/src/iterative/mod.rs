//! The iterative conversion of Yngve & Turk (2002), §3–§5: voxelize the mesh, then fit,
//! measure the two-way error between the goal's and the current surface's boundary voxels, and
//! add constraints where it is largest, until the surface is within a voxel of the goal (and
//! within 0.3 voxel on the whole, by the RMS).
//!
//! The loop's rooms: the goal volume, its signed distance and the choice of new constraints
//! (`goal.rs`, with the nearest-voxel search of `nearest.rs`); probes that keep a closed mesh's
//! topology (`topology.rs`); the polish against the mesh after the loop (`polish.rs`); the
//! paper's parameters (`settings.rs`); and here, the loop itself: its ranking of models, its
//! stopping rule and its budgets.

use std::time::Instant;

use rbf_core::{Constraint, ConstraintKind, FitSettings, Interpolant, Model};
use rbf_mesh::{MeshReport, TriMesh, Volume, VoxelSettings, WindingTree, voxelize};

mod goal;
mod nearest;
mod polish;
mod rival;
mod settings;
mod topology;

use goal::{Goal, summary};
use polish::{Polishing, polish_rounds};
pub use rival::RivalReport;
use rival::{refine_rival, rival_model};
pub use settings::IterativeSettings;
pub use topology::TopologyReport;
use topology::{Probe, fixes, measure, measure_cell, surface_near, thin_probes};

use crate::ConvertError;

/// The share of the budget's rows the loop's rival takes: nearly all (the rest for exterior
/// constraints far out), in normal constraints at an even spread of the vertices; with slabs,
/// [`SLAB_SHARE`] of them, and the rest for its refinement at its largest voxel errors.
const RIVAL_SHARE: f64 = 0.98;

/// The share of the budget's rows the rival's spread takes when it has slabs, before its
/// refinement: on the skull-like shell of `benches/thin_meshes.py`, 0.53 and 0.5 gave its
/// genus (2) and 0.68 one handle more; without the refinement (0.98) it was 4.2 voxels off.
/// Without slabs, the spread takes all: a bowl whose wall is 0.8 voxel, held by half as many
/// vertices, came out with genus 24 instead of 0.
const SLAB_SHARE: f64 = 0.5;

/// The topology measure's cube, in voxels, below which a polishing round's surface is
/// polygonized for it at half a voxel instead (the measure then follows the last round only).
const NEAR_CELL: f64 = 0.4;

/// Rounds of [`settle_far_field`].
const FAR_ROUNDS: usize = 4;

/// Constraint counts, boundary errors and timings of one fit-and-refine iteration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IterationReport {
    /// 1-based iteration.
    pub iteration: usize,
    /// Boundary constraints fitted this iteration.
    pub boundary: usize,
    /// Interior constraints fitted this iteration.
    pub interior: usize,
    /// Exterior constraints fitted this iteration.
    pub exterior: usize,
    /// Probes of thin gaps and parts that this iteration's surface violated, added as
    /// constraints for the next (see [`IterativeSettings::keep_topology`]).
    pub violated_probes: usize,
    /// Two-way Hausdorff error between the boundary voxels, in voxels (equation 6).
    pub max_error: f64,
    /// Root-mean-square of the same errors, in voxels.
    pub rms_error: f64,
    /// Seconds solving this iteration's fit.
    pub fit_seconds: f64,
    /// Seconds evaluating f over the volume.
    pub evaluate_seconds: f64,
    /// Seconds computing distances and errors.
    pub distance_seconds: f64,
    /// Seconds choosing new constraints.
    pub select_seconds: f64,
}

/// The goal volume, every iteration's figures, and which iteration's model was returned.
#[derive(Clone, Debug, PartialEq)]
pub struct IterativeReport {
    /// Voxels along x, y, z of the goal volume, margin included.
    pub shape: [usize; 3],
    /// Edge length of a voxel, in the mesh's units.
    pub voxel_size: f64,
    /// Whether the mesh passed the watertightness check (else winding numbers were used).
    pub watertight: bool,
    /// Every iteration run, in order (the first has `iteration` 1).
    pub iterations: Vec<IterationReport>,
    /// The loop's best iteration (see the ranking, `Rank`): its model is returned unless the
    /// rival was kept (`rival`).
    pub best: usize,
    /// For a closed mesh with [`IterativeSettings::keep_topology`]: the mesh's and the
    /// surface's genus and components, and the constraints added to keep them.
    pub topology: Option<TopologyReport>,
    /// Where the loop fell short of its goals on a closed mesh (as measured: a close loop whose
    /// polish reached the mesh's topology is not measured itself), the rival it was measured
    /// against (normal constraints at the mesh's vertices), and whether that was kept.
    pub rival: Option<RivalReport>,
}

/// Converts a mesh by the iterative method. `progress` hears of every iteration, with the model
/// it fitted.
///
/// ```
/// let mesh = rbf_mesh::TriMesh::icosphere(2);
/// let settings = rbf_convert::IterativeSettings { resolution: 24, ..Default::default() };
/// let (model, report) = rbf_convert::convert_iterative(&mesh, &settings, |_, _| {}).unwrap();
/// assert!(report.iterations[report.best - 1].max_error <= 1.5); // voxels
/// assert!(model.interpolant.value(&[0.0; 3]) > 0.0);
/// ```
pub fn convert_iterative(
    mesh: &TriMesh,
    settings: &IterativeSettings,
    progress: impl FnMut(&IterationReport, &Model<3>),
) -> Result<(Model<3>, IterativeReport), ConvertError> {
    // Checked once: a finely cut mesh's check takes a while (1.12·10⁶ triangles: 0.8 s).
    let checked = mesh.check();
    let watertight = checked.is_watertight();
    let voxels = |supersampling| VoxelSettings {
        resolution: settings.resolution,
        margin: settings.margin,
        supersampling,
        method: settings.voxel_method,
        memory_limit: rbf_solve::memory_budget(),
    };
    let density = voxelize(mesh, &voxels(settings.supersampling))?;
    // The goal's inside is the class of each voxel's centre, the same test the current surface
    // gets, so that the mesh itself would score zero; the densities give sub-voxel distances.
    let centres = voxelize(mesh, &voxels(1))?;
    let tree = WindingTree::new(mesh);
    let start = Instant::now();
    let keep = settings.keep_topology && watertight;
    let probes = if keep {
        thin_probes(
            mesh,
            &tree,
            density.voxel_size,
            2.0 * density.voxel_size,
            0.25 * density.voxel_size,
            0.5 * density.voxel_size,
        )
    } else {
        Vec::new()
    };
    let probe_seconds = start.elapsed().as_secs_f64();
    let goal = Goal::new(&density, &centres, Some(tree))?;
    let check = |f: &Interpolant<f64, 3>, constraints: &[Constraint<3>]| {
        fixes(&f.view(), &probes, constraints, goal.h)
    };
    let (model, mut report) = refine_to_goal(&goal, settings, watertight, check, progress)?;
    if !keep {
        return Ok((model, report));
    }
    let added = report.iterations[..report.best.saturating_sub(1)]
        .iter()
        .map(|it| it.violated_probes)
        .sum();
    let best = &report.iterations[report.best.saturating_sub(1)];
    let after = AfterTheLoop {
        mesh,
        checked: &checked,
        goal: &goal,
        probes: &probes,
        settings,
        added,
        loop_errors: (best.max_error, best.rms_error),
    };
    let (model, topology) = after.finish(model, probe_seconds, &mut report)?;
    report.topology = Some(topology);
    Ok((model, report))
}

/// What the stages after the loop share: the mesh and its check, the goal, the probes, and
/// the loop's kept model's probes (`added`) and voxel errors (max, RMS).
struct AfterTheLoop<'a> {
    mesh: &'a TriMesh,
    checked: &'a MeshReport,
    goal: &'a Goal,
    probes: &'a [Probe],
    settings: &'a IterativeSettings,
    added: usize,
    loop_errors: (f64, f64),
}

impl AfterTheLoop<'_> {
    /// The loop's model polished against the mesh, or its rival, and its topology.
    ///
    /// The loop's model is measured first (its topology decides whether the rival is tried),
    /// unless it came close (within [`CLOSE`] times the target) with room left in the budget
    /// and the measure's cubes are finer than [`NEAR_CELL`]: then it is polished first and the
    /// last round measured, and the loop's model is measured (and its rival tried, as it fell
    /// short) only if that round's topology is not the mesh's or there was no round. On most
    /// meshes that spares one measure, 4–6 s; a loop whose handles the polish closes is then
    /// not measured, nor its rival tried. A loop's model that did not come close meets its
    /// rival before its measure ([`AfterTheLoop::rival_first`]).
    fn finish(
        &self,
        model: Model<3>,
        probe_seconds: f64,
        report: &mut IterativeReport,
    ) -> Result<(Model<3>, TopologyReport), ConvertError> {
        let h = self.goal.h;
        let mut seconds = probe_seconds;
        let cell = measure_cell(self.mesh, self.probes, h);
        // (A model at the budget has no room for a polish: its surface would be wasted.)
        let room = rows(&model.constraints) < self.settings.max_constraints;
        let polish_first = room && self.close(self.loop_errors.0) && cell < NEAR_CELL * h;
        let (mut loop_topology, surface) = if polish_first {
            (None, surface_near(&model, 0.5 * h, &[]))
        } else {
            let fitted = if self.close(self.loop_errors.0) {
                None
            } else {
                match self.rival_first(&mut seconds, report) {
                    RivalFirst::Kept(model, t) => return Ok(with_seconds((model, t), seconds)),
                    RivalFirst::Waits(fitted) => Some(fitted),
                }
            };
            let (t, surface) = self.measure(&model, self.added, &mut seconds);
            if let Some(kept) = self.rival(&t, &mut seconds, report, fitted) {
                return Ok(with_seconds(kept, seconds));
            }
            (Some(t), surface)
        };
        let polishing = Polishing {
            mesh: self.mesh,
            checked: self.checked,
            goal: self.goal,
            probes: self.probes,
            settings: self.settings,
            added: self.added,
            measure_each: cell >= NEAR_CELL * h,
        };
        let rounds = polish_rounds(&polishing, &model, surface, loop_topology.as_ref())?;
        seconds += (rounds.iter())
            .filter_map(|(_, t)| t.map(|t| t.seconds))
            .sum::<f64>();
        // The last measured round that adds no topological difference to the loop's (a round
        // not measured is not measured now: that would cost the measure it was spared).
        for (polished, measured) in rounds.into_iter().rev() {
            let Some(t) = measured else {
                continue;
            };
            if loop_topology.is_none() && t.difference() > 0 {
                let (lt, _) = self.measure(&model, self.added, &mut seconds);
                if let Some(kept) = self.rival(&lt, &mut seconds, report, None) {
                    return Ok(with_seconds(kept, seconds));
                }
                loop_topology = Some(lt);
            }
            if loop_topology.is_none_or(|l| t.difference() <= l.difference()) {
                let polished_count = polished.constraints.len() - model.constraints.len();
                let t = TopologyReport {
                    polished: polished_count,
                    ..t
                };
                return Ok(with_seconds((polished, t), seconds));
            }
        }
        let t = match loop_topology {
            Some(t) => t,
            None => {
                let (t, _) = self.measure(&model, self.added, &mut seconds);
                if let Some(kept) = self.rival(&t, &mut seconds, report, None) {
                    return Ok(with_seconds(kept, seconds));
                }
                t
            }
        };
        Ok(with_seconds((model, t), seconds))
    }

    fn close(&self, max_error: f64) -> bool {
        max_error <= CLOSE * self.settings.target_error
    }

    /// The model's topology and the polygonization that measured it, its seconds added.
    fn measure(
        &self,
        model: &Model<3>,
        added: usize,
        seconds: &mut f64,
    ) -> (TopologyReport, Option<TriMesh>) {
        let (t, surface) = measure(
            self.mesh,
            self.checked,
            model,
            self.probes,
            self.goal.h,
            added,
        );
        *seconds += t.seconds;
        (t, surface)
    }

    /// Where the loop fell short (a topology other than the mesh's, `loop_topology`, or a
    /// surface more than [`CLOSE`] times the target off), its rival ([`AfterTheLoop::fit_rival`],
    /// or `fitted` if it was fitted before the loop's measure, `Some(None)` if that failed),
    /// measured the same way; returned, with its topology, if it stands better (it is not
    /// polished).
    fn rival(
        &self,
        loop_topology: &TopologyReport,
        seconds: &mut f64,
        report: &mut IterativeReport,
        fitted: Option<Option<Rival>>,
    ) -> Option<(Model<3>, TopologyReport)> {
        let loop_standing = Standing {
            close: self.close(self.loop_errors.0),
            topology: loop_topology.difference(),
            max_error: self.loop_errors.0,
            rms_error: self.loop_errors.1,
        };
        if loop_standing.close && loop_standing.topology == 0 {
            return None;
        }
        let mut rival = fitted.unwrap_or_else(|| self.fit_rival())?;
        // Its topology is measured only if it could win with the mesh's (the measure is most
        // of the rival's time: 10 s of 13 on the skull-like shell).
        if rival.measured.is_none() && rival.standing(0).beats(&loop_standing) {
            rival.measured = Some(self.measure(&rival.model, 0, seconds).0);
        }
        let kept = (rival.measured.as_ref())
            .is_some_and(|t| rival.standing(t.difference()).beats_loop(&loop_standing));
        self.report_rival(&rival, kept, report);
        let t = rival.measured.filter(|_| kept)?;
        Some((rival.model, TopologyReport { added: 0, ..t }))
    }

    /// Where the loop's model is not close (more than [`CLOSE`] times the target off): its
    /// rival, fitted before the loop's model is measured. A close rival with the mesh's
    /// topology beats such a model whatever its topology ([`Standing::beats_loop`]), and is
    /// then kept without that measure (4 s of the 30 a turned skull-like shell took);
    /// otherwise the rival, measured if it is close, waits for [`AfterTheLoop::rival`].
    fn rival_first(&self, seconds: &mut f64, report: &mut IterativeReport) -> RivalFirst {
        let Some(mut rival) = self.fit_rival() else {
            return RivalFirst::Waits(None);
        };
        if !rival.close {
            return RivalFirst::Waits(Some(rival));
        }
        let t = self.measure(&rival.model, 0, seconds).0;
        let kept = t.difference() == 0;
        rival.measured = Some(t);
        if !kept {
            return RivalFirst::Waits(Some(rival));
        }
        self.report_rival(&rival, true, report);
        RivalFirst::Kept(rival.model, TopologyReport { added: 0, ..t })
    }

    /// The loop's rival: normal constraints at the mesh's vertices (and slabs on thin walls),
    /// with nearly as many rows as the budget ([`RIVAL_SHARE`]), refined at its largest voxel
    /// errors and scored as the loop's models are; `None` if it could not be fitted.
    fn fit_rival(&self) -> Option<Rival> {
        let (goal, settings, h) = (self.goal, self.settings, self.goal.h);
        let half_rows = |share: f64| (share * settings.max_constraints as f64 / 2.0) as usize;
        let (vertices, with_slabs) = (half_rows(RIVAL_SHARE), half_rows(SLAB_SHARE));
        let rival = rival_model(
            self.mesh,
            goal.tree(),
            h,
            vertices,
            with_slabs,
            settings.lambda,
        )
        .ok()?;
        let rows = (RIVAL_SHARE * settings.max_constraints as f64) as usize;
        let rival = refine_rival(goal, rival, settings, rows);
        let check =
            |f: &Interpolant<f64, 3>, c: &[Constraint<3>]| fixes(&f.view(), self.probes, c, h);
        let model = settle_far_field(goal, rival, settings, check);
        let inside = goal.evaluate(&model.interpolant.view(), settings);
        let (max_error, rms_error) = summary(&goal.errors(&inside));
        Some(Rival {
            close: self.close(max_error),
            model,
            max_error,
            rms_error,
            measured: None,
        })
    }

    fn report_rival(&self, rival: &Rival, kept: bool, report: &mut IterativeReport) {
        let vertices = (rival.model.constraints.iter())
            .filter(|c| c.kind == ConstraintKind::Normal)
            .count();
        report.rival = Some(RivalReport {
            vertices,
            max_error: rival.max_error,
            rms_error: rival.rms_error,
            topology: (rival.measured.as_ref()).map(|t| (t.genus, t.components)),
            kept,
        });
    }
}

/// What [`AfterTheLoop::rival_first`] found: a rival kept, or one (if it could be fitted)
/// waiting for the loop's measure.
enum RivalFirst {
    Kept(Model<3>, TopologyReport),
    Waits(Option<Rival>),
}

/// The loop's rival, fitted and scored, with its topology once measured.
struct Rival {
    model: Model<3>,
    close: bool,
    max_error: f64,
    rms_error: f64,
    measured: Option<TopologyReport>,
}

impl Rival {
    /// How it stands with `topology` of difference from the mesh.
    fn standing(&self, topology: u64) -> Standing {
        Standing {
            close: self.close,
            topology,
            max_error: self.max_error,
            rms_error: self.rms_error,
        }
    }
}

/// Converts a planar region, given by its inside test over the box `[lo, hi]`, to a curve by the
/// iterative method (Yngve & Turk 2002, Figure 3): the same loop as [`convert_iterative`] on a
/// grid of pixels, whose densities come from `supersampling`² samples of `inside` each.
/// `resolution` counts pixels along the box's longer side; `voxel_method` is not used.
///
/// ```
/// // A disc of radius 1.
/// let inside = |p: [f64; 2]| p[0] * p[0] + p[1] * p[1] < 1.0;
/// let settings = rbf_convert::IterativeSettings { resolution: 48, ..Default::default() };
/// let (curve, report) =
///     rbf_convert::convert_iterative_2d(inside, ([-1.2; 2], [1.2; 2]), &settings, |_, _| {})
///         .unwrap();
/// assert!(report.iterations[report.best - 1].max_error <= 1.5); // pixels
/// assert!(curve.interpolant.value(&[0.0, 0.0]) > 0.0);
/// assert!(curve.interpolant.value(&[1.0, 0.0]).abs() < 0.1);
/// ```
pub fn convert_iterative_2d(
    inside: impl Fn([f64; 2]) -> bool + Sync,
    (lo, hi): ([f64; 2], [f64; 2]),
    settings: &IterativeSettings,
    progress: impl FnMut(&IterationReport, &Model<2>),
) -> Result<(Model<2>, IterativeReport), ConvertError> {
    let longest = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    let h = longest / settings.resolution as f64;
    let finite = lo.iter().chain(&hi).all(|v| v.is_finite());
    if !(finite && hi[0] > lo[0] && hi[1] > lo[1] && h > 0.0 && h.is_finite()) {
        return Err(ConvertError::Box {
            lo,
            hi,
            resolution: settings.resolution,
        });
    }
    let m = settings.margin;
    let side = |d: usize| {
        (((hi[d] - lo[d]) / h).ceil().max(1.0) as usize).saturating_add(m.saturating_mul(2))
    };
    let shape = [side(0), side(1), 1];
    rbf_mesh::check_volume_size(shape, rbf_solve::memory_budget())?;
    // Pixel (i, j) is centred at lo + (i − m + ½)·h, as the voxelizer places voxels.
    let origin = [
        lo[0] - (m as f64 - 0.5) * h,
        lo[1] - (m as f64 - 0.5) * h,
        0.0,
    ];
    let s = settings.supersampling.max(1);
    let mut density = Volume::filled(origin, h, shape, 0.0_f32);
    let mut centres = density.clone();
    for i in 0..shape[0] {
        for j in 0..shape[1] {
            let c = density.centre(i, j, 0);
            let sample = |a: usize, b: usize| {
                let at = |k: usize| (k as f64 + 0.5) / s as f64 - 0.5;
                inside([c[0] + at(a) * h, c[1] + at(b) * h])
            };
            let count = (0..s * s).filter(|&k| sample(k / s, k % s)).count();
            let v = density.index(i, j, 0);
            density.data[v] = count as f32 / (s * s) as f32;
            centres.data[v] = if inside([c[0], c[1]]) { 1.0 } else { 0.0 };
        }
    }
    let goal = Goal::new(&density, &centres, None)?;
    refine_to_goal(&goal, settings, true, |_, _| (0, Vec::new()), progress)
}

/// The loop of Yngve & Turk (2002, §5): fit, evaluate, measure, add constraints, until the
/// error is within `target_error` voxels (and its RMS within `target_rms`) or a limit of §5.4 is
/// reached; returns the best model.
fn refine_to_goal<const D: usize>(
    goal: &Goal,
    settings: &IterativeSettings,
    watertight: bool,
    check: impl Fn(&Interpolant<f64, D>, &[Constraint<D>]) -> (usize, Vec<Constraint<D>>),
    mut progress: impl FnMut(&IterationReport, &Model<D>),
) -> Result<(Model<D>, IterativeReport), ConvertError> {
    let fit_settings = FitSettings {
        lambda: settings.lambda,
        ..Default::default()
    };
    let mut constraints: Vec<Constraint<D>> = goal.initial(settings);
    let mut report = IterativeReport {
        shape: goal.shape,
        voxel_size: goal.h,
        watertight,
        iterations: Vec::new(),
        best: 0,
        topology: None,
        rival: None,
    };
    let mut best: Option<(Rank, Model<D>)> = None;
    // Iterations since the last progress: a better model, or either error below every one
    // before it (the RMS by a hundredth).
    let mut since_progress = 0;
    let (mut lowest_max, mut lowest_rms) = (f64::INFINITY, f64::INFINITY);
    for iteration in 1..=settings.max_iterations {
        let t = Instant::now();
        let fit = rbf_solve::fit(&constraints, &fit_settings)?;
        let fit_seconds = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let inside = goal.evaluate(&fit.interpolant.view(), settings);
        let evaluate_seconds = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let errors = goal.errors(&inside);
        let (max_error, rms_error) = summary(&errors);
        let distance_seconds = t.elapsed().as_secs_f64();
        let (violations, fixes) = check(&fit.interpolant, &constraints);
        let model = Model {
            constraints: constraints.clone(),
            settings: fit_settings,
            interpolant: fit.interpolant,
            report: Some(fit.report),
        };
        let count = |k| constraints.iter().filter(|c| c.kind == k).count();
        let (boundary, interior, exterior) = (
            count(ConstraintKind::Boundary),
            count(ConstraintKind::Interior),
            count(ConstraintKind::Exterior),
        );
        let t = Instant::now();
        let violated = violations > 0;
        let rank = Rank::new(violations, max_error, rms_error, settings);
        let better = best.as_ref().is_none_or(|(r, _)| rank < *r);
        if better {
            report.best = iteration;
        }
        // Probes to add: all of them, unless they would take more than half the room left;
        // then at most a share of the constraints there are (at least as many as the loop
        // starts with, at most half the room), spread evenly. A mesh thin everywhere (a bowl's
        // wall) has a probe at nearly every vertex, and taken at once they filled the budget
        // in the first iterations, before the loop had placed its own constraints. While
        // probes wait, patience counts no stall (the refinement still hears of one).
        let room = settings.max_constraints.saturating_sub(constraints.len());
        let share = if fixes.len() > room / 2 {
            let share = (settings.max_growth * constraints.len() as f64).ceil() as usize;
            share.max(settings.initial_constraints).min(room / 2)
        } else {
            fixes.len()
        };
        let waiting = fixes.len() > share;
        let progressed = better || max_error < lowest_max || rms_error < 0.99 * lowest_rms;
        if progressed || waiting {
            since_progress = 0;
        } else {
            since_progress += 1;
        }
        lowest_max = lowest_max.min(max_error);
        lowest_rms = lowest_rms.min(rms_error);
        let within = max_error <= settings.target_error && rms_error <= settings.target_rms;
        let done = (within && !violated)
            || since_progress >= settings.patience
            || iteration == settings.max_iterations
            || constraints.len() >= settings.max_constraints;
        let (violated_probes, added) = if done {
            (0, 0)
        } else {
            let fixes = spread_out(fixes, room.min(share));
            let probes = fixes.len();
            constraints.extend(fixes);
            // Once the errors are within their targets, only the probes are added.
            let refined = if within {
                0
            } else {
                goal.refine(&errors, &mut constraints, settings, !progressed)
            };
            (probes, probes + refined)
        };
        let it = IterationReport {
            iteration,
            boundary,
            interior,
            exterior,
            violated_probes,
            max_error,
            rms_error,
            fit_seconds,
            evaluate_seconds,
            distance_seconds,
            select_seconds: t.elapsed().as_secs_f64(),
        };
        progress(&it, &model);
        if better {
            best = Some((rank, model));
        }
        report.iterations.push(it);
        if done || added == 0 {
            break;
        }
    }
    let (_, model) = best.ok_or(ConvertError::NoIteration)?;
    Ok((settle_far_field(goal, model, settings, check), report))
}

/// The kept model with f made negative where it was positive far outside the volume
/// ([`Goal::far_field_fixes`]), a few rounds of exterior constraints there and a refit. Only
/// the kept model is checked: an early model's far field says nothing of the last one's, and
/// constraints added for it would only steer the loop. A round whose refit fails or violates
/// more probes (`check`) than the model before it is not taken.
fn settle_far_field<const D: usize>(
    goal: &Goal,
    mut model: Model<D>,
    settings: &IterativeSettings,
    check: impl Fn(&Interpolant<f64, D>, &[Constraint<D>]) -> (usize, Vec<Constraint<D>>),
) -> Model<D> {
    let mut violated = check(&model.interpolant, &model.constraints).0;
    for _ in 0..FAR_ROUNDS {
        let fixes = goal.far_field_fixes(&model.interpolant.view());
        let room = settings
            .max_constraints
            .saturating_sub(rows(&model.constraints));
        if fixes.is_empty() || room == 0 {
            break;
        }
        let mut constraints = model.constraints.clone();
        constraints.extend(fixes.into_iter().take(room));
        let Ok(fit) = rbf_solve::fit(&constraints, &model.settings) else {
            break;
        };
        let now = check(&fit.interpolant, &constraints).0;
        if now > violated {
            break;
        }
        violated = now;
        model = Model {
            constraints,
            interpolant: fit.interpolant,
            report: Some(fit.report),
            ..model
        };
    }
    model
}

/// The model with its topology, whose seconds are all the measures' (and the probes').
fn with_seconds(
    (model, t): (Model<3>, TopologyReport),
    seconds: f64,
) -> (Model<3>, TopologyReport) {
    (model, TopologyReport { seconds, ..t })
}

/// Rows of the system `constraints` make (a normal constraint, the rival's, takes two): the
/// budget counts rows.
fn rows<const D: usize>(constraints: &[Constraint<D>]) -> usize {
    constraints.iter().map(Constraint::rows).sum()
}

/// At most `count` of `constraints`, spread evenly: one in each cube of a lattice coarse enough
/// to hold no more (the first in each; often fewer than `count`, as each coarsening by a
/// quarter empties many cubes), all of them if they are few enough.
fn spread_out<const D: usize>(constraints: Vec<Constraint<D>>, count: usize) -> Vec<Constraint<D>> {
    if constraints.len() <= count {
        return constraints;
    }
    let positions: Vec<[f64; 3]> = constraints
        .iter()
        .map(|c| core::array::from_fn(|d| if d < D { c.position[d] } else { 0.0 }))
        .collect();
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in &positions {
        for d in 0..3 {
            lo[d] = lo[d].min(p[d]);
            hi[d] = hi[d].max(p[d]);
        }
    }
    let extent = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
    let mut cube = (extent / 1024.0).max(f64::MIN_POSITIVE);
    loop {
        let chosen = topology::one_per_cube(&positions, cube, |_| 0);
        if chosen.len() <= count || !(cube < extent) {
            let mut keep = vec![false; constraints.len()];
            for &i in chosen.iter().take(count) {
                keep[i] = true;
            }
            return constraints
                .into_iter()
                .zip(keep)
                .filter_map(|(c, k)| k.then_some(c))
                .collect();
        }
        cube *= 1.25;
    }
}

/// How the loop ranks its models, best first: those close to the mesh (a maximum error within
/// twice the target) that leave no probe violated, those within the RMS target first; then
/// every other by its maximum error, the probes it violates, and its RMS error. A model that
/// keeps the topology but misses the mesh by several voxels is not preferred to one close to
/// it with a probe or two violated. Among close models the RMS target comes before the
/// maximum: the polish after the loop mends a surface where it strays more than a voxel, not
/// one a fraction of a voxel off on the whole (a turned knot's loop: a model a voxel off at
/// most with 0.35 RMS was preferred to one at 1.41 with 0.28, and ended 0.27 voxel RMS from
/// the mesh).
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
struct Rank {
    not_close_or_violated: bool,
    /// Close, with no probe violated, but above the RMS target.
    rough: bool,
    max_error: f64,
    violations: usize,
    rms_error: f64,
}

/// How a finished model stands against the mesh: for the loop's model and its rival.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Standing {
    /// Its maximum voxel error within [`CLOSE`] times the target.
    close: bool,
    /// Its genus and component differences from the mesh, summed.
    topology: u64,
    max_error: f64,
    rms_error: f64,
}

impl Standing {
    /// Whether this model is to be kept instead of `other`. Both close: the smaller topological
    /// difference, then the smaller maximum error, then RMS. Otherwise only a model no worse
    /// in any of closeness, topology and maximum error, and better in one (or, tied in all
    /// three, in RMS): ranked by its
    /// maximum error alone, a rival 2.85 voxels off with genus 22 beat the sword's loop, 2.9
    /// voxels off with its genus; ranked by topology first, one 5 voxels off (17.7 to the mesh)
    /// beat a bowl's loop 2.8 off with two extra handles.
    fn beats(&self, other: &Standing) -> bool {
        let key = |s: &Standing| (s.topology, s.max_error, s.rms_error);
        if self.close && other.close {
            return key(self) < key(other);
        }
        self.close >= other.close
            && self.topology <= other.topology
            && self.max_error <= other.max_error
            && key(self) < key(other)
    }

    /// Whether this rival is to be kept instead of the loop's model `other`: it
    /// [beats](Standing::beats) it, and where the loop's model is close, also has less of the
    /// topology wrong. A close loop's model has its polish still ahead, which may mend its
    /// topology (the falcon statue's: a difference of 5 → 3, where a rival 1.41 voxels off to
    /// the loop's 2.0 had 5 too, and was kept for being closer).
    fn beats_loop(&self, other: &Standing) -> bool {
        self.beats(other) && (!other.close || self.topology < other.topology)
    }
}

/// Maximum errors, as multiples of the target, that count as close.
const CLOSE: f64 = 2.0;

impl Rank {
    fn new(
        violations: usize,
        max_error: f64,
        rms_error: f64,
        settings: &IterativeSettings,
    ) -> Self {
        let not_close_or_violated = violations > 0 || !(max_error <= CLOSE * settings.target_error);
        Self {
            not_close_or_violated,
            rough: !not_close_or_violated && !(rms_error <= settings.target_rms),
            max_error,
            violations,
            rms_error,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{IterativeSettings, Rank, Standing, spread_out};

    fn standing(close: bool, topology: u64, max_error: f64, rms_error: f64) -> Standing {
        Standing {
            close,
            topology,
            max_error,
            rms_error,
        }
    }

    #[test]
    fn a_rival_is_kept_only_where_it_stands_better() {
        // The skull-like shell: the loop 9.3 voxels off with genus 15 in six pieces; the
        // rival 3.2 off with the mesh's genus.
        assert!(standing(false, 0, 3.16, 0.28).beats(&standing(false, 18, 9.27, 1.78)));
        // The sword: not a rival as far off with 22 handles.
        assert!(!standing(false, 22, 2.85, 0.42).beats(&standing(false, 0, 2.9, 0.73)));
        // The bowl under a voxel: not a rival with fewer handles but farther off.
        assert!(!standing(false, 1, 5.0, 0.55).beats(&standing(false, 3, 2.83, 0.82)));
        // Close beats far, unless it has more topology wrong.
        assert!(standing(true, 0, 1.7, 0.3).beats(&standing(false, 0, 2.9, 0.7)));
        assert!(!standing(true, 2, 1.7, 0.3).beats(&standing(false, 0, 2.9, 0.7)));
        // Both close: topology first, then the errors.
        assert!(standing(true, 0, 1.73, 0.3).beats(&standing(true, 4, 1.41, 0.38)));
        assert!(standing(true, 0, 1.0, 0.2).beats(&standing(true, 0, 1.41, 0.2)));
        assert!(!standing(true, 0, 1.41, 0.2).beats(&standing(true, 0, 1.41, 0.2)));
        // A close loop's model, whose polish is still ahead, gives way to a rival only for
        // less of the topology wrong: not to the falcon statue's, closer with as many wrong.
        assert!(standing(true, 5, 1.41, 0.3).beats(&standing(true, 5, 2.0, 0.34)));
        assert!(!standing(true, 5, 1.41, 0.3).beats_loop(&standing(true, 5, 2.0, 0.34)));
        assert!(standing(true, 1, 1.73, 0.32).beats_loop(&standing(true, 4, 1.41, 0.38)));
        // A far loop's model gives way as before.
        assert!(standing(true, 0, 1.41, 0.16).beats_loop(&standing(false, 18, 9.27, 1.78)));
    }

    #[test]
    fn close_models_within_the_rms_target_rank_first() {
        let settings = IterativeSettings::default();
        let rank = |max, rms, violations| Rank::new(violations, max, rms, &settings);
        // The turned knot's iterations 13 and 20.
        assert!(rank(1.41, 0.277, 0) < rank(1.0, 0.351, 0));
        // Both within the RMS target, or both above it: the maximum decides.
        assert!(rank(1.0, 0.29, 0) < rank(1.41, 0.2, 0));
        assert!(rank(1.0, 0.5, 0) < rank(1.41, 0.31, 0));
        // Far models, or close ones with a probe violated, by their maximum error as before.
        assert!(rank(2.5, 0.9, 0) < rank(3.0, 0.2, 0));
        assert!(rank(1.41, 0.5, 1) < rank(1.73, 0.2, 1));
        // Any close model with no probe violated before every other.
        assert!(rank(2.0, 0.9, 0) < rank(1.0, 0.1, 1));
    }

    #[test]
    fn a_close_rival_with_the_topology_beats_a_far_loop_whatever_its_topology() {
        // What lets `rival_first` keep such a rival without measuring the loop's model: close
        // means within CLOSE (2) times the target (1 voxel), far beyond it.
        for rival_max in [0.5, 1.0, 1.41, 2.0] {
            for rival_rms in [0.05, 0.3, 1.0] {
                let rival = standing(true, 0, rival_max, rival_rms);
                for loop_max in [2.0001, 2.45, 9.3] {
                    for loop_rms in [0.01, 0.4, 2.0] {
                        for topology in [0, 1, 18] {
                            let far = standing(false, topology, loop_max, loop_rms);
                            assert!(rival.beats_loop(&far), "{rival:?} against {far:?}");
                        }
                    }
                }
            }
        }
    }
    use rbf_core::Constraint;

    #[test]
    fn spread_out_keeps_at_most_the_count_and_covers_the_whole_extent() {
        // 1000 points crowded at one end of a segment, 10 spread over the rest.
        let crowded = (0..1000).map(|i| [i as f64 * 1e-4, 0.0, 0.0]);
        let spread = (1..=10).map(|i| [i as f64, 0.0, 0.0]);
        let all: Vec<Constraint<3>> = crowded.chain(spread).map(Constraint::boundary).collect();
        assert_eq!(spread_out(all.clone(), 2000).len(), all.len());
        let kept = spread_out(all, 20);
        assert!(kept.len() <= 20 && kept.len() >= 10, "{}", kept.len());
        // Every one of the far points keeps its own cube: the crowd does not take the count.
        for i in 1..=10 {
            assert!(kept.iter().any(|c| c.position[0] == i as f64), "{i}");
        }
        assert!(spread_out(Vec::<Constraint<3>>::new(), 0).is_empty());
    }
}
