//! Adhesive contact simulated directly: an adhesion law on the FE model's contact line
//! ([`law`]), the equilibrium at one depth as a minimum of the total energy ([`equilibrium`]),
//! and the loading-unloading path under displacement control with its pull-off ([`path`]).
//!
//! This route uses no JKR energy balance and no BEM: only the FE model (condensed onto the
//! contact line) and the law. As the law's range shrinks it tends to the JKR solution, which the
//! harness's other route ([`crate::adhesion`]) builds from the non-adhesive ring-BEM solutions.

pub mod annular;
pub mod equilibrium;
pub mod free_band;
pub mod law;
pub mod path;
pub mod study;
