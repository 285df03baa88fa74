//! The finite-element contact solve: the active set of the unilateral contact line
//! ([`contact`]), the band of nodes where the free edge can sit ([`contact_band`]), the contact
//! line condensed to a surface response ([`surface_response`]) and the mesh ladder with its error
//! estimate ([`solver`]). Built on [`crate::mesh`], [`crate::discretisation`] and the SPD seam
//! [`crate::sparse`].

pub mod contact;
pub mod contact_band;
pub mod solver;
pub mod surface_response;

// The FEM's API for the methods (`methods::Fem` wraps it for users and the harness): a solve
// with its full state (fields, reactions, timings), a solve on a given mesh (convergence
// ladders), the mesh ladder and its start, the component of the error refinement does not
// reduce, and nodal contact pressures.
pub use contact::nodal_pressure;
pub use solver::{
    contact_start, default_degree, mesh_directory, mesh_sequence, solve, solve_free_edges_on_level,
    solve_on_mesh, FemLoad, FemOptions, FemState, FemTimings, DEFAULT_TOLERANCE, METHOD,
    MIN_TOLERANCE, UNRESOLVED_COMPONENT,
};
