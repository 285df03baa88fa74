//! The axisymmetric ring-element BEM as a [`Solver`]: exact elliptic kernel, Gauss-Chebyshev
//! collocation, its own node ladder for the error estimate.

use std::time::Instant;

use super::ladder::{Ladder, LocatedEdges, Rung, StudyCase};
use super::units::base;
use super::Solver;
use crate::bem::ring::{ContactRegion, RingSystem};
use crate::bem::ring_contact::{self, RingBemSolver, RingState};
use crate::error::{Error, Result};
use crate::numerics::tanh_sinh::TanhSinhRule;
use crate::scene::{Load, Scene};
use crate::solution::{PressureSample, Solution};

/// The ring BEM; it holds its [`RingBemSolver`] (quadrature built once), so one value solves
/// many scenes cheaply.
#[derive(Default)]
pub struct RingBem {
    solver: RingBemSolver,
}

impl RingBem {
    /// A ring BEM with its own solver.
    pub fn new() -> Self {
        Self::default()
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
        let rule = TanhSinhRule::new(1.0 / 16.0);
        let region = if case.eps > 0.0 {
            ContactRegion::Annulus { eps: case.eps }
        } else {
            ContactRegion::Disk
        };
        if case.punch.is_concave() {
            return Err(Error::Unsupported {
                method: "ring-bem".into(),
                reason: "convergence studies of the ring BEM cover the flat punches (its concave \
                         states are certified by the node ladder)"
                    .into(),
            });
        }
        let system = RingSystem::assemble(region, n, &rule);
        let field = system
            .solve(&vec![1.0; n])
            .ok_or_else(|| Error::NoConvergence {
                method: "ring-bem".into(),
                reason: "singular system".into(),
            })?;
        Ok(Rung {
            label: format!("N = {n}"),
            size: 1.0 / n as f64,
            unknowns: n,
            value: 0.5 * field.force,
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
