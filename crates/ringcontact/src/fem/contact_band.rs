//! The contact iteration at one numeric factorisation: condensation onto a band of the contact
//! line.
//!
//! A warm start from a coarser model places the free edge of a concave punch within a narrow band.
//! The contact nodes above the band (the **core**, `r >= r_core`) are certainly in contact: they
//! are held at their prescribed displacement in the factorised matrix `K_S` (with the supports).
//! Any active set `A = core ∪ J`, `J` in the band, is then solved without a new factorisation:
//!
//! `u = v + Σ_{j∈J} μ_j w_j`,  `W_JJ μ = ū_J - v_J`,
//!
//! where `v` solves the core-held system, `w_j = K_S⁻¹ e_j` is the response to a unit force at band
//! dof `j` (computed once per node, in blocks), `W_JJ` is their symmetric positive definite
//! matrix of values at `J`, and `μ_j` is the force that holds node `j` at `ū_j` (minus its
//! reaction). The prescribed values are `ū = -d + s g(r)` (depth `d`, gap shape `g` weighted by
//! `s`), so `v = d v₁ + s v_g` from two base solves reused for every depth. A final step of
//! iterative refinement applies the same condensation to the residual of the `A`-system.

use std::collections::HashMap;

use nalgebra::{DMatrix, DVector};

use crate::error::{Error, Result};
use crate::sparse::constrained::ConstrainedCholesky;

/// Most band nodes held by condensation: beyond it a factorisation is cheaper (one unit response
/// costs about 1/20 of a numeric factorisation in blocks of 16 on P2/P3 models).
pub(crate) const MAX_BAND_NODES: usize = 64;

/// The core-held factorisation and the band's unit responses.
pub struct BandedSystem<'s, 'a> {
    pub(super) solver: &'s mut ConstrainedCholesky<'a>,
    /// Per contact node: held in the factorised matrix.
    pub core: Vec<bool>,
    /// The core is the contact nodes at `r >= core_radius`.
    pub core_radius: f64,
    /// `u_z` dof of each contact node.
    contact_dofs: Vec<usize>,
    /// Gap shape `g(r)` at each contact node.
    shape: Vec<f64>,
    /// Supports and core dofs: the constraint set of the factorisation.
    base_mask: Vec<bool>,
    /// Base solution with the core held at `-1` (per unit depth).
    per_depth: Option<Vec<f64>>,
    /// Base solution with the core held at `g(r)`.
    per_shape: Option<Vec<f64>>,
    /// Unit responses `w_j` by contact-node index.
    responses: HashMap<usize, Vec<f64>>,
}

fn band_error(reason: String) -> Error {
    Error::NoConvergence {
        method: "fem".into(),
        reason,
    }
}

impl<'s, 'a> BandedSystem<'s, 'a> {
    /// A banded system over `solver`'s matrix: `supports` are the fixed dofs, `core` marks the
    /// contact nodes held in the factorisation.
    pub fn new(
        solver: &'s mut ConstrainedCholesky<'a>,
        supports: Vec<bool>,
        contact_dofs: Vec<usize>,
        shape: Vec<f64>,
        core: Vec<bool>,
        core_radius: f64,
    ) -> Self {
        let mut base_mask = supports;
        for (&dof, &c) in contact_dofs.iter().zip(&core) {
            if c {
                base_mask[dof] = true;
            }
        }
        Self {
            solver,
            core,
            core_radius,
            contact_dofs,
            shape,
            base_mask,
            per_depth: None,
            per_shape: None,
            responses: HashMap::new(),
        }
    }

    /// Hold another core (the next solve refactorises; cached solutions are dropped).
    pub(crate) fn set_core(&mut self, core: Vec<bool>, core_radius: f64) {
        for ((&dof, &old), &new) in self.contact_dofs.iter().zip(&self.core).zip(&core) {
            if old && !new {
                self.base_mask[dof] = false;
            }
            if new {
                self.base_mask[dof] = true;
            }
        }
        self.core = core;
        self.core_radius = core_radius;
        self.per_depth = None;
        self.per_shape = None;
        self.responses.clear();
    }

    /// Number of unit responses computed so far.
    pub fn responses_computed(&self) -> usize {
        self.responses.len()
    }

    /// Base solve: `force` on the free dofs, `prescribed` values on the core and supports
    /// (refined: one step of iterative refinement).
    fn base_solve(&mut self, force: &[f64], prescribed: &[f64], refined: bool) -> Result<Vec<f64>> {
        match refined {
            true => self.solver.solve(force, &self.base_mask, prescribed),
            false => self
                .solver
                .solve_unrefined(force, &self.base_mask, prescribed),
        }
    }

    fn core_prescription(&self, value: impl Fn(usize) -> f64) -> Vec<f64> {
        let mut prescribed = vec![0.0; self.base_mask.len()];
        for (i, (&dof, &c)) in self.contact_dofs.iter().zip(&self.core).enumerate() {
            if c {
                prescribed[dof] = value(i);
            }
        }
        prescribed
    }

