//! The process's allocator: mimalloc (ADR 0018), asked through its plain
//! `mi_malloc` for every layout it already aligns.
//!
//! The `mimalloc` crate hands every request to `mi_malloc_aligned`. In
//! mimalloc 3 that call takes its fast path only while the page of the
//! size's bin has a free block at hand; it never collects the blocks other
//! threads freed into that page, and otherwise over-allocates (a bigger bin,
//! a slower path). The front end allocates trees on the parser thread and
//! frees them on the checking thread (ADR 0018), so nearly every tree node of
//! a long check took the slow path: 121,000 of the parser's allocations in
//! the 1.25 MB check benchmark. `mi_malloc` collects those frees and reuses
//! the blocks.
//!
//! A block of `mi_malloc` starts a multiple of its bin's size after a page
//! start aligned to 16 bytes; a bin is an exact number of words up to eight
//! words and an even number above, and a Rust layout's size is a multiple of
//! its alignment. So for alignments up to 16 (and not above the size) the
//! block is aligned as asked; larger alignments still go to the aligned call.

use libmimalloc_sys::{
    mi_free, mi_malloc, mi_malloc_aligned, mi_realloc, mi_realloc_aligned, mi_zalloc, mi_zalloc_aligned,
};
use std::alloc::{GlobalAlloc, Layout};
use std::ffi::c_void;

/// Alignment every `mi_malloc` block of at least this size has.
const PLAIN_ALIGN: usize = 16;

/// mimalloc, through its plain calls where they align enough.
pub struct Allocator;

fn plain(align: usize, size: usize) -> bool {
    align <= PLAIN_ALIGN && align <= size
}

// SAFETY: every call hands mimalloc a size and (where needed) an alignment
// it supports and returns its block unchanged; blocks from either call are
// freed by `mi_free`.
unsafe impl GlobalAlloc for Allocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if plain(layout.align(), layout.size()) {
            unsafe { mi_malloc(layout.size()) as *mut u8 }
        } else {
            unsafe { mi_malloc_aligned(layout.size(), layout.align()) as *mut u8 }
        }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if plain(layout.align(), layout.size()) {
            unsafe { mi_zalloc(layout.size()) as *mut u8 }
        } else {
            unsafe { mi_zalloc_aligned(layout.size(), layout.align()) as *mut u8 }
        }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, _layout: Layout) {
        unsafe { mi_free(ptr as *mut c_void) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if plain(layout.align(), new_size) {
            unsafe { mi_realloc(ptr as *mut c_void, new_size) as *mut u8 }
        } else {
            unsafe { mi_realloc_aligned(ptr as *mut c_void, new_size, layout.align()) as *mut u8 }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every alignment up to 16 over sizes across the small and medium
    /// bins comes back aligned, from the plain path.
    #[test]
    fn plain_blocks_are_aligned() {
        for align in [1usize, 2, 4, 8, 16] {
            for size in (align..=4096).step_by(align) {
                let layout = Layout::from_size_align(size, align).unwrap();
                let blocks: Vec<*mut u8> = (0..4).map(|_| unsafe { Allocator.alloc(layout) }).collect();
                for &p in &blocks {
                    assert!(!p.is_null());
                    assert_eq!(p as usize % align, 0, "size {size} align {align}");
                }
                let grown = unsafe { Allocator.realloc(blocks[0], layout, size * 3) };
                assert_eq!(grown as usize % align, 0, "realloc to {} align {align}", size * 3);
                unsafe { Allocator.dealloc(grown, Layout::from_size_align(size * 3, align).unwrap()) };
                for &p in &blocks[1..] {
                    unsafe { Allocator.dealloc(p, layout) };
                }
            }
        }
    }
}
