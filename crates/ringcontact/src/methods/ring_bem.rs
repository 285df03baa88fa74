//! The axisymmetric ring-element BEM as a [`Solver`]: exact elliptic kernel, Gauss-Chebyshev
//! collocation, its own node ladder for the error estimate.

use std::time::Instant;

use super::ladder::{Ladder, LocatedEdges, Rung, StudyCase};
use super::units::base;
use super::Solver;
use crate::bem::ring::{ContactRegion, RingSystem};
use crate::bem::ring_contact::{self, RingBemSolver};
use crate::error::{Error, Result};
use crate::numerics::tanh_sinh::TanhSinhRule;
use crate::punch::PunchKind;
use crate::scene::{Load, Scene};
use crate::solution::{PressureSample, Solution};

pub use crate::bem::ring_contact::{BandState, RingState};

/// The ring BEM; it holds its [`RingBemSolver`] (quadrature built once), so one value solves
/// many scenes cheaply. Besides [`Solver::solve`] (a scene in physical units), it answers in the
/// unit scene (`a = h = E* = 1`) with the method's own [`RingState`]: `γ`, `γ1`, `γ2`, the edges,
/// their stress intensities and the pressure, which the JKR analysis and the studies read.
#[derive(Default)]
pub struct RingBem {
    solver: RingBemSolver,
}

impl RingBem {
    /// A ring BEM with its own solver.
    pub fn new() -> Self {
        Self::default()
    }

    /// The BEM engine itself, for the library's analyses built on its lower-level routes.
    pub fn engine(&self) -> &RingBemSolver {
        &self.solver
    }

    /// Factorisations so far (the cost of the answers given).
    pub fn factorisations(&self) -> usize {
        self.solver.factorisations()
    }

    /// A flat-faced punch's contact of `b/a = eps` (0 for the disk) at unit depth: `γ = F/(2 E* d a)`.
    pub fn flat(&self, eps: f64, tolerance: f64) -> Result<RingState> {
        self.solver.flat(eps, tolerance)
    }

    /// `γ = F/(2 E* d a)` of a flat-faced punch on `b/a = eps` (0: the disk) with `nodes`
    /// collocation nodes and no refinement: one rung of its node ladder.
    pub fn flat_on_nodes(&self, eps: f64, nodes: usize) -> Result<f64> {
        let rule = TanhSinhRule::new(1.0 / 16.0);
        let region = if eps > 0.0 {
            ContactRegion::Annulus { eps }
        } else {
            ContactRegion::Disk
        };
        let field = RingSystem::assemble(region, nodes, &rule)
            .solve(&vec![1.0; nodes])
            .ok_or_else(|| Error::NoConvergence {
                method: ring_contact::METHOD.into(),
                reason: format!("singular system at {nodes} nodes"),
            })?;
        Ok(0.5 * field.force)
    }

    /// A concave punch whose free inner edge sits at `b/a = eps`: `γ1 = d/h`, `γ2 = F/(2 E* h a)`.
    pub fn concave_at_ratio(
        &self,
        kind: &PunchKind,
        eps: f64,
        tolerance: f64,
    ) -> Result<RingState> {
        self.solver.concave_at_ratio(kind, eps, tolerance)
    }

    /// A concave punch pressed to `d/h = depth_over_hole` (full contact past the closure).
    pub fn concave_at_depth(
        &self,
        kind: &PunchKind,
        depth_over_hole: f64,
        tolerance: f64,
    ) -> Result<RingState> {
        self.solver
            .concave_at_depth(kind, depth_over_hole, tolerance)
    }

    /// A concave punch under the force `F/(2 E* h a) = force`.
    pub fn concave_at_force(
        &self,
        kind: &PunchKind,
        force: f64,
        tolerance: f64,
    ) -> Result<RingState> {
        self.solver.concave_at_force(kind, force, tolerance)
    }

    /// A concave punch in full contact at `d/h = depth_over_hole` (past its closure).
    pub fn full_contact(
        &self,
        kind: &PunchKind,
        depth_over_hole: f64,
        tolerance: f64,
    ) -> Result<RingState> {
        self.solver.full_contact(kind, depth_over_hole, tolerance)
    }

    /// The contact band `inner < ρ < outer` held against the gap `gap(ρ)` at `d/h = depth`:
    /// its force and the stress intensities of both edges (a prescribed band, no complementarity).
    pub fn prescribed_band(
        &self,
        gap: impl Fn(f64) -> f64,
        inner: f64,
        outer: f64,
        depth: f64,
        tolerance: f64,
    ) -> Result<BandState> {
        self.solver
            .prescribed_band(gap, inner, outer, depth, tolerance)
    }

