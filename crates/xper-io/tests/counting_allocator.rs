//! The counting allocator follows allocations, reallocations and frees byte for byte.

#[global_allocator]
static ALLOCATOR: xper_io::CountingAllocator = xper_io::CountingAllocator;

#[test]
fn heap_counts_follow_a_vector_through_growth_and_drop() {
    let before = xper_io::current_heap_bytes().expect("this binary counts");
    let mut v: Vec<u8> = Vec::with_capacity(1 << 20);
    v.push(1);
    let held = xper_io::current_heap_bytes().unwrap();
    // Other threads of the test harness may allocate a little meanwhile.
    assert!(held >= before + (1 << 20) && held < before + (1 << 20) + 65536);
    v.reserve_exact((3 << 20) - 1);
    let grown = xper_io::current_heap_bytes().unwrap();
    assert!(grown >= before + (3 << 20) && grown < before + (3 << 20) + 65536);
    v.shrink_to(1 << 19);
    let shrunk = xper_io::current_heap_bytes().unwrap();
    assert!(shrunk >= before + (1 << 19) && shrunk < before + (1 << 19) + 65536);
    assert!(xper_io::peak_heap_bytes().unwrap() >= before + (3 << 20));
    drop(v);
    let after = xper_io::current_heap_bytes().unwrap();
    assert!(
        after < before + 65536,
        "{after} after dropping, {before} before"
    );
}
