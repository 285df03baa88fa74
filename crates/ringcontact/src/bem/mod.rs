//! Boundary-element methods for the half-space.

pub mod grid;
pub mod grid_contact;
pub mod grid_estimate;
pub mod ring;
pub mod ring_contact;
