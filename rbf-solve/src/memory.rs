//! Memory checks before large allocations.

use rbf_core::FitError;

use crate::probe::memory_budget;

/// Refuses a system of `rows` rows when `matrices` dense `rows` × `rows` matrices of `f64`
/// would take more than the [`memory_budget`] (or more than the address space can hold).
///
/// ```
/// assert!(rbf_solve::check_fits(1000, 1).is_ok()); // 8 MB
/// assert!(rbf_solve::check_fits(10_000_000, 1).is_err()); // 800 TB
/// ```
#[doc(hidden)]
pub fn check_fits(rows: usize, matrices: u64) -> Result<(), FitError> {
    let n = rows as u64;
    let bytes = n
        .saturating_mul(n)
        .saturating_mul(8)
        .saturating_mul(matrices);
    let available = memory_budget();
    let limit = available.unwrap_or(u64::MAX).min(isize::MAX as u64);
    if bytes > limit {
        return Err(FitError::TooLarge {
            rows,
            bytes,
            available,
        });
    }
    Ok(())
}

/// A dense column-major matrix of `rows` × `cols`, each column filled by `fill(j, column)` in
/// parallel. The columns are first touched by the thread that fills them, and on Linux the
/// buffer is backed by huge pages where the kernel allows it: on a fresh allocation, page
/// faults otherwise cost more than computing the entries.
pub(crate) fn filled_matrix(
    rows: usize,
    cols: usize,
    fill: impl Fn(usize, &mut [f64]) + Sync,
) -> Result<Vec<f64>, FitError> {
    use rayon::prelude::*;
    let len = rows.saturating_mul(cols);
    let too_large = || FitError::TooLarge {
        rows: rows.max(cols),
        bytes: (len as u64).saturating_mul(8),
        available: memory_budget(),
    };
    let mut v: Vec<f64> = Vec::new();
    v.try_reserve_exact(len).map_err(|_| too_large())?;
    advise_huge_pages(v.spare_capacity_mut());
    if rows > 0 {
        v.spare_capacity_mut()[..len]
            .par_chunks_mut(rows)
            .enumerate()
            .for_each(|(j, col)| {
                for x in col.iter_mut() {
                    x.write(0.0);
                }
                // SAFETY: every element of `col` was initialized just above, and
                // `MaybeUninit<f64>` has the layout of `f64`.
                let col = unsafe {
                    std::slice::from_raw_parts_mut(col.as_mut_ptr().cast::<f64>(), col.len())
                };
                fill(j, col);
            });
    }
    // SAFETY: the capacity is at least `len` and all `len` elements were initialized above.
    unsafe { v.set_len(len) };
    Ok(v)
}

#[cfg(target_os = "linux")]
fn advise_huge_pages<T>(buffer: &mut [T]) {
    const HUGE: usize = 2 << 20;
    let start = buffer.as_mut_ptr() as usize;
    let end = start + std::mem::size_of_val(buffer);
    let aligned = start.next_multiple_of(HUGE);
    if end > aligned + HUGE {
        let len = (end - aligned) / HUGE * HUGE;
        // SAFETY: the range lies inside `buffer`, which this process owns; MADV_HUGEPAGE only
        // changes how the kernel backs those pages, never their contents. Failure is harmless.
        unsafe {
            libc::madvise(aligned as *mut libc::c_void, len, libc::MADV_HUGEPAGE);
        }
    }
}

#[cfg(not(target_os = "linux"))]
fn advise_huge_pages<T>(_buffer: &mut [T]) {}

/// Refuses, before any checking or assembly, constraints whose system (one row per constraint,
/// two per normal constraint) could not be held in memory even once.
///
/// ```
/// use rbf_core::Constraint;
/// let few = [Constraint::boundary([0.0; 3])];
/// assert!(rbf_solve::check_constraints_fit(&few).is_ok());
/// ```
#[doc(hidden)]
pub fn check_constraints_fit<const D: usize>(
    constraints: &[rbf_core::Constraint<D>],
) -> Result<(), FitError> {
    let normals = constraints
        .iter()
        .filter(|c| c.kind == rbf_core::ConstraintKind::Normal)
        .count();
    check_fits(constraints.len().saturating_add(normals), 1)
}
