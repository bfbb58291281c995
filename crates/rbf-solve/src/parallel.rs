//! Batch evaluation on every core, with the widest vector instructions the CPU has.

use rayon::prelude::*;
use rbf_core::{InterpolantView, LengthMismatch, Real};

/// Points per parallel task: enough to amortize scheduling, few enough to balance.
const CHUNK: usize = 512;

/// `out[i] = f(points[i])`, in parallel over the rayon pool.
///
/// On x86-64 the inner loop is compiled for AVX-512 and AVX2 as well and chosen at run time,
/// so a portable binary runs at the machine's full width.
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
        .for_each(|(p, o)| values_widest(f, p, o));
    Ok(())
}

/// f at points on this thread, with the widest instruction set available.
pub fn values_widest<T: Real, const D: usize>(
    f: &InterpolantView<'_, T, D>,
    points: &[[T; D]],
    out: &mut [T],
) {
    #[cfg(target_arch = "x86_64")]
    {
        if std::is_x86_feature_detected!("avx512f") {
            // SAFETY: the CPU supports AVX-512F, checked just above.
            unsafe { values_avx512(f, points, out) };
            return;
        }
        if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
            // SAFETY: the CPU supports AVX2 and FMA, checked just above.
            unsafe { values_avx2(f, points, out) };
            return;
        }
    }
    // Lengths are equal (callers slice them so), so this cannot fail.
    let _ = f.values(points, out);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
unsafe fn values_avx512<T: Real, const D: usize>(
    f: &InterpolantView<'_, T, D>,
    points: &[[T; D]],
    out: &mut [T],
) {
    let _ = f.values(points, out);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn values_avx2<T: Real, const D: usize>(
    f: &InterpolantView<'_, T, D>,
    points: &[[T; D]],
    out: &mut [T],
) {
    let _ = f.values(points, out);
}
