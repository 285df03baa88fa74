//! The verification harness: tables comparing methods with each other and with the references.

pub mod comparison;
pub mod fenicsx;
