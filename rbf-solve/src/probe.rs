//! How much memory the machine has free, for refusing work that would not fit before it is
//! allocated. The only place in the workspace that asks the operating system.

/// Bytes of memory available (Linux `MemAvailable`), if known.
///
/// ```
/// if let Some(bytes) = rbf_solve::available_memory() {
///     assert!(bytes > 0);
/// }
/// ```
pub fn available_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib.saturating_mul(1024))
}

/// Bytes that one large allocation may take: [`available_memory`] less a reserve (5 %, and at
/// least 256 MiB) for the rest of the process and the system. The size checks before dense
/// systems and volumes compare against this, so that whatever they accept also runs.
///
/// ```
/// if let (Some(budget), Some(available)) = (rbf_solve::memory_budget(), rbf_solve::available_memory()) {
///     assert!(budget < available);
/// }
/// ```
pub fn memory_budget() -> Option<u64> {
    available_memory().map(|a| a.saturating_sub((a / 20).max(256 << 20)))
}
