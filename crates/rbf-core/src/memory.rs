//! How much memory the machine has free, for refusing work that would not fit (`std` only).

/// Bytes of memory available (Linux `MemAvailable`), if known.
///
/// ```
/// if let Some(bytes) = rbf_core::available_memory() {
///     assert!(bytes > 0);
/// }
/// ```
pub fn available_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib.saturating_mul(1024))
}