    /// The displacement with the contact nodes of `active` held at `-depth + s g(r)`, the rest of
    /// the contact line free; `refine` adds a step of iterative refinement. `None` when the band
    /// holds more than [`MAX_BAND_NODES`] nodes.
    pub fn solve(
        &mut self,
        active: &[bool],
        depth: f64,
        shape_weight: f64,
        refine: bool,
    ) -> Result<Option<Vec<f64>>> {
        let band: Vec<usize> = (0..active.len())
            .filter(|&i| active[i] && !self.core[i])
            .collect();
        if band.len() > MAX_BAND_NODES {
            return Ok(None);
        }
        self.ensure_responses(&band)?;
        let n = self.base_mask.len();
        let zero = vec![0.0; n];
        if self.per_depth.is_none() {
            let prescribed = self.core_prescription(|_| -1.0);
            self.per_depth = Some(self.base_solve(&zero, &prescribed, false)?);
        }
        if self.per_shape.is_none() && shape_weight != 0.0 {
            let shape = self.shape.clone();
            let prescribed = self.core_prescription(|i| shape[i]);
            self.per_shape = Some(self.base_solve(&zero, &prescribed, false)?);
        }
        let target = |i: usize| -depth + shape_weight * self.shape[i];
        let mut v: Vec<f64> = self
            .per_depth
            .as_ref()
            .map(|p| p.iter().map(|x| depth * x).collect())
            .unwrap_or_default();
        if shape_weight != 0.0 {
            if let Some(p) = &self.per_shape {
                for (x, y) in v.iter_mut().zip(p) {
                    *x += shape_weight * y;
                }
            }
        }
        let targets: Vec<f64> = band.iter().map(|&i| target(i)).collect();
        let mut u = self.condense(v, &band, &targets)?;
        if refine {
            // Residual of the A-system: forces on its free dofs, misfits on its held ones.
            let ku = self.solver.residual(&u, &zero);
            let mut held = self.base_mask.clone();
            for &i in &band {
                held[self.contact_dofs[i]] = true;
            }
            let force: Vec<f64> = (0..n).map(|k| if held[k] { 0.0 } else { -ku[k] }).collect();
            let core_target: Vec<f64> = (0..self.core.len()).map(target).collect();
            let mut prescribed = vec![0.0; n];
            for k in 0..n {
                if self.base_mask[k] {
                    prescribed[k] = -u[k];
                }
            }
            for (i, (&dof, &c)) in self.contact_dofs.iter().zip(&self.core).enumerate() {
                if c {
                    prescribed[dof] = core_target[i] - u[dof];
                }
            }
            let v = self.base_solve(&force, &prescribed, true)?;
            let misfit: Vec<f64> = band
                .iter()
                .zip(&targets)
                .map(|(&i, t)| t - u[self.contact_dofs[i]])
                .collect();
            let correction = self.condense(v, &band, &misfit)?;
            for (x, dx) in u.iter_mut().zip(&correction) {
                *x += dx;
            }
        }
        Ok(Some(u))
    }

    /// `v + Σ μ_j w_j` with `μ` such that the band nodes take `targets`.
    fn condense(&self, mut v: Vec<f64>, band: &[usize], targets: &[f64]) -> Result<Vec<f64>> {
        let m = band.len();
        if m == 0 {
            return Ok(v);
        }
        let dof = |a: usize| self.contact_dofs[band[a]];
        let w = |b: usize| &self.responses[&band[b]];
        let matrix = DMatrix::from_fn(m, m, |a, b| 0.5 * (w(b)[dof(a)] + w(a)[dof(b)]));
        let rhs = DVector::from_fn(m, |a, _| targets[a] - v[dof(a)]);
        let cholesky = matrix.cholesky().ok_or_else(|| {
            band_error(format!(
                "the condensed band matrix of {m} contact nodes is not positive definite"
            ))
        })?;
        let mu = cholesky.solve(&rhs);
        for b in 0..m {
            let (coefficient, response) = (mu[b], w(b));
            for (x, y) in v.iter_mut().zip(response) {
                *x += coefficient * y;
            }
        }
        if v.iter().any(|x| !x.is_finite()) {
            return Err(band_error(
                "the condensed band solve produced non-finite values".into(),
            ));
        }
        Ok(v)
    }

    /// Compute the unit responses of the band nodes not yet known, in one blocked solve.
    fn ensure_responses(&mut self, band: &[usize]) -> Result<()> {
        let missing: Vec<usize> = band
            .iter()
            .copied()
            .filter(|i| !self.responses.contains_key(i))
            .collect();
        if missing.is_empty() {
            return Ok(());
        }
        let dofs: Vec<usize> = missing.iter().map(|&i| self.contact_dofs[i]).collect();
        let columns = self.solver.unit_responses(&self.base_mask, &dofs)?;
        for (i, column) in missing.into_iter().zip(columns) {
            self.responses.insert(i, column);
        }
        Ok(())
    }
}
