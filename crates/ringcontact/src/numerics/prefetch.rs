//! Cache prefetch hints for loops whose next accesses are known but scattered in memory.
//!
//! Several steps of a solve visit large arrays in an order that is not their own (the parts'
//! elimination order over `K`'s columns, cells over `K`'s values, the factor's layout over `K`'s
//! values): each access then waits for memory (about 100 ns on the 2-core machine) unless the
//! processor is asked for it a few iterations ahead. A prefetch is a hint: it reads nothing
//! architecturally and cannot fault, so a wrong or stale address costs only the hint.

/// Bytes per cache line of the x86-64 processors this is tuned on.
const LINE_BYTES: usize = 64;

/// Ask for the cache line holding `values[index]` (nothing when `index` is out of range; a
/// no-op off x86-64).
#[inline(always)]
pub fn prefetch<T>(values: &[T], index: usize) {
    if let Some(value) = values.get(index) {
        prefetch_address(value);
    }
}

/// Ask for every cache line of `values`.
#[inline(always)]
pub(crate) fn prefetch_range<T>(values: &[T]) {
    let per_line = (LINE_BYTES / std::mem::size_of::<T>().max(1)).max(1);
    for line in values.chunks(per_line) {
        prefetch_address(&line[0]);
    }
}

#[inline(always)]
fn prefetch_address<T>(value: &T) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: a prefetch is a hint that neither reads memory architecturally nor faults, whatever
    // the address; this one is a live reference.
    unsafe {
        std::arch::x86_64::_mm_prefetch::<{ std::arch::x86_64::_MM_HINT_T0 }>(
            (value as *const T).cast::<i8>(),
        )
    };
    #[cfg(not(target_arch = "x86_64"))]
    let _ = value;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hints_change_nothing_and_accept_any_index() {
        let values: Vec<u64> = (0..100).collect();
        prefetch(&values, 0);
        prefetch(&values, 99);
        prefetch(&values, 100);
        prefetch(&values, usize::MAX);
        prefetch_range(&values[10..90]);
        prefetch_range::<u64>(&[]);
        assert_eq!(values, (0..100).collect::<Vec<_>>());
    }
}
