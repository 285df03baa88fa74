//! The contact line's elastic response on one FE model: the discrete compliance
//! `C_ij = u_z(r_i)` under a unit normal nodal force at node `j` (`C = (K⁻¹)_cc` restricted to
//! the contact-line `u_z` dofs, the supports held), and the nodal quadrature weights
//! `A_i = ∫ φ_i 2π r dr` of the contact line (the consistent load of a unit pressure).
//!
//! A surface law (a cohesive zone) then acts on the contact line alone: the half-space's
//! response to any nodal forces `f` there is `u_z = C f`, exactly that of the full FE model.

use nalgebra::DMatrix;

use crate::discretisation::export::unit_pressure_load;
use crate::error::{Error, Result};
use crate::fem::contact::ContactModel;
use crate::sparse::constrained::ConstrainedCholesky;

/// Unit responses computed per blocked triangular solve.
const BLOCK: usize = 64;

/// The FE model condensed onto its contact line.
#[derive(Clone, Debug)]
pub struct SurfaceResponse {
    /// `r/a` of the contact-line nodes, increasing.
    pub radii: Vec<f64>,
    /// Nodal weights `A_i = ∫ φ_i 2π r dr` (area units of `a²`; sum `π (1 - b²)`).
    pub weights: Vec<f64>,
    /// `C_ij`: `u_z` at node `i` (positive into the solid) per unit force at node `j` pushing
    /// into the solid (units `1/(E* a)`); symmetric positive definite.
    pub compliance: DMatrix<f64>,
    /// Unknowns of the FE model.
    pub unknowns: usize,
}

impl SurfaceResponse {
    /// The response of a model whose length unit is `frame a` in units of `a`: radii times
    /// `frame`, weights (areas) times `frame²`, and the compliance (a displacement per force)
    /// divided by `frame` (by the scaling of linear elasticity, as
    /// [`crate::fem::contact::ContactModel::with_free_edges`]).
    pub fn in_units_of_a(mut self, frame: f64) -> Self {
        for r in &mut self.radii {
            *r *= frame;
        }
        for w in &mut self.weights {
            *w *= frame * frame;
        }
        self.compliance /= frame;
        self
    }
}

/// Condense `model` (its stiffness factorised by `solver`) onto the contact line.
pub(crate) fn condense(
    model: &ContactModel,
    solver: &mut ConstrainedCholesky,
    supports: &[bool],
) -> Result<SurfaceResponse> {
    let nodes = &model.contact_nodes;
    let radii: Vec<f64> = nodes.iter().map(|&n| model.mesh.nodes[n][0]).collect();
    let load = unit_pressure_load(model.mesh);
    let mut weights: Vec<f64> = nodes.iter().map(|&n| -load[2 * n + 1]).collect();
    // The weight of the node on the axis is zero (the factor r), to rounding.
    let rounding = 1e-12 * weights.iter().map(|w| w.abs()).fold(0.0, f64::max);
    if let Some(i) = weights.iter().position(|w| w.is_nan() || *w < -rounding) {
        return Err(Error::InvalidMesh {
            path: model.mesh.source.clone(),
            message: format!(
                "the contact-line node at r = {} has a negative quadrature weight {:.3e}",
                radii[i], weights[i]
            ),
        });
    }
    for w in &mut weights {
        *w = w.max(0.0);
    }
    let dofs: Vec<usize> = nodes.iter().map(|&n| 2 * n + 1).collect();
    let n = dofs.len();
    let mut compliance = DMatrix::zeros(n, n);
    for (block, chunk) in dofs.chunks(BLOCK).enumerate() {
        let columns = solver.unit_responses(supports, chunk)?;
        for (k, column) in columns.iter().enumerate() {
            let j = block * BLOCK + k;
            for (i, &dof) in dofs.iter().enumerate() {
                // A unit force pushing into the solid is -e_z (z points out of the solid), and
                // u_z into the solid is -u_z: the two signs cancel.
                compliance[(i, j)] = column[dof];
            }
        }
    }
    // Symmetric to rounding: make it exactly so.
    let symmetric = (&compliance + compliance.transpose()) * 0.5;
    Ok(SurfaceResponse {
        radii,
        weights,
        compliance: symmetric,
        unknowns: supports.len(),
    })
}
