//! Yngve & Turk 2002, Figure 3, in 2D: their iterative refinement on a pixel grid — fit,
//! compare the current curve's boundary pixels with the goal's, add constraints where the
//! two-way error is largest (pruned as in §5.3) — for the gallery.

use rbf_core::{Constraint, FitSettings, Model};

/// A teapot in silhouette: body, lid knob, spout and a ring handle (its hole makes two curves).
fn teapot(p: [f64; 2]) -> bool {
    let [x, y] = p;
    let body = (x / 1.0).powi(2) + (y / 0.7).powi(2) < 1.0;
    let knob = x * x + (y - 0.78).powi(2) < 0.15 * 0.15;
    // The spout: a band 0.16 wide along the segment from (0.8, −0.1) to (1.55, 0.55).
    let (ax, ay, bx, by) = (0.8, -0.1, 1.55, 0.55);
    let t = (((x - ax) * (bx - ax) + (y - ay) * (by - ay))
        / ((bx - ax).powi(2) + (by - ay).powi(2)))
    .clamp(0.0, 1.0);
    let spout = (x - ax - t * (bx - ax)).hypot(y - ay - t * (by - ay)) < 0.08 + 0.06 * (1.0 - t);
    let r = (x + 1.05).hypot(y - 0.05);
    let handle = (0.28..0.42).contains(&r) && x < -0.85;
    body || knob || spout || handle
}

/// One refinement step's figures and its model.
pub(crate) struct Step {
    pub(crate) model: Model<2>,
    pub(crate) max_error: f64,
    pub(crate) rms_error: f64,
}

/// The grid: `n` pixels across the box [lo, hi].
struct Grid {
    n: [usize; 2],
    lo: [f64; 2],
    h: f64,
}

impl Grid {
    fn point(&self, i: usize) -> [f64; 2] {
        let (x, y) = (i % self.n[0], i / self.n[0]);
        [
            self.lo[0] + (x as f64 + 0.5) * self.h,
            self.lo[1] + (y as f64 + 0.5) * self.h,
        ]
    }

    /// Pixels with a 4-neighbour of the other class.
    fn boundary(&self, inside: &[bool]) -> Vec<usize> {
        let [nx, ny] = self.n;
        (0..nx * ny)
            .filter(|&i| {
                let (x, y) = (i % nx, i / nx);
                let mut other = false;
                if x > 0 {
                    other |= inside[i - 1] != inside[i];
                }
                if x + 1 < nx {
                    other |= inside[i + 1] != inside[i];
                }
                if y > 0 {
                    other |= inside[i - nx] != inside[i];
                }
                if y + 1 < ny {
                    other |= inside[i + nx] != inside[i];
                }
                other
            })
            .collect()
    }

    /// Distance in pixels from pixel i to the nearest of `set`.
    fn distance(&self, i: usize, set: &[usize]) -> f64 {
        let nx = self.n[0];
        let (x, y) = ((i % nx) as f64, (i / nx) as f64);
        set.iter()
            .map(|&j| ((j % nx) as f64 - x).hypot((j / nx) as f64 - y))
            .fold(f64::INFINITY, f64::min)
    }
}

