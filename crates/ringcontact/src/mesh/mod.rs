//! Meshes of the half-space: the triangulation and its checks ([`triangulation`]), reading
//! gmsh's `.msh` files ([`msh`]), making them with gmsh ([`gmsh`]), refining the rim corner
//! ([`corner_refinement`]), and choosing, making and caching the mesh a scene needs
//! ([`provider`], with the data and cache directories in [`files`]).

pub mod corner_refinement;
pub mod files;
pub mod gmsh;
pub mod msh;
pub mod provider;
pub mod triangulation;
