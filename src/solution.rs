//! What every method returns for a scene: the physical state, the dimensionless functions of the
//! paper, the pressure profile, and what the answer cost and how accurate it is believed to be.

use serde::Serialize;

use crate::punch::PunchKind;

/// One sample of the contact pressure.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct PressureSample {
    /// Radius `r` (length units of the scene).
    pub r: f64,
    /// Pressure `p(r)` (stress units of the scene), compression positive.
    pub p: f64,
}

/// The solution of a scene by one method.
///
/// Dimensionless functions (paper eqs. 1 and 5): flat punches `F = 2 E* d a γ(eps)`; concave
/// punches `d = h γ1(eps)`, `F = 2 E* h a γ2(eps)`.
#[derive(Clone, Debug, Serialize)]
pub struct Solution {
    /// Punch shape.
    pub punch: PunchKind,
    /// Method that produced the numbers (`ring-bem`, `reference:<name>`, ...).
    pub method: String,
    /// Contact ratio `b/a` (0 for full contact).
    pub eps: f64,
    /// Indentation depth `d` of the rim (length units).
    pub depth: f64,
    /// Normal force `F` (force units), compression positive.
    pub force: f64,
    /// Inner contact radius `b` (length units).
    pub inner_radius: f64,
    /// Rim radius `a` (length units).
    pub rim_radius: f64,
    /// `γ = F / (2 E* d a)` (flat punches).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gamma: Option<f64>,
    /// `γ1 = d / h` (concave punches).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gamma1: Option<f64>,
    /// `γ2 = F / (2 E* h a)` (concave punches).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gamma2: Option<f64>,
    /// Mode-I stress intensity factor at the rim, `K = lim sqrt(2π(a - r)) p(r)` (stress·√length).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stress_intensity_rim: Option<f64>,
    /// Stress intensity factor at the inner edge `r = b` (0 at a free inner edge).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stress_intensity_inner: Option<f64>,
    /// Estimated error of the dimensionless results: the largest of the relative errors of
    /// `γ`/`γ1`/`γ2` and the absolute error of `eps`. `None` where the method has no estimate.
    pub error_estimate: Option<f64>,
    /// Wall time of the solve (seconds), including the error estimate.
    pub wall_s: f64,
    /// Number of unknowns of the finest discretisation used (0 for closed forms).
    pub unknowns: usize,
    /// Factorisations (ring BEM) or active-set iterations (FEM) spent.
    pub iterations: usize,
    /// Degrees of freedom of the finest finite-element model used (FEM only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dofs: Option<usize>,
    /// Mesh used, relative to the repository root (FEM only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mesh: Option<String>,
    /// SHA-256 of that mesh file (FEM only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mesh_sha256: Option<String>,
    /// Where the mesh came from: `committed`, `cache`, `gmsh` (made for this run) or `user`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mesh_origin: Option<crate::fem::mesh_provider::MeshOrigin>,
    /// Version of the gmsh that made the mesh (generated meshes only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gmsh_version: Option<String>,
    /// Far-field treatment of the FEM domain: `fixed` or `boussinesq`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub far_field: Option<crate::fem::far_field::FarField>,
    /// Element degree, 1 or 2 (FEM only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub degree: Option<u8>,
    /// Complementarity residual of the contact solution (FEM concave punches, grid BEM).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub complementarity_residual: Option<f64>,
    /// Cells per side of the square grid (grid BEM only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub grid: Option<usize>,
    /// Why this method was chosen (`--method auto`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub selection: Option<String>,
    /// Pressure profile, ascending in `r` (empty for references without one).
    pub pressure: Vec<PressureSample>,
    /// How the numbers were obtained, in one line.
    pub provenance: String,
}
