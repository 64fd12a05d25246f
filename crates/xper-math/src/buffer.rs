//! Reusable buffers sized to what they hold.
//!
//! A stepper refills the same vectors every step. `Vec`'s own growth at least doubles the
//! capacity, so a buffer refilled with a slowly growing count ends up to twice as large as
//! needed. These helpers give a buffer that is short of room a new allocation of the count
//! plus a sixteenth (so a count creeping up step by step reallocates rarely), freeing the old
//! one first (nothing is copied, and the two never coexist): a buffer's capacity stays within
//! a sixteenth of the largest count it held.

/// Empties `buffer` and makes room for at least `n` items.
#[inline]
pub fn clear_for<T>(buffer: &mut Vec<T>, n: usize) {
    if buffer.capacity() < n {
        *buffer = Vec::new();
        buffer.reserve_exact(n + n / 16);
    } else {
        buffer.clear();
    }
}

/// Frees `buffer`, then gives it room for exactly `n` items: for a buffer that lives during
/// one stage only and is released after it, so that it never holds room for a larger count
/// of an earlier step (the old block is freed before the new one is taken).
#[inline]
pub fn renew_for<T>(buffer: &mut Vec<T>, n: usize) {
    *buffer = Vec::new();
    buffer.reserve_exact(n);
}

/// Replaces the contents of `buffer` by `items`, in room for exactly their count (see
/// [`renew_for`]).
#[inline]
pub fn renew<T>(buffer: &mut Vec<T>, items: impl ExactSizeIterator<Item = T>) {
    renew_for(buffer, items.len());
    buffer.extend(items);
}

/// Replaces the contents of `buffer` by `items` (see [`clear_for`]).
#[inline]
pub fn refill<T>(buffer: &mut Vec<T>, items: impl ExactSizeIterator<Item = T>) {
    clear_for(buffer, items.len());
    buffer.extend(items);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refilling_grows_to_the_largest_count_and_a_sixteenth() {
        let mut v: Vec<u32> = Vec::new();
        // 1600 gets 1600 + 100; 1650 and 1700 fit; 1701 gets 1701 + 106.
        for (n, capacity) in [
            (1600, 1700),
            (1650, 1700),
            (1700, 1700),
            (1701, 1807),
            (50, 1807),
        ] {
            refill(&mut v, 0..n);
            assert_eq!(v, (0..n).collect::<Vec<_>>());
            assert_eq!(v.capacity(), capacity, "after {n} items");
        }
        clear_for(&mut v, 10);
        assert!(v.is_empty());
        assert_eq!(v.capacity(), 1807);
    }

    #[test]
    fn renewing_holds_exactly_the_count_whatever_was_held_before() {
        let mut v: Vec<u32> = Vec::new();
        for n in [1600, 50, 1701, 0] {
            renew(&mut v, 0..n);
            assert_eq!(v, (0..n).collect::<Vec<_>>());
            assert_eq!(v.capacity(), n as usize, "after {n} items");
        }
        renew_for(&mut v, 7);
        assert!(v.is_empty());
        assert_eq!(v.capacity(), 7);
    }
}
