//! Axisymmetric finite-element solver for the punch problems, on gmsh meshes.

pub mod assembly;
pub mod contact;
pub mod contact_band;
pub mod corner_refinement;
pub mod dense_cholesky;
pub mod element;
pub mod export;
pub mod far_field;
pub mod gmsh;
pub mod linear_solver;
pub mod mesh;
pub mod mesh_provider;
pub mod msh;
pub mod node_ordered_cholesky;
pub mod node_pair_analysis;
pub mod norms;
pub mod permuted_lower;
pub mod prefetch;
pub mod quadrature;
pub mod separator;
pub mod solver;
pub mod split_cholesky;
pub mod surface_response;
pub mod vertex_ordering;
pub mod vtu;
pub mod zeroed;
