//! The native backend of the SPD seam: this crate's supernodal Cholesky factorisation on `faer`'s
//! symbolic supernodal layout, of the whole matrix ([`whole`]) or, where the model admits a
//! separator, of its two parts on two cores and the separator's dense Schur complement
//! ([`split`]). The only code that reads `faer`'s internal layouts or holds `unsafe` blocks
//! of the linear algebra; its speed against the public backend is in
//! `benches/records/linear-solver.md`.

pub mod dense;
pub mod node_pair_analysis;
pub mod permuted_lower;
pub mod split;
pub mod supernodal_numeric;
pub mod whole;
