//! Peak resident memory of the current process.

/// Peak resident set size ("high water mark") of this process in bytes, read
/// from `VmHWM` in `/proc/self/status`. `None` when not on Linux or when the
/// value cannot be read or parsed.
pub fn peak_memory_bytes() -> Option<u64> {
    if !cfg!(target_os = "linux") {
        return None;
    }
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    parse_vm_hwm(&status)
}

/// Extracts `VmHWM` (in kB) from the text of `/proc/self/status` as bytes.
fn parse_vm_hwm(status: &str) -> Option<u64> {
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let mut parts = line["VmHWM:".len()..].split_whitespace();
    let value: u64 = parts.next()?.parse().ok()?;
    match parts.next() {
        Some("kB") | None => value.checked_mul(1024),
        Some(_) => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_status_text() {
        let text = "Name:\tx\nVmPeak:\t  2000 kB\nVmHWM:\t    1234 kB\nVmRSS:\t 1000 kB\n";
        assert_eq!(parse_vm_hwm(text), Some(1234 * 1024));
        assert_eq!(parse_vm_hwm("VmHWM:\t abc kB\n"), None);
        assert_eq!(parse_vm_hwm("VmRSS:\t 5 kB\n"), None);
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn live_value_is_positive() {
        let v = peak_memory_bytes().expect("VmHWM readable on Linux");
        assert!(v > 0);
    }
}
