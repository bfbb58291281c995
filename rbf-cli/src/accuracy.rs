//! `--accuracy` and `--exact`, shared by the commands that evaluate models (eval, mesh,
//! render): how a model is summed, through the far field or directly.

use clap::Args;
use rbf_core::InterpolantView;
use rbf_far::Evaluator;

use crate::failure::{Failure, USAGE};

/// How a model's sums are taken.
#[derive(Args, Debug, Clone, Copy)]
pub(crate) struct AccuracyArgs {
    /// Largest error allowed in f, in the model's units [default: 1e-6 of the diagonal of the
    /// centres' bounding box]. Models of 15 000 centres and more go through a far field when it
    /// is that accurate at 1000 sampled points.
    #[arg(long, value_name = "A", conflicts_with = "exact")]
    accuracy: Option<f64>,
    /// Sum over every centre directly, however large the model.
    #[arg(long)]
    exact: bool,
}

impl AccuracyArgs {
    /// The evaluator of `view` for points like `sample` (the query points, or the centres when
    /// the points are not known in advance).
    pub(crate) fn evaluator<'a, const D: usize>(
        &self,
        view: InterpolantView<'a, f64, D>,
        sample: &[[f64; D]],
    ) -> Result<Evaluator<'a, D>, Failure> {
        self.evaluator_with(view, sample, false)
    }

    /// [`AccuracyArgs::evaluator`] with a coarse far field beside it, for what only steers
    /// (a render's bounds and samples).
    pub(crate) fn steering_evaluator<'a, const D: usize>(
        &self,
        view: InterpolantView<'a, f64, D>,
        sample: &[[f64; D]],
    ) -> Result<Evaluator<'a, D>, Failure> {
        self.evaluator_with(view, sample, true)
    }

    fn evaluator_with<'a, const D: usize>(
        &self,
        view: InterpolantView<'a, f64, D>,
        sample: &[[f64; D]],
        coarse: bool,
    ) -> Result<Evaluator<'a, D>, Failure> {
        if self.exact {
            return Ok(Evaluator::direct(view));
        }
        let accuracy = match self.accuracy {
            Some(a) if a > 0.0 && a.is_finite() => a,
            Some(a) => {
                return Err(Failure::new(
                    USAGE,
                    format!("--accuracy {a}: the accuracy must be a finite number > 0"),
                ));
            }
            None => rbf_far::default_accuracy(view.centres()),
        };
        Ok(if coarse {
            Evaluator::with_coarse(view, sample, accuracy)
        } else {
            Evaluator::new(view, sample, accuracy)
        })
    }
}
