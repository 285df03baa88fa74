//! The finite-element contact solve: the active set of the unilateral contact line
//! ([`contact`]), the band of nodes where the free edge can sit ([`contact_band`]), the contact
//! line condensed to a surface response ([`surface_response`]) and the mesh ladder with its error
//! estimate ([`solver`]). Built on [`crate::mesh`], [`crate::discretisation`] and the SPD seam
//! [`crate::sparse`].

pub mod contact;
pub mod contact_band;
pub mod solver;
pub mod surface_response;
