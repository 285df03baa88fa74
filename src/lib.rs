//! # ringcontact
//!
//! Cross-verification harness for rigid axisymmetric punches whose contact with an elastic
//! half-space is a ring: the flat annular, the conical concave and the spherical concave punch
//! (and the flat circular punch as a check case).
//!
//! **Conventions** (see `shared/docs/PHYSICS.md`): `E* = E/(1 - nu²)` of the half-space (rigid
//! punch); `a` the rim radius, `b` the inner contact radius, `eps = b/a`; `d` the indentation
//! depth of the rim, positive into the solid; `h` the depth of the concave hole; `F` the normal
//! force, positive in compression. Any consistent units; the dimensionless functions are
//! `F = 2 E* d a γ(eps)` (flat annulus) and `d = h γ1(eps)`, `F = 2 E* h a γ2(eps)` (concave).
//!
//! A [`scene::Scene`] goes in, a [`solution::Solution`] comes out; every solver is a
//! [`methods::Method`] behind that one interface.

pub mod adhesion;
pub mod bem;
pub mod cli;
pub mod cohesive;
pub mod error;
pub mod fem;
pub mod finite;
pub mod fit;
pub mod harness;
pub mod heartbeat;
pub mod methods;
pub mod numerics;
pub mod punch;
pub mod reference;
pub mod scene;
pub mod solution;
pub mod thread_pinning;

pub use error::{Error, Result};

/// Memory allocator of every program built on this crate (the `verify` binary, tests, benches):
/// mimalloc keeps freed memory for reuse where the system allocator returns each large block to
/// the kernel and takes fresh zeroed pages for the next one. A finite-element solve allocates
/// and frees blocks of tens to hundreds of megabytes (pattern, factor, scratch); with the
/// system allocator 29 % of its time went to page faults, zeroing and unmapping (perf, 61 k
/// P3 unknowns), and the solve took 0.28-0.30 s against 0.18-0.20 s with mimalloc.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

extern "C" {
    /// mimalloc's `void mi_option_set(mi_option_t option, long value)` (`mimalloc.h`; the
    /// library is linked by the `mimalloc` crate).
    fn mi_option_set(option: std::ffi::c_int, value: std::ffi::c_long);
}

/// `mi_option_purge_delay` in mimalloc's `mi_option_e` (`mimalloc.h`, v2 and v3).
const MI_OPTION_PURGE_DELAY: std::ffi::c_int = 15;

/// Keep the memory freed by one solve for the next solve of the same process, instead of
/// returning it to the kernel 10 ms after it is freed (mimalloc's default purge delay). Programs
/// that solve a sequence of models (the harness, convergence ladders, studies) then take most
/// of each model's memory from the previous ones, where fresh pages cost the kernel's zeroing
/// (about 0.5 ns a byte on the 2-core machine): the FEniCSx comparison's solves of 3e3-3e4
/// unknowns took 10-35 % less time (medians of three runs with `MIMALLOC_PURGE_DELAY` 10 and -1).
/// The process's resident memory stays at its peak until it exits.
/// Call once, at the start of `main`.
pub fn keep_freed_memory_for_reuse() {
    // SAFETY: sets one of mimalloc's documented options to a documented value (-1: never
    // purge); safe at any time, from any thread.
    unsafe { mi_option_set(MI_OPTION_PURGE_DELAY, -1) };
}

/// The environment variable by which a user sets mimalloc's use of transparent huge pages
/// (`MIMALLOC_ALLOW_THP`, 0 or 1); when it is set, [`use_base_pages_for_a_single_solve`] leaves
/// the user's choice alone.
pub const ALLOW_THP_VARIABLE: &str = "MIMALLOC_ALLOW_THP";

/// Turn transparent huge pages off for this process (Linux's `prctl(PR_SET_THP_DISABLE, 1)`,
/// inherited by child processes such as gmsh) unless the user set [`ALLOW_THP_VARIABLE`];
/// returns whether they are now off. For a program that solves one scene: all of its memory is
/// fresh, and a fresh 2 MB page costs far more than the translation misses it saves when the
/// program has been idle for a few seconds on a virtual machine (the host backs the guest's
/// memory again; measured on the 2-core Firecracker machine, `verify solve --method fem`, cone at
/// `d = 2h`, a solve 4 s after the previous one): 0.17-0.21 s with huge pages against 0.04-0.07
/// s without at the default `--tol 1e-3` (8 006 unknowns), 0.52-0.61 against 0.31-0.39 s at
/// `--tol 1e-6` (63 434). Back to back they cost 10-20 % (0.26-0.27 against 0.29-0.34 s at
/// `--tol 1e-6`), which is why the harness's commands, whose solves reuse each other's memory,
/// keep them; so does the grid BEM, which iterates over the same large arrays (`--grid 512`:
/// 9.2-9.4 s with huge pages against 9.6-10.5 s without after idle, 8.0 against 9.1 s back to
/// back). Call once, at the start of `main`, before the solve allocates.
pub fn use_base_pages_for_a_single_solve() -> bool {
    if std::env::var_os(ALLOW_THP_VARIABLE).is_some() {
        return false;
    }
    #[cfg(target_os = "linux")]
    {
        // SAFETY: `prctl(PR_SET_THP_DISABLE, 1, 0, 0, 0)` sets one flag of the calling process
        // (Linux 3.15 and later; an older kernel returns -1 and nothing changes).
        unsafe { libc::prctl(libc::PR_SET_THP_DISABLE, 1, 0, 0, 0) == 0 }
    }
    #[cfg(not(target_os = "linux"))]
    {
        false
    }
}

#[cfg(all(test, target_os = "linux"))]
mod tests {
    /// A single solve's process runs without transparent huge pages: the kernel reports its flag
    /// back (`prctl(PR_GET_THP_DISABLE)` is 1), unless the user chose with `MIMALLOC_ALLOW_THP`.
    #[test]
    fn a_single_solve_turns_transparent_huge_pages_off() {
        let user_chose = std::env::var_os(super::ALLOW_THP_VARIABLE).is_some();
        let applied = super::use_base_pages_for_a_single_solve();
        assert_eq!(applied, !user_chose);
        // SAFETY: reads one flag of the calling process.
        let flag = unsafe { libc::prctl(libc::PR_GET_THP_DISABLE, 0, 0, 0, 0) };
        if applied {
            assert_eq!(flag, 1, "the kernel did not record the flag");
        }
    }
}
