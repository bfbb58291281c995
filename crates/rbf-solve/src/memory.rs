//! Memory checks before large allocations.

use rbf_core::FitError;

/// Bytes of memory the system says are available (Linux `MemAvailable`), if known.
pub fn available_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// Refuses a system of `rows` whose dense matrices would take `bytes` when that is more than
/// the memory available (or more than the address space can hold).
pub fn check_fits(rows: usize, matrices: u64) -> Result<(), FitError> {
    let n = rows as u64;
    let bytes = n
        .saturating_mul(n)
        .saturating_mul(8)
        .saturating_mul(matrices);
    let available = available_memory();
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

/// A zeroed vector of `len` entries, or [`FitError::TooLarge`] if it cannot be allocated.
pub(crate) fn zeroed(len: usize, rows: usize) -> Result<Vec<f64>, FitError> {
    let mut v = Vec::new();
    v.try_reserve_exact(len).map_err(|_| FitError::TooLarge {
        rows,
        bytes: (len as u64).saturating_mul(8),
        available: available_memory(),
    })?;
    v.resize(len, 0.0);
    Ok(v)
}
