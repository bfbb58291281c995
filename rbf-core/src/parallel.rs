//! Batch evaluation on every core (feature `rayon`): the points are cut into chunks, each
//! evaluated by the vectorized batch routines of [`InterpolantView`] on its own thread.

use rayon::prelude::*;

use crate::{InterpolantView, LengthMismatch, Real};

/// Points per parallel task: a chunk of 256 points costs 256·K kernel evaluations, enough to
/// amortize a task's scheduling, and leaves enough tasks to balance the cores on small batches.
const CHUNK: usize = 256;

impl<T: Real + Send + Sync, const D: usize> InterpolantView<'_, T, D> {
    /// `out[i] = f(points[i])` on every core of the rayon pool; the same numbers as
    /// [`InterpolantView::values`].
    ///
    /// ```
    /// use rbf_core::{InterpolantView, Kernel};
    /// let f = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[-1.0], 1.0, [0.0; 3]).unwrap();
    /// let points: Vec<[f64; 3]> = (0..1000).map(|i| [i as f64 / 1000.0, 0.0, 0.0]).collect();
    /// let mut out = vec![0.0; points.len()];
    /// f.par_values(&points, &mut out).unwrap();
    /// assert_eq!(out[500], 1.0 - 0.125);
    /// ```
    pub fn par_values(&self, points: &[[T; D]], out: &mut [T]) -> Result<(), LengthMismatch> {
        LengthMismatch::check("output", points.len(), out.len())?;
        points
            .par_chunks(CHUNK)
            .zip(out.par_chunks_mut(CHUNK))
            .try_for_each(|(p, o)| self.values(p, o))
    }

    /// f and ∇f on every core of the rayon pool; the same numbers as
    /// [`InterpolantView::values_and_gradients`].
    ///
    /// ```
    /// use rbf_core::{InterpolantView, Kernel};
    /// let f = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[-1.0], 1.0, [0.0; 3]).unwrap();
    /// let points = vec![[0.0, 2.0, 0.0]; 600];
    /// let (mut v, mut g) = (vec![0.0; 600], vec![[0.0; 3]; 600]);
    /// f.par_values_and_gradients(&points, &mut v, &mut g).unwrap();
    /// assert_eq!((v[599], g[599]), (-7.0, [0.0, -12.0, 0.0]));
    /// ```
    pub fn par_values_and_gradients(
        &self,
        points: &[[T; D]],
        values: &mut [T],
        gradients: &mut [[T; D]],
    ) -> Result<(), LengthMismatch> {
        LengthMismatch::check("values", points.len(), values.len())?;
        LengthMismatch::check("gradients", points.len(), gradients.len())?;
        points
            .par_chunks(CHUNK)
            .zip(values.par_chunks_mut(CHUNK))
            .zip(gradients.par_chunks_mut(CHUNK))
            .try_for_each(|((p, v), g)| self.values_and_gradients(p, v, g))
    }
}

/// Centres per block of [`InterpolantView::par_values_compensated`].
const BLOCK: usize = 2048;

impl<const D: usize> InterpolantView<'_, f64, D> {
    /// f at every point, on every core, with the sum over the centres taken in blocks of 2048
    /// whose partial sums are added with Neumaier's compensation: rounding then grows with the
    /// block, not with K. For models of 10⁵ centres and more, whose weights cancel (Σ|wⱼ|φ far
    /// above |f|), where plain sums lose digits a residual check needs; about as fast as
    /// [`InterpolantView::par_values`].
    ///
    /// ```
    /// use rbf_core::{InterpolantView, Kernel};
    /// // Two huge weights that cancel: f is small beside each term.
    /// let centres = [[0.0, 0.0, 0.0], [1e-3, 0.0, 0.0]];
    /// let f = InterpolantView::new(Kernel::Cubic, &centres, &[1e12, -1e12], 0.0, [0.0; 3]).unwrap();
    /// let x = [[2.0, 0.0, 0.0]];
    /// let mut out = [0.0];
    /// f.par_values_compensated(&x, &mut out).unwrap();
    /// let exact = 1e12 * (8.0 - 1.999_f64.powi(3));
    /// assert!((out[0] - exact).abs() <= 1e-6 * exact.abs());
    /// ```
    pub fn par_values_compensated(
        &self,
        points: &[[f64; D]],
        out: &mut [f64],
    ) -> Result<(), LengthMismatch> {
        LengthMismatch::check("output", points.len(), out.len())?;
        let k = self.centres().len();
        points
            .par_chunks(CHUNK)
            .zip(out.par_chunks_mut(CHUNK))
            .try_for_each(|(targets, o)| {
                let mut part = alloc::vec![0.0; targets.len()];
                let mut compensation = alloc::vec![0.0; targets.len()];
                o.fill(0.0);
                for start in (0..k).step_by(BLOCK) {
                    let end = (start + BLOCK).min(k);
                    let block = InterpolantView::new(
                        self.kernel(),
                        &self.centres()[start..end],
                        &self.weights()[start..end],
                        0.0,
                        [0.0; D],
                    )?;
                    block.values(targets, &mut part)?;
                    for ((sum, c), &term) in o.iter_mut().zip(compensation.iter_mut()).zip(&part) {
                        neumaier(sum, c, term);
                    }
                }
                for ((v, c), x) in o.iter_mut().zip(&compensation).zip(targets) {
                    *v += c + self.affine(x);
                }
                Ok(())
            })
    }
}

/// sum += term, with what rounding lost added to `compensation` (Neumaier's summation).
#[inline(always)]
pub(crate) fn neumaier(sum: &mut f64, compensation: &mut f64, term: f64) {
    let t = *sum + term;
    *compensation += if sum.abs() >= term.abs() {
        (*sum - t) + term
    } else {
        (term - t) + *sum
    };
    *sum = t;
}
