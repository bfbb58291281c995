//! Batch evaluation on every core, with the widest vector instructions the CPU has.

use rayon::prelude::*;
use rbf_core::{InterpolantView, LengthMismatch, Real};

/// Points per parallel task: enough to amortize scheduling, few enough to balance.
const CHUNK: usize = 512;

/// `out[i] = f(points[i])`, in parallel over the rayon pool.
///
/// Each thread runs [`InterpolantView::values`], which uses AVX-512 or AVX2 where the CPU has
/// them.
///
/// ```
/// use rbf_core::{InterpolantView, Kernel};
/// let f = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[-1.0], 1.0, [0.0; 3]).unwrap();
/// let points: Vec<[f64; 3]> = (0..1000).map(|i| [i as f64 / 1000.0, 0.0, 0.0]).collect();
/// let mut out = vec![0.0; points.len()];
/// rbf_solve::par_values(&f, &points, &mut out).unwrap();
/// assert_eq!(out[500], 1.0 - 0.125);
/// ```
pub fn par_values<T: Real, const D: usize>(
    f: &InterpolantView<'_, T, D>,
    points: &[[T; D]],
    out: &mut [T],
) -> Result<(), LengthMismatch> {
    if points.len() != out.len() {
        return Err(LengthMismatch {
            what: "output",
            expected: points.len(),
            found: out.len(),
        });
    }
    points
        .par_chunks(CHUNK)
        .zip(out.par_chunks_mut(CHUNK))
        .for_each(|(p, o)| {
            // Chunks of equal lengths: this cannot fail.
            let _ = f.values(p, o);
        });
    Ok(())
}