/// Runs `steps` iterations of the refinement on the teapot, on an `n`-pixel-wide grid.
pub(crate) fn refine(n: usize, steps: usize) -> Result<Vec<Step>, rbf_core::FitError> {
    let (lo, hi) = ([-1.7, -1.2], [1.9, 1.2]);
    let h = (hi[0] - lo[0]) / n as f64;
    let grid = Grid {
        n: [n, ((hi[1] - lo[1]) / h).ceil() as usize],
        lo,
        h,
    };
    let pixels = grid.n[0] * grid.n[1];
    let goal: Vec<bool> = (0..pixels).map(|i| teapot(grid.point(i))).collect();
    let goal_boundary = grid.boundary(&goal);
    // Signed distance of the goal, in model units, positive inside.
    let sd = |i: usize| -> f64 {
        let d = grid.distance(i, &goal_boundary) * h;
        if goal[i] { d } else { -d }
    };
    // Start: boundary constraints spread over the goal's boundary (farthest-point order), the
    // deepest interior pixel, and exterior constraints at the box's corners and mid-sides.
    let mut chosen = vec![goal_boundary[0]];
    while chosen.len() < 12 {
        let next = goal_boundary
            .iter()
            .copied()
            .max_by(|&a, &b| {
                grid.distance(a, &chosen)
                    .total_cmp(&grid.distance(b, &chosen))
            })
            .unwrap_or(goal_boundary[0]);
        chosen.push(next);
    }
    let mut constraints: Vec<Constraint<2>> = chosen
        .iter()
        .map(|&i| Constraint::boundary(grid.point(i)))
        .collect();
    let deepest = (0..pixels)
        .max_by(|&a, &b| sd(a).total_cmp(&sd(b)))
        .unwrap_or(0);
    constraints.push(Constraint::interior(grid.point(deepest), sd(deepest)));
    for (x, y) in [
        (0, 0),
        (1, 0),
        (0, 1),
        (1, 1),
        (0, 2),
        (1, 2),
        (2, 0),
        (2, 1),
    ] {
        let fx = [lo[0], hi[0], 0.5 * (lo[0] + hi[0])][x];
        let fy = [lo[1], hi[1], 0.5 * (lo[1] + hi[1])][y];
        if (x, y) != (2, 2) {
            let i = {
                let px = (((fx - lo[0]) / h) as usize).min(grid.n[0] - 1);
                let py = (((fy - lo[1]) / h) as usize).min(grid.n[1] - 1);
                py * grid.n[0] + px
            };
            constraints.push(Constraint::exterior([fx, fy], sd(i).min(-h)));
        }
    }
    let settings = FitSettings::default();
    let mut out = Vec::new();
    for _ in 0..steps {
        let fit = rbf_solve::fit(&constraints, &settings)?;
        let f = &fit.interpolant;
        let current: Vec<bool> = (0..pixels).map(|i| f.value(&grid.point(i)) > 0.0).collect();
        let current_boundary = grid.boundary(&current);
        // Two-way errors: goal boundary pixels to the current boundary, and back.
        let mut errors: Vec<(usize, f64, bool)> = goal_boundary
            .iter()
            .map(|&i| (i, grid.distance(i, &current_boundary), true))
            .collect();
        errors.extend(
            current_boundary
                .iter()
                .map(|&i| (i, sd(i).abs() / h, false)),
        );
        let max = errors.iter().map(|e| e.1).fold(0.0, f64::max);
        let rms =
            (errors.iter().map(|e| e.1 * e.1).sum::<f64>() / errors.len().max(1) as f64).sqrt();
        out.push(Step {
            model: Model {
                constraints: constraints.clone(),
                settings,
                interpolant: fit.interpolant.clone(),
                report: Some(fit.report),
            },
            max_error: max,
            rms_error: rms,
        });
        // §5.3: largest first (goal first in a tie), at least half the maximum, not within a
        // pixel of a constraint, not within 2·error of one added this step.
        errors.retain(|e| e.1 >= 0.5 * max && e.1 > 0.0);
        errors.sort_by(|a, b| b.1.total_cmp(&a.1).then(b.2.cmp(&a.2)));
        let mut added: Vec<([f64; 2], f64)> = Vec::new();
        for (i, error, from_goal) in errors {
            let p = grid.point(i);
            let near = |q: [f64; 2], r: f64| (p[0] - q[0]).hypot(p[1] - q[1]) < r;
            if constraints.iter().any(|c| near(c.position, h))
                || added.iter().any(|&(q, e)| near(q, 2.0 * e * h))
            {
                continue;
            }
            added.push((p, error));
            constraints.push(if from_goal {
                Constraint::boundary(p)
            } else if sd(i) > 0.0 {
                Constraint::interior(p, sd(i))
            } else {
                Constraint::exterior(p, sd(i))
            });
        }
        if added.is_empty() {
            break;
        }
    }
    Ok(out)
}

/// Whether a point is inside the goal (for drawing it under the curves).
pub(crate) fn goal(p: [f64; 2]) -> bool {
    teapot(p)
}
