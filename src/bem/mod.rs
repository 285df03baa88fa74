//! Boundary-element methods for the half-space.

pub mod ring;
pub mod ring_contact;
