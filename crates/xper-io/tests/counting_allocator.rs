//! The counting allocator follows allocations, reallocations and frees byte for byte.

#[global_allocator]
static ALLOCATOR: xper_io::CountingAllocator = xper_io::CountingAllocator;

/// Whether `now` is `expected` within what the test harness's other thread may allocate or
/// free meanwhile (a few kilobytes at most).
fn near(now: u64, expected: u64) -> bool {
    now.abs_diff(expected) < 65536
}

#[test]
fn heap_counts_follow_a_vector_through_growth_and_drop() {
    let before = xper_io::current_heap_bytes().expect("this binary counts");
    let mut v: Vec<u8> = Vec::with_capacity(1 << 20);
    v.push(1);
    assert!(near(
        xper_io::current_heap_bytes().unwrap(),
        before + (1 << 20)
    ));
    v.reserve_exact((3 << 20) - 1);
    assert!(near(
        xper_io::current_heap_bytes().unwrap(),
        before + (3 << 20)
    ));
    assert!(xper_io::peak_heap_bytes().unwrap() + 65536 >= before + (3 << 20));
    v.shrink_to(1 << 19);
    assert!(near(
        xper_io::current_heap_bytes().unwrap(),
        before + (1 << 19)
    ));
    drop(v);
    let after = xper_io::current_heap_bytes().unwrap();
    assert!(
        near(after, before),
        "{after} after dropping, {before} before"
    );
}
