//! Stored results compared with ours: other codes' (FEniCSx [`fenicsx`], Tamaas and
//! ContactMechanics [`peers`], [`adhesion_peers`], [`operator`]), our own earlier runs
//! ([`pulloff`], [`baselines`]), the speed records ([`benchmarks`]) and how they are read
//! ([`stored`]).

pub mod adhesion_peers;
pub mod baselines;
pub mod benchmarks;
pub mod fenicsx;
pub mod operator;
pub mod peers;
pub mod pulloff;
pub mod stored;