    /// A free band of half-width `half_width` whose edges carry the stress intensity
    /// `intensity` (the JKR equilibrium of a band), centred near `centre_hint` if given.
    pub fn band_with_edge_intensity(
        &self,
        kind: &PunchKind,
        half_width: f64,
        intensity: f64,
        tolerance: f64,
        centre_hint: Option<f64>,
    ) -> Result<RingState> {
        self.solver
            .band_with_edge_intensity(kind, half_width, intensity, tolerance, centre_hint)
    }
}

impl Solver for RingBem {
    fn name(&self) -> &'static str {
        ring_contact::METHOD
    }

    fn compute(&self, scene: &Scene) -> Result<Solution> {
        solve_ring_bem(scene, &self.solver)
    }
}

/// The ring BEM's ladder: `6 + 2k` nodes on a flat-faced punch's contact (its concave states are
/// certified by their own node ladder).
impl Ladder for RingBem {
    fn check_levels(&self, _case: &StudyCase, _levels: usize) -> Result<()> {
        Ok(())
    }

    fn level(&self, case: &StudyCase, k: usize, _located: LocatedEdges) -> Result<Rung> {
        let n = 6 + 2 * k;
        if case.punch.is_concave() {
            return Err(Error::Unsupported {
                method: "ring-bem".into(),
                reason: "convergence studies of the ring BEM cover the flat punches (its concave \
                         states are certified by the node ladder)"
                    .into(),
            });
        }
        Ok(Rung {
            label: format!("N = {n}"),
            size: 1.0 / n as f64,
            unknowns: n,
            value: self.flat_on_nodes(case.eps, n)?,
            free_edge: None,
            outer_edge: None,
        })
    }
}

/// Solve with a given ring-BEM solver (reuse it across many scenes to keep its quadrature).
fn solve_ring_bem(scene: &Scene, solver: &RingBemSolver) -> Result<Solution> {
    let start = Instant::now();
    let factorised = solver.factorisations();
    let kind = scene.punch.kind.clone();
    let tol = scene.tolerance.unwrap_or(crate::scene::DEFAULT_TOLERANCE);
    let h = scene.punch.hole_depth;
    let a = scene.punch.rim_radius;
    let es = scene.material.effective_modulus;
    let state = match (kind.is_concave(), scene.load) {
        (false, _) => solver.flat(scene.punch.inner_ratio(), tol)?,
        (_, Load::ContactRatio(eps)) => solver.concave_at_ratio(&kind, eps, tol)?,
        (_, Load::Depth(d)) => solver.concave_at_depth(&kind, d / h, tol)?,
        (_, Load::Force(f)) => solver.concave_at_force(&kind, f / (2.0 * es * h * a), tol)?,
    };
    let wall_s = start.elapsed().as_secs_f64();
    let iterations = solver.factorisations() - factorised;
    Ok(Solution {
        iterations,
        provenance: format!(
            "ring BEM, Gauss-Chebyshev collocation, N = {} nodes, {iterations} factorisations, \
             self-convergence estimate against the previous ladder rung",
            state.unknowns
        ),
        ..ring_state_to_solution(scene, &state, wall_s)?
    })
}

fn ring_state_to_solution(scene: &Scene, state: &RingState, wall_s: f64) -> Result<Solution> {
    let a = scene.punch.rim_radius;
    let es = scene.material.effective_modulus;
    let base = base(
        scene,
        ring_contact::METHOD,
        state.eps,
        (state.gamma, state.gamma1, state.gamma2),
        wall_s,
    )?;
    // Pressures and intensities scale with the depth (flat punches) or the hole depth (concave).
    let length = if state.gamma.is_some() {
        base.depth
    } else {
        scene.punch.hole_depth
    };
    let pressure_scale = es * length / a;
    let k_scale = es * length / a.sqrt();
    Ok(Solution {
        outer_radius: state.outer_edge * a,
        // A free band has no rim (its outer edge is free: K = 0 there).
        stress_intensity_rim: scene
            .punch
            .kind
            .has_rim()
            .then_some(state.rim_stress_intensity * k_scale),
        stress_intensity_inner: Some(state.inner_stress_intensity * k_scale),
        error_estimate: Some(state.error_estimate),
        unknowns: state.unknowns,
        pressure: state
            .pressure
            .iter()
            .map(|&(r, p)| PressureSample {
                r: r * a,
                p: p * pressure_scale,
            })
            .collect(),
        ..base
    })
}
