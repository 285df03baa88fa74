//! The studies the report runs: methods against references ([`comparison`]), mesh and grid
//! convergence ([`convergence`]), speed against accuracy ([`speed_accuracy`]), stability where
//! methods fail ([`stability`]) and parameter sweeps ([`sweeps`]).

pub mod claims;
pub mod comparison;
pub mod convergence;
pub mod figures;
pub mod speed_accuracy;
pub mod stability;
pub mod sweeps;
