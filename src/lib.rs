//! # ringcontact-verify
//!
//! The cross-verification harness over the [`ringcontact`] library: the studies, records,
//! report and dataset ([`harness`]) and the `verify` command line ([`cli`]). The library
//! itself carries no command line, no progress bars and no process-wide settings; this crate
//! reads the environment and the flags and passes what they choose to the library as values.

pub mod cli;
pub mod harness;
