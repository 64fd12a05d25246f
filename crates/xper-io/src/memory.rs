//! Memory of the current process: peak resident set, and the heap bytes
//! counted by [`CountingAllocator`].

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering::Relaxed};

/// Peak resident set size ("high water mark") of this process in bytes, read
/// from `VmHWM` in `/proc/self/status`. `None` when not on Linux or when the
/// value cannot be read or parsed.
pub fn peak_memory_bytes() -> Option<u64> {
    if !cfg!(target_os = "linux") {
        return None;
    }
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    parse_status_field(&status, "VmHWM:")
}

/// Extracts `field` (in kB) from the text of `/proc/self/status` as bytes.
fn parse_status_field(status: &str, field: &str) -> Option<u64> {
    let line = status.lines().find(|l| l.starts_with(field))?;
    let mut parts = line[field.len()..].split_whitespace();
    let value: u64 = parts.next()?.parse().ok()?;
    match parts.next() {
        Some("kB") | None => value.checked_mul(1024),
        Some(_) => None,
    }
}

/// A global allocator that counts the bytes it holds: [`System`](std::alloc::System) plus two
/// relaxed atomic updates per allocation. The resident set size includes the executable, its
/// libraries and memory the C allocator keeps after it is freed; the count is what the data
/// of a run needs, exactly and the same on every run. A binary installs it with
/// `#[global_allocator] static ALLOCATOR: CountingAllocator = CountingAllocator;`.
pub struct CountingAllocator;

static HEAP_NOW: AtomicUsize = AtomicUsize::new(0);
static HEAP_PEAK: AtomicUsize = AtomicUsize::new(0);
static COUNTING: AtomicBool = AtomicBool::new(false);

// SAFETY: every call is forwarded to `System` unchanged; only counters are updated.
unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        COUNTING.store(true, Relaxed);
        let now = HEAP_NOW.fetch_add(layout.size(), Relaxed) + layout.size();
        HEAP_PEAK.fetch_max(now, Relaxed);
        // SAFETY: the caller's contract is `System`'s.
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        COUNTING.store(true, Relaxed);
        let now = HEAP_NOW.fetch_add(layout.size(), Relaxed) + layout.size();
        HEAP_PEAK.fetch_max(now, Relaxed);
        // SAFETY: as for `alloc`.
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        HEAP_NOW.fetch_sub(layout.size(), Relaxed);
        // SAFETY: `ptr` was allocated by `System` with `layout`.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if new_size >= layout.size() {
            let now =
                HEAP_NOW.fetch_add(new_size - layout.size(), Relaxed) + new_size - layout.size();
            HEAP_PEAK.fetch_max(now, Relaxed);
        } else {
            HEAP_NOW.fetch_sub(layout.size() - new_size, Relaxed);
        }
        // SAFETY: as for `dealloc`; `new_size` is the caller's.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

/// Largest number of heap bytes held at once so far, when this process counts its
/// allocations (installs [`CountingAllocator`]); `None` otherwise.
pub fn peak_heap_bytes() -> Option<u64> {
    COUNTING
        .load(Relaxed)
        .then(|| HEAP_PEAK.load(Relaxed) as u64)
}

/// Heap bytes held now, when this process counts its allocations; `None` otherwise.
pub fn current_heap_bytes() -> Option<u64> {
    COUNTING
        .load(Relaxed)
        .then(|| HEAP_NOW.load(Relaxed) as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_status_text() {
        let text = "Name:\tx\nVmPeak:\t  2000 kB\nVmHWM:\t    1234 kB\nVmRSS:\t 1000 kB\n";
        assert_eq!(parse_status_field(text, "VmHWM:"), Some(1234 * 1024));
        assert_eq!(parse_status_field(text, "VmRSS:"), Some(1000 * 1024));
        assert_eq!(parse_status_field("VmHWM:\t abc kB\n", "VmHWM:"), None);
        assert_eq!(parse_status_field("VmRSS:\t 5 kB\n", "VmHWM:"), None);
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn live_value_is_positive() {
        let v = peak_memory_bytes().expect("VmHWM readable on Linux");
        assert!(v > 0);
    }
}
