//! Memory of the current process: peak resident set, and the heap bytes
//! counted by [`CountingAllocator`].

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};

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

/// A global allocator that counts the bytes it holds: [`System`](std::alloc::System) plus a
/// few relaxed atomic updates per allocation. The resident set size includes the executable,
/// its libraries and memory the C allocator keeps after it is freed; the count is the bytes
/// the program asked for (without the C allocator's headers), the same on every run of the
/// same input and build. A reallocation counts its change of size (the old and new blocks of
/// a moving reallocation briefly coexist; that moment is not counted). A binary installs it
/// with `#[global_allocator] static ALLOCATOR: CountingAllocator = CountingAllocator;`.
pub struct CountingAllocator;

static HEAP_NOW: AtomicUsize = AtomicUsize::new(0);
static HEAP_PEAK: AtomicUsize = AtomicUsize::new(0);

/// Adds `bytes` to the count and raises the peak if needed.
#[inline]
fn grow(bytes: usize) {
    let now = HEAP_NOW.fetch_add(bytes, Relaxed) + bytes;
    if now > HEAP_PEAK.load(Relaxed) {
        HEAP_PEAK.fetch_max(now, Relaxed);
    }
}

// SAFETY: every call is forwarded to `System` unchanged; the counters change only when it
// succeeds.
unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: the caller's contract is `System`'s.
        let ptr = unsafe { System.alloc(layout) };
        if !ptr.is_null() {
            grow(layout.size());
        }
        ptr
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        // SAFETY: as for `alloc`.
        let ptr = unsafe { System.alloc_zeroed(layout) };
        if !ptr.is_null() {
            grow(layout.size());
        }
        ptr
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: `ptr` was allocated by `System` with `layout`.
        unsafe { System.dealloc(ptr, layout) };
        HEAP_NOW.fetch_sub(layout.size(), Relaxed);
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: as for `dealloc`; `new_size` is the caller's.
        let moved = unsafe { System.realloc(ptr, layout, new_size) };
        if !moved.is_null() {
            if new_size >= layout.size() {
                grow(new_size - layout.size());
            } else {
                HEAP_NOW.fetch_sub(layout.size() - new_size, Relaxed);
            }
        }
        moved
    }
}

/// Largest number of heap bytes held at once so far, when this process counts its
/// allocations (installs [`CountingAllocator`]); `None` otherwise.
pub fn peak_heap_bytes() -> Option<u64> {
    let peak = HEAP_PEAK.load(Relaxed);
    (peak > 0).then_some(peak as u64)
}

/// Heap bytes held now, when this process counts its allocations; `None` otherwise.
pub fn current_heap_bytes() -> Option<u64> {
    (HEAP_PEAK.load(Relaxed) > 0).then(|| HEAP_NOW.load(Relaxed) as u64)
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
