//! Reusable buffers sized exactly.
//!
//! A stepper refills the same vectors every step. `Vec`'s own growth at least doubles the
//! capacity, so a buffer refilled with a slowly growing count ends up to twice as large as
//! needed; these helpers grow a buffer to exactly what it must hold, so its capacity is the
//! largest count seen and the memory per body or per contact is what the data needs.

/// Empties `buffer` and makes room for exactly `n` items (the capacity is kept when larger).
#[inline]
pub fn clear_for<T>(buffer: &mut Vec<T>, n: usize) {
    buffer.clear();
    buffer.reserve_exact(n);
}

/// Replaces the contents of `buffer` by `items`, growing it to exactly their number.
#[inline]
pub fn refill<T>(buffer: &mut Vec<T>, items: impl ExactSizeIterator<Item = T>) {
    clear_for(buffer, items.len());
    buffer.extend(items);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refilling_grows_to_the_largest_count_only() {
        let mut v: Vec<u32> = Vec::new();
        let mut largest = 0;
        for n in [100, 101, 103, 50, 104] {
            refill(&mut v, 0..n);
            largest = largest.max(n as usize);
            assert_eq!(v, (0..n).collect::<Vec<_>>());
            // Vec's own growth would have doubled to 200 at the second refill.
            assert_eq!(v.capacity(), largest);
        }
        clear_for(&mut v, 10);
        assert!(v.is_empty());
        assert_eq!(v.capacity(), 104);
    }
}
