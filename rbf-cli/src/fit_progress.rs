//! What a fit shows while it runs: one message for the spinner from each report of
//! `rbf_solve::fit_with`, and what the closing lines need afterwards (a stall at the rounding
//! floor, relaxed products). `rbf fit` and `rbf convert --method normals` share it.

use std::time::Instant;

use rbf_solve::{FitProgress, IterativeProgress};

/// The state of a fit's messages.
pub(crate) struct FitMessages {
    rows: usize,
    /// The residual the iterative solver aims at (relative to max|h|), for the time left.
    tolerance: f64,
    /// When the iterations began, and the first iteration's estimate.
    solving: Instant,
    first: f64,
    /// Where the solve stalled, if at the rounding floor.
    pub(crate) rounding_floor: Option<f64>,
    /// Products through a relaxed far field, of all products.
    pub(crate) relaxed: Option<(usize, usize)>,
    /// The default limit, raised to the far field's.
    pub(crate) limit: Option<f64>,
}

impl FitMessages {
    pub(crate) fn new(tolerance: f64) -> Self {
        Self {
            rows: 0,
            tolerance,
            solving: Instant::now(),
            first: f64::NAN,
            rounding_floor: None,
            relaxed: None,
            limit: None,
        }
    }

    /// The spinner's message for `p`.
    pub(crate) fn message(&mut self, p: FitProgress) -> String {
        let rows = self.rows;
        let p = match p {
            FitProgress::Checking { rows } => {
                self.rows = rows;
                return format!("checking {rows} rows");
            }
            FitProgress::Factoring { rows } => {
                return format!("solving a dense system of {rows} rows");
            }
            FitProgress::Iterative(p) => p,
        };
        match p {
            IterativeProgress::Preconditioning => {
                format!("{rows} rows: factoring the subdomains")
            }
            IterativeProgress::FarField { order } => {
                format!("{rows} rows: products through the far field (order {order})")
            }
            IterativeProgress::DirectSums => format!("{rows} rows: products by direct sums"),
            IterativeProgress::Relaxed { products, of } => {
                self.relaxed = Some((products, of));
                format!("{rows} rows: {products} of {of} products through a relaxed far field")
            }
            IterativeProgress::DefaultLimit { limit } => {
                self.limit = Some(limit);
                self.tolerance = limit;
                format!("{rows} rows: fitting to {limit:.0e} of max|h|, the iterative default")
            }
            IterativeProgress::RoundingFloor { residual, floor } => {
                self.rounding_floor = Some(floor);
                format!("{rows} rows: stopped at residual {residual:.1e}, the rounding floor")
            }
            IterativeProgress::Iteration {
                iteration,
                estimate,
            } => {
                if iteration == 1 {
                    self.first = estimate;
                }
                let left = self.time_left(iteration, estimate);
                format!("{rows} rows: iteration {iteration}, residual ≈ {estimate:.1e}{left}")
            }
            IterativeProgress::Checked {
                iteration,
                residual,
                from_recurrence,
            } => {
                if iteration == 0 {
                    self.solving = Instant::now();
                }
                let how = if from_recurrence {
                    " (the recurrence's, certified at sampled rows)"
                } else {
                    ""
                };
                format!("{rows} rows: iteration {iteration}, residual {residual:.1e}{how}")
            }
        }
    }

    /// ", about N s left": the iterations still needed if the residual keeps falling at its
    /// rate since the first iteration, at the average time of an iteration so far; empty until
    /// it can tell.
    fn time_left(&self, iteration: usize, estimate: f64) -> String {
        let rate = (estimate / self.first).ln() / (iteration as f64 - 1.0);
        if !(iteration >= 3 && rate < 0.0 && estimate > self.tolerance) {
            return String::new();
        }
        let more = (self.tolerance / estimate).ln() / rate;
        let seconds = self.solving.elapsed().as_secs_f64() / iteration as f64 * more;
        format!(", about {seconds:.0} s left")
    }
}
