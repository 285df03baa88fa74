//! The finite-element discretisation of the axisymmetric half-space: Lagrange triangles of
//! degree 1-3 ([`element`]) with their quadrature ([`quadrature`]), the stiffness assembly
//! ([`assembly`]), the Boussinesq far-field condition ([`far_field`]), energy norms ([`norms`]),
//! the node orderings the sparse factorisation runs in ([`vertex_ordering`], [`separator`],
//! joined in [`node_ordering`]) and the
//! exports of a model ([`export`], [`vtu`]).

pub mod assembly;
pub mod element;
pub mod export;
pub mod far_field;
pub mod node_ordering;
pub mod norms;
pub mod quadrature;
pub mod separator;
pub mod vertex_ordering;
pub mod vtu;
