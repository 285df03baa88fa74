//! Large zero-filled arrays whose memory is written, not only allocated, before it is used.
//!
//! `vec![0.0; n]` asks the allocator for zeroed memory, and fresh pages from the kernel are zero
//! already, so nothing writes them. Code that then adds into such an array (`a[i] += x`) reads
//! each page first: the kernel maps its shared zero page, and the write that follows faults a
//! second time and flushes that page from the other cores' TLBs with an inter-processor
//! interrupt, slow on a virtual machine (11 % of a cold 9e4-unknown solve's CPU time).
//! Memory the allocator reuses, on the other hand, it must clear itself, and a second pass to
//! write it would be work done twice. [`zeros_written`] does exactly one pass, on all cores.

use rayon::prelude::*;

/// `len` zeros, every element written (in parallel) into memory that nothing wrote before: one
/// pass whether the allocator's memory is fresh or reused (see the module's documentation).
pub(crate) fn zeros_written(len: usize) -> Vec<f64> {
    rayon::iter::repeat_n(0.0, len).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_element_is_zero_and_the_length_is_asked_for() {
        for len in [0, 1, 7, 1 << 20] {
            let v = zeros_written(len);
            assert_eq!(v.len(), len);
            assert!(v.iter().all(|&x| x == 0.0 && x.is_sign_positive()));
        }
    }
}
