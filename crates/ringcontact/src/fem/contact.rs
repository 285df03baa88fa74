//! Punch contact on an assembled axisymmetric model (dimensionless: `a = 1`, `E* = 1`).
//!
//! Displacements are `(u_r, u_z)` with `z` up, the solid below `z = 0`; the punch pushes down, so
//! the deflection is `w = -u_z`. Supports: `u = 0` on the far boundary, `u_r = 0` on the axis.
//!
//! * **Flat punches**: `u_z = -d` on the contact line, `u_r` free (frictionless).
//! * **Concave punches**: unilateral constraints at every contact-line node,
//!   `u_z <= -d + g(r)` (no penetration), reaction `λ = -(K u - f)_z >= 0` (compression), and
//!   `λ (u_z + d - g) = 0`, solved exactly by the primal-dual active-set method (Hintermüller, Ito
//!   and Kunisch 2002): the active set is `{λ > 0}` ∪ `{u_z > -d + g}` of the previous iterate,
//!   until it repeats.
//!
//! The force is the sum of the nodal reactions of the contact line (consistent, since the element
//! stiffness carries the `2π r` factor).

use crate::error::{Error, Result};
use crate::fem::contact_band::BandedSystem;
use crate::mesh::triangulation::{tags, Degree, Mesh};
use crate::punch::PunchKind;
use crate::sparse::constrained::ConstrainedCholesky;

/// Times a banded solve whose core was released is retried with a higher core before the
/// factorisation-per-iteration loop takes over.
const BAND_RETRIES: usize = 2;

/// An active-set iteration that changes at most this many nodes is creeping: the hybrid loop
/// hands over to the banded solve. Cold starts change about half as many nodes per iteration as
/// the one before (266, 48, 20, 10, 4, 2 on a 7e4-unknown linear gap model).
const CREEP_CHANGES: usize = 12;

/// Fewest nodes above the inner edge left in the band when the hybrid loop hands over (at least
/// twice the last iteration's changes, plus four).
const CREEP_BAND_NODES: usize = 8;

/// Window of the free-edge secant step: two successive plain steps of the edge whose ratio lies in
/// it (same direction, shrinking about by half, as near a free edge) are extrapolated
/// (`ContactModel::edge_secant`). Steps still far from the edge shrink more slowly (0.68 on a P1
/// model whose edge lies off its refined zone: the jump overshot and cost a factorisation) or
/// faster (0.03 where the first steps cross the coarse part of the line).
const EDGE_SECANT_RATIO: std::ops::RangeInclusive<f64> = 0.25..=0.6;

/// Iteration cap of the active-set loop.
const MAX_ACTIVE_SET_ITERATIONS: usize = 100;

/// Contact nodes (the axis's included) from which a disk of contact at the axis counts as
/// resolved ([`ContactModel::check_single_ring`]): the artefact of a nearly closed hole is the
/// axis node alone.
const RESOLVED_DISK_NODES: usize = 4;

/// Result of one contact solve.
#[derive(Clone, Debug)]
pub struct ContactSolution {
    /// Total force (units of `E* a h` or `E* a d`).
    pub force: f64,
    /// Inner contact radius `b/a` located between the last free and the first active node.
    pub inner_radius: f64,
    /// Spacing of the contact-line nodes around `b` (0 for flat punches and full contact): the
    /// resolution of the discrete contact boundary.
    pub inner_node_spacing: f64,
    /// Active-set iterations (1 for flat punches).
    pub iterations: usize,
    /// `max(-λ_i)⁺/max λ` over active and `max(-gap_i)⁺/d` over inactive nodes: zero at an exact
    /// solution.
    pub complementarity_residual: f64,
    /// `(r, λ_i)` of the contact-line nodes, ascending in `r` (nodal reaction forces).
    pub reactions: Vec<(f64, f64)>,
    /// Radii of the contact-line nodes in contact (constrained), ascending.
    pub active_radii: Vec<f64>,
    /// Nodal displacements.
    pub displacement: Vec<f64>,
    /// The located edge's conditioning at the converged active set ([`Conditioning`]).
    pub conditioning: Conditioning,
    /// Outer contact radius: the rim `r = 1` for a punch with one, else the free outer edge
    /// located as the inner one is ([`ContactModel::with_free_edges`]).
    pub outer_radius: f64,
    /// Spacing of the contact-line nodes around the free outer edge (0 at a rim).
    pub outer_node_spacing: f64,
}

impl ContactSolution {
    /// The solution of a model whose length unit is `frame a` ([`ContactModel::with_free_edges`])
    /// in units of `a`: radii and spacings times `frame`, forces times `frame²`; the
    /// displacement stays the model's (its mesh's units), and the conditioning, a ratio of
    /// lengths, is unchanged.
    pub fn in_units_of_a(mut self, frame: f64) -> Self {
        let area = frame * frame;
        self.force *= area;
        self.inner_radius *= frame;
        self.inner_node_spacing *= frame;
        self.outer_radius *= frame;
        self.outer_node_spacing *= frame;
        for (r, lambda) in &mut self.reactions {
            *r *= frame;
            *lambda *= area;
        }
        for r in &mut self.active_radii {
            *r *= frame;
        }
        self
    }
}

/// How a concave solution's located edge, or its full contact, moves with the depth, from one
/// more solve at its converged active set ([`ContactModel::concave_with_sensitivity`]).
#[derive(Clone, Copy, Debug)]
pub struct Conditioning {
    /// `db/dd`: the located inner radius's change per unit depth
    /// ([`ContactModel::edge_depth_sensitivity`]); 0 for flat punches and without a hole.
    pub edge_depth_sensitivity: f64,
    /// Full contact: the relative depth decrease `Δd/d` that would release the innermost contact
    /// node off the axis ([`ContactModel::opening_margins`]); infinite otherwise.
    pub opening_margin: f64,
    /// Full contact: a lower bound of the relative depth decrease at which the contact opens at
    /// the axis, extrapolated from the two innermost nodes' margins
    /// ([`ContactModel::opening_margins`]; meaningful for a profile smooth at the axis);
    /// `-inf` otherwise.
    pub closure_margin: f64,
}

impl Default for Conditioning {
    /// Unknown: no edge movement, no margins.
    fn default() -> Self {
        Conditioning {
            edge_depth_sensitivity: 0.0,
            opening_margin: f64::INFINITY,
            closure_margin: f64::NEG_INFINITY,
        }
    }
}

/// The free side's extrapolation of the inner radius ([`ContactModel::locate_inner_radius`]).
enum Extrapolated {
    /// No node before the active ring is free (or only the axis node).
    NoHole,
    /// Too few free nodes to extrapolate: the edge lies between these two radii.
    Between(f64, f64),
    /// The extrapolated root and the element gap it is clamped to.
    Root { root: f64, low: f64, high: f64 },
}

/// What the active-set loop does once an iteration only creeps (changes at most
/// [`CREEP_CHANGES`] nodes): near a free edge the primal-dual iteration otherwise releases one
/// node per factorisation (4-7 such steps).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Creep {
    /// Go on with one factorisation per new active set.
    Factorise,
    /// Hand the remaining steps to the banded solve ([`ContactModel::hand_over`]), again after
    /// each secant jump of the edge.
    HandToBand,
}

/// The loop's place in its [`Creep`] strategy.
struct CreepState {
    creep: Creep,
    /// Whether the hand-over is done (or never to be done): the secant may then jump at any step.
    handed_over: bool,
}

impl CreepState {
    fn new(creep: Creep) -> Self {
        CreepState {
            creep,
            handed_over: creep == Creep::Factorise,
        }
    }

    /// Whether the edge's secant may jump at a step that changed `changes` nodes: not where the
    /// loop is about to hand the creep over to the band (its steps then cost responses; a jump
    /// there delays the hand-over).
    fn secant_allowed(&self, changes: usize) -> bool {
        self.handed_over || changes > CREEP_CHANGES
    }

    /// A secant jump landed near the edge: the band may take over from there (at once when the
    /// step was creeping already).
    fn jumped(&mut self) {
        self.handed_over = self.creep == Creep::Factorise;
    }

    /// Whether a step that changed `changes` nodes hands over now (once).
    fn hands_over(&mut self, changes: usize) -> bool {
        let now = !self.handed_over && changes <= CREEP_CHANGES;
        self.handed_over |= now;
        now
    }
}

/// One primal-dual step: the displacement, its reactions and gaps, and the next active set.
struct PrimalDualStep {
    u: Vec<f64>,
    reactions: Vec<(f64, f64)>,
    gaps: Vec<f64>,
    next: Vec<bool>,
}

/// How a banded contact solve ended.
enum BandOutcome {
    /// Converged, with its active set.
    Solved(ContactSolution, Vec<bool>),
    /// The solution releases a core node (the band was too narrow): the largest radius released,
    /// and the active set reached.
    CoreReleased(f64, Vec<bool>),
    /// The band holds more than [`crate::fem::contact_band::MAX_BAND_NODES`] nodes.
    TooWide,
}

/// The model: mesh, contact-line nodes and the fixed supports.
pub struct ContactModel<'m> {
    pub mesh: &'m Mesh,
    /// Contact-line nodes sorted by `r`.
    pub contact_nodes: Vec<usize>,
    supports: Vec<bool>,
    /// The mesh's length unit in units of `a`: the contact line `[0, 1]` of the mesh is
    /// `[0, frame a]` ([`Self::with_free_edges`]; 1 for a punch with a rim).
    frame: f64,
    /// Whether the contact line ends at the punch's rim (its last node is a rim held in contact).
    rim: bool,
}

fn fem_error(reason: String) -> Error {
    Error::NoConvergence {
        method: "fem".into(),
        reason,
    }
}

impl<'m> ContactModel<'m> {
    /// Set up supports and the contact line; the mesh must be in units of the rim radius.
    /// `dofs` is the size of the system: `2 × nodes`, plus any extra dofs appended after the
    /// nodal ones (the far-field amplitude), which are left free.
    pub fn new(mesh: &'m Mesh, dofs: usize) -> Result<Self> {
        let mut contact_nodes = mesh.boundary_nodes(tags::CONTACT);
        contact_nodes.sort_by(|&a, &b| mesh.nodes[a][0].total_cmp(&mesh.nodes[b][0]));
        let rim = contact_nodes
            .last()
            .map(|&n| mesh.nodes[n][0])
            .unwrap_or(0.0);
        if (rim - 1.0).abs() > 1e-9 {
            return Err(Error::InvalidMesh {
                path: mesh.source.clone(),
                message: format!("the contact line ends at r = {rim}; meshes must be in units of the rim radius (a = 1)"),
            });
        }
        let mut supports = vec![false; dofs.max(2 * mesh.nodes.len())];
        for node in mesh.boundary_nodes(tags::FAR) {
            supports[2 * node] = true;
            supports[2 * node + 1] = true;
        }
        for node in mesh.boundary_nodes(tags::AXIS) {
            supports[2 * node] = true;
        }
        Ok(Self {
            mesh,
            contact_nodes,
            supports,
            frame: 1.0,
            rim: true,
        })
    }

    /// The model of a contact with two free edges (a free band): the mesh's contact line `[0, 1]`
    /// is `[0, frame a]`, with no rim at its end. By the scaling of linear elasticity, a
    /// displacement field `u(x)` of the problem in units of `a` is `frame u'(x / frame)` of the
    /// problem on the mesh, so the gap shape on the mesh is `g(frame r') / frame`, a depth `d`
    /// is `d / frame` and a force `F` is `F / frame²` (stresses are unchanged).
    pub fn with_free_edges(mut self, frame: f64) -> Self {
        self.frame = frame;
        self.rim = false;
        self
    }

    /// Gap shape at the contact node radius `r` of the mesh: `g(frame r) / frame`
    /// ([`Self::with_free_edges`]; `g(r)` for a punch with a rim).
    fn gap_at(&self, kind: PunchKind, r: f64) -> f64 {
        if self.rim {
            kind.gap_shape(r)
        } else {
            kind.gap_shape(self.frame * r) / self.frame
        }
    }

    /// The fixed supports (far arc, axis): one flag per dof of the system.
    pub(crate) fn supports(&self) -> &[bool] {
        &self.supports
    }

    /// Inner end `b/a` of the contact line of the mesh.
    pub(crate) fn contact_line_start(&self) -> f64 {
        self.contact_nodes
            .first()
            .map(|&n| self.mesh.nodes[n][0])
            .unwrap_or(0.0)
    }

    /// `(r, reaction)` at each contact node of a solution `u` without applied forces: the
    /// reaction is `-(K u)` at the node's `z` dof.
    fn reactions(&self, solver: &ConstrainedCholesky, u: &[f64]) -> Vec<(f64, f64)> {
        let dofs: Vec<usize> = self.contact_nodes.iter().map(|&n| 2 * n + 1).collect();
        let products = solver.product_at(u, &dofs);
        self.contact_nodes
            .iter()
            .zip(products)
            .map(|(&n, ku)| (self.mesh.nodes[n][0], -ku))
            .collect()
    }

    /// Flat-faced punch: `u_z = -depth` on the whole contact line.
    pub fn flat(&self, solver: &mut ConstrainedCholesky, depth: f64) -> Result<ContactSolution> {
        let dofs = self.supports.len();
        let mut constrained = self.supports.clone();
        let mut prescribed = vec![0.0; dofs];
        for &n in &self.contact_nodes {
            constrained[2 * n + 1] = true;
            prescribed[2 * n + 1] = -depth;
        }
        let zero = vec![0.0; dofs];
        let u = solver.solve(&zero, &constrained, &prescribed)?;
        let reactions = self.reactions(solver, &u);
        Ok(ContactSolution {
            active_radii: reactions.iter().map(|r| r.0).collect(),
            force: reactions.iter().map(|r| r.1).sum(),
            inner_radius: self.contact_line_start(),
            inner_node_spacing: 0.0,
            iterations: 1,
            complementarity_residual: 0.0,
            reactions,
            displacement: u,
            conditioning: Conditioning::default(),
            outer_radius: 1.0,
            outer_node_spacing: 0.0,
        })
    }

    /// Concave punch pressed to `depth` (units of `h`, with `h = 1`): unilateral contact by the
    /// primal-dual active-set method, starting from `initial_active` if given (else from the
    /// nodes where the rigid punch would penetrate the undeformed surface). Every iteration with a
    /// new active set is one numeric factorisation; [`Self::concave_banded`] needs one in all.
    pub fn concave(
        &self,
        solver: &mut ConstrainedCholesky,
        kind: PunchKind,
        depth: f64,
        initial_active: Option<Vec<bool>>,
    ) -> Result<(ContactSolution, Vec<bool>)> {
        let mut system = self.banded_system(solver, kind.clone(), f64::INFINITY);
        self.active_set_loop(&mut system, kind, depth, initial_active, Creep::Factorise)
    }

    /// The primal-dual active-set loop as named phases: a primal-dual step (one factorisation
    /// per new active set, [`Self::primal_dual_step`]); its end where the set repeats; the
    /// free edge's secant jump ([`Self::edge_secant`]); and, by the `creep` strategy, the
    /// hand-over of a creeping iteration to the banded solve ([`Self::hand_over`]).
    fn active_set_loop(
        &self,
        system: &mut BandedSystem,
        kind: PunchKind,
        depth: f64,
        initial_active: Option<Vec<bool>>,
        creep: Creep,
    ) -> Result<(ContactSolution, Vec<bool>)> {
        let bound = self.bound(kind.clone(), depth);
        let mut active = self.initial_active(initial_active, &bound);
        let mut creep = CreepState::new(creep);
        let zero = vec![0.0; self.supports.len()];
        // The last plain step of the free edge, `(from, to)` radii, for the secant step.
        let mut last_step: Option<(f64, f64)> = None;
        for iteration in 1..=MAX_ACTIVE_SET_ITERATIONS {
            let step = self.primal_dual_step(system, &bound, &active, &zero)?;
            let mut next = step.next;
            if next == active {
                let solution = self.converged(
                    &active,
                    step.reactions,
                    &step.gaps,
                    depth,
                    step.u,
                    iteration,
                );
                return Ok((solution, active));
            }
            let changes = next.iter().zip(&active).filter(|(a, b)| a != b).count();
            let edge_step = self.ring_edge(&active).zip(self.ring_edge(&next));
            if let (Some(edge_step), Some(previous)) = (edge_step, last_step) {
                if creep.secant_allowed(changes) {
                    if let Some(edge) = Self::edge_secant(previous, edge_step) {
                        next = self.active_set_for_radius(edge);
                        creep.jumped();
                    }
                }
            }
            last_step = edge_step;
            if creep.hands_over(changes) {
                match self.hand_over(system, kind.clone(), depth, &next, changes)? {
                    Some(BandOutcome::Solved(mut solution, active)) => {
                        solution.iterations += iteration;
                        return Ok((solution, active));
                    }
                    Some(BandOutcome::CoreReleased(_, reached)) => {
                        active = reached;
                        continue;
                    }
                    Some(BandOutcome::TooWide) | None => {}
                }
            }
            active = next;
        }
        Err(fem_error(format!(
            "the primal-dual active set did not settle in {MAX_ACTIVE_SET_ITERATIONS} iterations"
        )))
    }

    /// One primal-dual step from `active`: the displacement with the active nodes held at
    /// `bound` (no body force: `zero`), its reactions and gaps, and the next active set.
    fn primal_dual_step(
        &self,
        system: &mut BandedSystem,
        bound: &[f64],
        active: &[bool],
        zero: &[f64],
    ) -> Result<PrimalDualStep> {
        let (constrained, prescribed) = self.constraints(active, bound);
        let u = system.solver.solve(zero, &constrained, &prescribed)?;
        let reactions = self.reactions(system.solver, &u);
        let gaps = self.gaps(bound, &u);
        let next = self.next_active(active, &reactions, &gaps)?;
        Ok(PrimalDualStep {
            u,
            reactions,
            gaps,
            next,
        })
    }

    /// The hand-over of a creeping iteration to the banded solve: the nodes from
    /// [`CREEP_BAND_NODES`] (or twice the step's `changes` plus four) above the inner edge of
    /// `next` up are held as the core (one more factorisation), the remaining steps cost unit
    /// responses ([`Self::concave_banded`]); `None` for an empty active set.
    fn hand_over(
        &self,
        system: &mut BandedSystem,
        kind: PunchKind,
        depth: f64,
        next: &[bool],
        changes: usize,
    ) -> Result<Option<BandOutcome>> {
        let Some(first) = next.iter().position(|&a| a) else {
            return Ok(None);
        };
        // The remaining steps release about as many nodes as this one did, in all.
        let band_nodes = CREEP_BAND_NODES.max(2 * changes + 4);
        let above = (first + band_nodes).min(next.len() - 1);
        let core_radius = self.mesh.nodes[self.contact_nodes[above]][0];
        system.set_core(self.core_for(core_radius), core_radius);
        self.concave_banded(system, kind, depth, next.to_vec())
            .map(Some)
    }

    /// A punch with a rim whose converged contact is not one ring `[b, a]` (active nodes near the
    /// axis, free ones, then the ring: the punch touches the floor of its hole, as a gap
    /// `1 - ρ^n` with `n > 2` does before its ring closes) is declined by name: the model locates
    /// one free edge, and refining the mesh cannot make a disk and an annulus one. Only a disk that
    /// is resolved is taken as one: at least as wide as the free stretch between it and the ring,
    /// or held by [`RESOLVED_DISK_NODES`] nodes (a coarse model of a nearly closed hole may hold
    /// the axis node alone, which a finer one releases: the parabolic gap at `d = 2.9999 h`, hole
    /// 6.1e-3 a, on a first model of node spacing 2.7e-2 a; the cube `n = 3` holds a disk of
    /// 0.16-0.2 a on 5 to 40 nodes at `d = 2.4 h`, of 0.08-0.12 a on 3 to 19 at `d = 2.36 h`,
    /// narrower than the free stretch beside it on every model).
    fn check_single_ring(&self, kind: PunchKind, active: &[bool]) -> Result<()> {
        if !self.rim || !active.iter().any(|&a| a) || self.ring_edge(active).is_some() {
            return Ok(());
        }
        let radius = |i: usize| self.mesh.nodes[self.contact_nodes[i]][0];
        let last_inner = active
            .iter()
            .position(|&a| !a)
            .map_or(0, |i| i.saturating_sub(1));
        let ring_start = active.iter().rposition(|&a| !a).map_or(0, |i| i + 1);
        let (disk, free) = (
            radius(last_inner),
            radius(ring_start.min(active.len() - 1)) - radius(last_inner),
        );
        let resolved = disk >= free || last_inner + 1 >= RESOLVED_DISK_NODES;
        if !active[0] || !resolved {
            return Ok(());
        }
        Err(Error::OutOfRange {
            method: "fem".into(),
            reason: format!(
                "the {kind} touches the floor of its hole: the contact is a disk (r/a <= {}) and \
                 an annulus (from r/a = {}), which a model with one free edge does not resolve \
                 (docs/conventions.md fact 8)",
                crate::error::show(radius(last_inner)),
                crate::error::show(radius(ring_start.min(active.len() - 1)))
            ),
        })
    }

    /// Inner edge of an active set that is a ring (every contact node from the first active one
    /// outwards active): the first active node's radius; `None` otherwise.
    fn ring_edge(&self, active: &[bool]) -> Option<f64> {
        let first = active.iter().position(|&a| a)?;
        active[first..]
            .iter()
            .all(|&a| a)
            .then(|| self.mesh.nodes[self.contact_nodes[first]][0])
    }

    /// Secant step of the free edge. Near a free edge the contact pressure of a ring that is too
    /// wide (or narrow) by `δ` has a `1/√(r - x)` term of the wrong sign, and the primal-dual step
    /// moves the edge about half of `δ` (ratios 0.45-0.55 per step, one factorisation each). Two
    /// successive plain steps `x0 -> x1 -> x2` (the second starting where the first ended) that
    /// shrink by a ratio `ρ = (x2 - x1)/(x1 - x0)` in [`EDGE_SECANT_RATIO`] are extrapolated to the
    /// edge their geometric series converges to, `x2 + (x2 - x1) ρ/(1 - ρ)` (the secant root of the
    /// step as a function of the edge). The loop still ends only at an active set that repeats, so
    /// this changes the path, not the solution.
    fn edge_secant(previous: (f64, f64), step: (f64, f64)) -> Option<f64> {
        let (x0, x1) = previous;
        let (from, x2) = step;
        if from != x1 || x1 == x0 {
            return None;
        }
        let ratio = (x2 - x1) / (x1 - x0);
        EDGE_SECANT_RATIO
            .contains(&ratio)
            .then(|| x2 + (x2 - x1) * ratio / (1.0 - ratio))
    }

    /// [`Self::concave`] at the cost of one factorisation, for a warm start that places the free
    /// edge within a band: the contact nodes at `r >= core_radius` (the core) are held in
    /// contact in the factorised matrix, and the active-set iteration runs on the nodes below
    /// through their unit responses ([`BandedSystem`]). Returns `None` when the solution releases
    /// a core node (the band was too narrow) or the band needs more than
    /// [`crate::fem::contact_band::MAX_BAND_NODES`] responses; the caller then falls back to
    /// [`Self::concave`].
    fn concave_banded(
        &self,
        system: &mut BandedSystem,
        kind: PunchKind,
        depth: f64,
        initial_active: Vec<bool>,
    ) -> Result<BandOutcome> {
        let bound = self.bound(kind, depth);
        let mut active: Vec<bool> = initial_active
            .iter()
            .zip(&system.core)
            .map(|(&a, &c)| a || c)
            .collect();
        for iteration in 1..=MAX_ACTIVE_SET_ITERATIONS {
            let Some(u) = system.solve(&active, depth, 1.0, false)? else {
                return Ok(BandOutcome::TooWide);
            };
            let reactions = self.reactions(system.solver, &u);
            let gaps = self.gaps(&bound, &u);
            let next = self.next_active(&active, &reactions, &gaps)?;
            let released = next
                .iter()
                .zip(&system.core)
                .enumerate()
                .filter(|(_, (&a, &c))| c && !a)
                .map(|(i, _)| self.mesh.nodes[self.contact_nodes[i]][0])
                .fold(f64::NEG_INFINITY, f64::max);
            if released.is_finite() {
                return Ok(BandOutcome::CoreReleased(released, next));
            }
            if next == active {
                // The converged set once more with a step of iterative refinement.
                let Some(u) = system.solve(&active, depth, 1.0, true)? else {
                    return Ok(BandOutcome::TooWide);
                };
                let reactions = self.reactions(system.solver, &u);
                let gaps = self.gaps(&bound, &u);
                let solution = self.converged(&active, reactions, &gaps, depth, u, iteration);
                return Ok(BandOutcome::Solved(solution, active));
            }
            active = next;
        }
        Ok(BandOutcome::TooWide)
    }

    /// The given start, else the nodes where the rigid punch would penetrate the undeformed
    /// surface; never empty (the rim node always touches for `d > 0`; with two free edges the
    /// node nearest the punch's lowest point is taken).
    fn initial_active(&self, given: Option<Vec<bool>>, bound: &[f64]) -> Vec<bool> {
        let mut active = given.unwrap_or_else(|| bound.iter().map(|&b| b < 0.0).collect());
        if !active.iter().any(|&a| a) {
            // The node that comes nearest the punch: the rim's, or with two free edges the one
            // nearest the punch's lowest point (the smallest bound).
            let nearest = if self.rim {
                Some(active.len().saturating_sub(1))
            } else {
                (0..bound.len()).min_by(|&i, &j| bound[i].total_cmp(&bound[j]))
            };
            if let Some(node) = nearest.filter(|&n| n < active.len()) {
                active[node] = true;
            }
        }
        active
    }

    /// Constraint set and prescribed values of an active set: supports, and `u_z = bound` on the
    /// active contact nodes.
    fn constraints(&self, active: &[bool], bound: &[f64]) -> (Vec<bool>, Vec<f64>) {
        let mut constrained = self.supports.clone();
        let mut prescribed = vec![0.0; self.supports.len()];
        for ((&n, &b), &a) in self.contact_nodes.iter().zip(bound).zip(active) {
            if a {
                constrained[2 * n + 1] = true;
                prescribed[2 * n + 1] = b;
            }
        }
        (constrained, prescribed)
    }

    /// Prescribed `u_z` of each contact node if in contact: `-d + g(r)`.
    fn bound(&self, kind: PunchKind, depth: f64) -> Vec<f64> {
        self.contact_nodes
            .iter()
            .map(|&n| -depth + self.gap_at(kind.clone(), self.mesh.nodes[n][0]))
            .collect()
    }

    /// Gap `bound - u_z` of each contact node (negative: penetration).
    fn gaps(&self, bound: &[f64], u: &[f64]) -> Vec<f64> {
        self.contact_nodes
            .iter()
            .zip(bound)
            .map(|(&n, &b)| b - u[2 * n + 1])
            .collect()
    }

    /// The primal-dual active-set update: a node in contact stays if its reaction is compressive,
    /// a free node enters if it penetrates.
    fn next_active(
        &self,
        active: &[bool],
        reactions: &[(f64, f64)],
        gaps: &[f64],
    ) -> Result<Vec<bool>> {
        let mut next: Vec<bool> = active
            .iter()
            .zip(reactions)
            .zip(gaps)
            .map(|((&a, &(_, lambda)), &gap)| if a { lambda > 0.0 } else { gap < 0.0 })
            .collect();
        // Nodes at the singular rim stay in contact: P2/P3 vertices next to the rim carry
        // negative consistent reactions on very small elements, and releasing them one per
        // iteration costs a factorisation each. The protected zone is
        // 1 % of the ring's width; what negative reaction remains there is reported in the
        // complementarity residual.
        if let Some(first) = next.iter().position(|&a| a).filter(|_| self.rim) {
            let r = |i: usize| self.mesh.nodes[self.contact_nodes[i]][0];
            let zone = 1.0 - 0.01 * (1.0 - r(first));
            for (i, a) in next.iter_mut().enumerate().skip(first) {
                if r(i) >= zone {
                    *a = true;
                }
            }
        }
        if !next.iter().any(|&a| a) {
            return Err(fem_error(
                "the active set emptied: no contact at this depth".into(),
            ));
        }
        Ok(next)
    }

    /// Package a converged active set: force, located inner radius, complementarity residual.
    fn converged(
        &self,
        active: &[bool],
        reactions: Vec<(f64, f64)>,
        gaps: &[f64],
        depth: f64,
        u: Vec<f64>,
        iterations: usize,
    ) -> ContactSolution {
        let lambda_scale = reactions
            .iter()
            .map(|r| r.1.abs())
            .fold(f64::MIN_POSITIVE, f64::max);
        let mut residual: f64 = 0.0;
        for ((&a, &(_, lambda)), &gap) in active.iter().zip(&reactions).zip(gaps) {
            residual = residual.max(if a {
                (-lambda).max(0.0) / lambda_scale
            } else {
                (-gap).max(0.0) / depth
            });
        }
        let inner_radius = self.locate_inner_radius(active, gaps);
        let inner_node_spacing = self.spacing_at(active);
        let (outer_radius, outer_node_spacing) = if self.rim {
            (1.0, 0.0)
        } else {
            self.locate_outer_edge(active, gaps)
        };
        let force = reactions
            .iter()
            .zip(active)
            .filter(|(_, &a)| a)
            .map(|(r, _)| r.1)
            .sum();
        let active_radii = reactions
            .iter()
            .zip(active)
            .filter(|(_, &a)| a)
            .map(|(r, _)| r.0)
            .collect();
        ContactSolution {
            active_radii,
            force,
            inner_radius,
            inner_node_spacing,
            iterations,
            complementarity_residual: residual,
            reactions,
            displacement: u,
            conditioning: Conditioning::default(),
            outer_radius,
            outer_node_spacing,
        }
    }

    /// The banded system of this model for a core of contact nodes at `r >= core_radius`
    /// (see [`Self::concave_banded`]).
    pub fn banded_system<'s, 'a>(
        &self,
        solver: &'s mut ConstrainedCholesky<'a>,
        kind: PunchKind,
        core_radius: f64,
    ) -> BandedSystem<'s, 'a> {
        let core = self.core_for(core_radius);
        let contact_dofs = self.contact_nodes.iter().map(|&n| 2 * n + 1).collect();
        let shape = self
            .contact_nodes
            .iter()
            .map(|&n| self.gap_at(kind.clone(), self.mesh.nodes[n][0]))
            .collect();
        BandedSystem::new(
            solver,
            self.supports.clone(),
            contact_dofs,
            shape,
            core,
            core_radius,
        )
    }

    /// Inner contact radius from the free side: near a non-adhesive edge the gap grows like
    /// `(b - r)^{3/2}`, so `q = gap^{2/3}` is nearly linear in `r`. `q` is interpolated by a
    /// quadratic through the three free nodes next to the innermost active one (a line if only
    /// two exist) and its root is taken, clamped to the element gap between the last free and the
    /// first active node.
    fn locate_inner_radius(&self, active: &[bool], gaps: &[f64]) -> f64 {
        match self.extrapolated_inner_radius(active, gaps) {
            Extrapolated::NoHole => 0.0,
            Extrapolated::Between(low, high) => 0.5 * (low + high),
            Extrapolated::Root { root, low, high } => root.clamp(low, high),
        }
    }

    /// The root of [`Self::locate_inner_radius`]'s extrapolation before it is clamped to the
    /// element gap between the last free and the first active node (`low`, `high`). With two
    /// free edges, the inner edge of the active ring's nodes up to its outermost.
    fn extrapolated_inner_radius(&self, active: &[bool], gaps: &[f64]) -> Extrapolated {
        let radii: Vec<f64> = self
            .contact_nodes
            .iter()
            .map(|&n| self.mesh.nodes[n][0])
            .collect();
        let end = if self.rim {
            active.len()
        } else {
            active
                .iter()
                .rposition(|&a| a)
                .map_or(active.len(), |i| i + 1)
        };
        let cubic = self.mesh.degree == Degree::Cubic;
        extrapolated_edge(&radii[..end], &active[..end], &gaps[..end], cubic)
    }

    /// The free outer edge and the node spacing there ([`Self::with_free_edges`]): the inner
    /// edge's extrapolation ([`extrapolated_edge`]) on the contact line mirrored about the axis
    /// (`r -> -r`, order reversed) from the active ring's innermost node outwards. The
    /// line's end `r = 1` when its last node is in contact (no free node beyond: the caller
    /// widens the line).
    fn locate_outer_edge(&self, active: &[bool], gaps: &[f64]) -> (f64, f64) {
        let radius = |i: usize| self.mesh.nodes[self.contact_nodes[i]][0];
        let (Some(first), Some(last)) = (
            active.iter().position(|&a| a),
            active.iter().rposition(|&a| a),
        ) else {
            return (0.0, 0.0);
        };
        if last + 1 >= active.len() {
            return (radius(last), 0.0);
        }
        let mirrored = |values: &[f64]| values[first..].iter().rev().copied().collect::<Vec<_>>();
        let radii: Vec<f64> = (first..active.len()).rev().map(|i| -radius(i)).collect();
        let flags: Vec<bool> = active[first..].iter().rev().copied().collect();
        let cubic = self.mesh.degree == Degree::Cubic;
        let edge = match extrapolated_edge(&radii, &flags, &mirrored(gaps), cubic) {
            Extrapolated::NoHole => radius(last),
            Extrapolated::Between(low, high) => -0.5 * (low + high),
            Extrapolated::Root { root, low, high } => -root.clamp(low, high),
        };
        (edge, radius(last + 1) - radius(last))
    }

    /// Distance between the last free and the first active contact node.
    fn spacing_at(&self, active: &[bool]) -> f64 {
        // The first node of the ring that reaches the rim; with two free edges, the first
        // active node (the nodes beyond the outer edge are free too).
        let first = if self.rim {
            active.iter().rposition(|&a| !a).map_or(0, |i| i + 1)
        } else {
            active.iter().position(|&a| a).unwrap_or(0)
        };
        let r = |i: usize| self.mesh.nodes[self.contact_nodes[i]][0];
        if first == 0 || first >= active.len() || (first == 1 && r(0) == 0.0) {
            return 0.0;
        }
        r(first) - r(first - 1)
    }

    /// Concave punch at `depth`: [`Self::concave_banded`] on `system` when its band holds the free
    /// edge, else [`Self::concave`] (one factorisation per active-set change).
    pub fn concave_with(
        &self,
        system: &mut BandedSystem,
        kind: PunchKind,
        depth: f64,
        initial_active: Option<Vec<bool>>,
    ) -> Result<(ContactSolution, Vec<bool>, bool)> {
        if !self.rim {
            // Two free edges: the band's core (every node above a radius) does not apply; one
            // factorisation per active-set change.
            let (solution, active) =
                self.active_set_loop(system, kind, depth, initial_active, Creep::Factorise)?;
            return Ok((solution, active, false));
        }
        let mut warm = initial_active;
        if let Some(start) = warm.clone() {
            let mut start = start;
            for _ in 0..=BAND_RETRIES {
                let lowest = start
                    .iter()
                    .position(|&a| a)
                    .map(|i| self.mesh.nodes[self.contact_nodes[i]][0]);
                match self.concave_banded(system, kind.clone(), depth, start)? {
                    BandOutcome::Solved(solution, active) => return Ok((solution, active, true)),
                    BandOutcome::TooWide => break,
                    BandOutcome::CoreReleased(radius, reached) => {
                        // Move the core above the released node by twice the band's width (from
                        // the lowest node the start held to the core), refactorise. (The width
                        // was once taken from the released node, which lies above the core: it
                        // was never positive, and the core crept up one released node per
                        // factorisation.)
                        let lowest = lowest.unwrap_or(radius);
                        let width = (system.core_radius - lowest).max(radius - system.core_radius);
                        let core_radius = radius + 2.0 * width.max(f64::EPSILON);
                        system.set_core(self.core_for(core_radius), core_radius);
                        warm = Some(reached.clone());
                        start = reached;
                    }
                }
            }
        }
        let (solution, active) =
            self.active_set_loop(system, kind, depth, warm, Creep::HandToBand)?;
        Ok((solution, active, false))
    }

    /// Contact nodes at `r >= radius`.
    fn core_for(&self, radius: f64) -> Vec<bool> {
        self.contact_nodes
            .iter()
            .map(|&n| self.mesh.nodes[n][0] >= radius)
            .collect()
    }

    /// Concave punch under force control: Newton on the depth. At a fixed active set the force is
    /// affine in the depth, `F(d) = F(d0) + k (d - d0)`, with `k` from one more solve (same
    /// constraint set, unit depth increment); each step re-solves the contact at the new depth,
    /// until the depth and the active set settle. Solves go through `system` (one factorisation
    /// for every depth while its core holds).
    pub fn concave_at_force(
        &self,
        system: &mut BandedSystem,
        kind: PunchKind,
        target_force: f64,
        depth_guess: f64,
        initial_active: Option<Vec<bool>>,
        relative_tolerance: f64,
    ) -> Result<(ContactSolution, f64)> {
        let mut depth = depth_guess;
        let mut warm = initial_active;
        let mut iterations = 0;
        for _ in 0..MAX_ACTIVE_SET_ITERATIONS {
            let (solution, active, banded) =
                self.concave_with(system, kind.clone(), depth, warm.take())?;
            iterations += solution.iterations;
            // Force per unit depth at this active set: prescribed u_z = -1 on active nodes.
            let unit = self.unit_depth_response(system, &active, banded)?;
            let stiffness: f64 = self
                .reactions(system.solver, &unit)
                .iter()
                .zip(&active)
                .filter(|(_, &a)| a)
                .map(|(r, _)| r.1)
                .sum();
            if stiffness.is_nan() || stiffness <= 0.0 {
                return Err(fem_error(
                    "non-positive contact stiffness under force control".into(),
                ));
            }
            let step = (target_force - solution.force) / stiffness;
            let settled = step.abs() <= 1e-3 * relative_tolerance * depth.abs().max(1e-12);
            if settled {
                self.check_single_ring(kind.clone(), &active)?;
                let mut solution = solution;
                solution.iterations = iterations;
                self.fill_conditioning(system.solver, kind, depth, &active, &mut solution, &unit);
                return Ok((solution, depth));
            }
            depth = (depth + step).max(0.5 * depth);
            warm = Some(active);
        }
        Err(fem_error("force control: the depth did not settle".into()))
    }

    /// Concave punch at `depth` with the located edge's conditioning
    /// ([`Self::edge_depth_sensitivity`], [`Self::opening_margins`]) filled in:
    /// [`Self::concave_with`] and one more solve on the converged constraint set (a
    /// back-substitution, or the band's responses).
    pub(crate) fn concave_with_sensitivity(
        &self,
        system: &mut BandedSystem,
        kind: PunchKind,
        depth: f64,
        initial_active: Option<Vec<bool>>,
    ) -> Result<ContactSolution> {
        let (mut solution, active, banded) =
            self.concave_with(system, kind.clone(), depth, initial_active)?;
        self.check_single_ring(kind.clone(), &active)?;
        let unit = self.unit_depth_response(system, &active, banded)?;
        self.fill_conditioning(system.solver, kind, depth, &active, &mut solution, &unit);
        Ok(solution)
    }

    /// Fill in `solution`'s [`Conditioning`] ([`Self::edge_depth_sensitivity`],
    /// [`Self::opening_margins`]) from its [`Self::unit_depth_response`] `unit`.
    fn fill_conditioning(
        &self,
        solver: &ConstrainedCholesky,
        kind: PunchKind,
        depth: f64,
        active: &[bool],
        solution: &mut ContactSolution,
        unit: &[f64],
    ) {
        let (opening_margin, closure_margin) =
            self.opening_margins(solver, depth, active, solution, unit);
        solution.conditioning = Conditioning {
            edge_depth_sensitivity: self
                .edge_depth_sensitivity(kind, depth, active, solution, unit),
            opening_margin,
            closure_margin,
        };
    }

    /// Full contact (every contact node off the axis active): `(μ1, μ0_low)`. `μ_i`, the
    /// relative decrease of the depth `Δd/d` at which contact node `i` would release: at a fixed
    /// active set its reaction is affine in the depth, `λ(d) = λ(d0) + (d - d0) λ'` with `λ'`
    /// the reaction of the [`Self::unit_depth_response`], so `μ_i = λ_i / (d λ'_i)`. `μ1` is the
    /// innermost node's off the axis (the axis node's reaction vanishes with its area and is
    /// skipped). For a profile smooth at the axis the margin is even and smooth in `r`, so the
    /// two innermost nodes' give the axis' `μ0 = μ1 - (μ2 - μ1) r1² / (r2² - r1²)`, and
    /// `μ0_low = μ0 - |μ1 - μ0|` keeps the whole extrapolation as its uncertainty.
    /// `(inf, -inf)` when a hole is located or the nodes would not release.
    ///
    /// A hole opens as the innermost node releases: when the model's own error, as a relative
    /// depth error, exceeds `μ1`, the model cannot tell a closed contact from an open hole; when
    /// it is below `μ0_low`, no hole is open at all.
    fn opening_margins(
        &self,
        solver: &ConstrainedCholesky,
        depth: f64,
        active: &[bool],
        solution: &ContactSolution,
        unit: &[f64],
    ) -> (f64, f64) {
        let none = (f64::INFINITY, f64::NEG_INFINITY);
        let radius = |i: usize| self.mesh.nodes[self.contact_nodes[i]][0];
        let closed = (0..active.len()).all(|i| active[i] || radius(i) <= 0.0);
        if !closed || unit.len() != solution.displacement.len() {
            return none;
        }
        let mut inner = (0..active.len()).filter(|&i| radius(i) > 0.0);
        let (Some(first), second) = (inner.next(), inner.next()) else {
            return none;
        };
        let rates = self.reactions(solver, unit);
        let margin = |i: usize| {
            let m = solution.reactions[i].1 / (rates[i].1 * depth);
            (rates[i].1 > 0.0 && m.is_finite() && m >= 0.0).then_some(m)
        };
        let Some(mu1) = margin(first) else {
            return none;
        };
        let closure = second
            .and_then(|j| margin(j).map(|mu2| (radius(j), mu2)))
            .map_or(f64::NEG_INFINITY, |(r2, mu2)| {
                let r1 = radius(first);
                let mu0 = mu1 - (mu2 - mu1) * r1 * r1 / (r2 * r2 - r1 * r1);
                mu0 - (mu1 - mu0).abs()
            });
        (mu1, closure)
    }

    /// Displacements `w` for the active set pressed down by a unit depth (`u_z = -1` on the
    /// active contact nodes, the gap shape left out), the other contact nodes free: at a fixed
    /// active set the solution is affine in the depth, `u(d) = u(d0) + (d - d0) w`. Through the
    /// band's responses when `banded` (the set was solved on the band), else one solve on the
    /// current factorisation.
    fn unit_depth_response(
        &self,
        system: &mut BandedSystem,
        active: &[bool],
        banded: bool,
    ) -> Result<Vec<f64>> {
        if banded {
            if let Some(unit) = system.solve(active, 1.0, 0.0, true)? {
                return Ok(unit);
            }
        }
        let dofs = self.supports.len();
        let mut constrained = self.supports.clone();
        let mut prescribed = vec![0.0; dofs];
        for (&n, &a) in self.contact_nodes.iter().zip(active) {
            if a {
                constrained[2 * n + 1] = true;
                prescribed[2 * n + 1] = -1.0;
            }
        }
        system
            .solver
            .solve(&vec![0.0; dofs], &constrained, &prescribed)
    }

    /// `db/dd`, the change of the located inner radius `b` ([`Self::locate_inner_radius`]) per
    /// unit depth at the converged active set `active` of `solution` (at `depth`):
    /// `db/dd = Σ_i (∂b/∂g_i)(∂g_i/∂d)`, where the free nodes' gaps `g_i = -d + g(r_i) - u_z,i`
    /// change by `∂g_i/∂d = -1 - w_i` (`w` the [`Self::unit_depth_response`]) and `∂b/∂g` is
    /// taken by a central difference along that direction, with a step that moves no gap by
    /// more than 1e-3 of itself. 0 without a located hole.
    ///
    /// It measures how well the edge is conditioned: near a closing hole (the parabolic gap as
    /// `d → 3h`) the edge moves tens of times the relative depth, so a small error of the
    /// displacement field (of the size of the relative force error) moves it that much more.
    pub(crate) fn edge_depth_sensitivity(
        &self,
        kind: PunchKind,
        depth: f64,
        active: &[bool],
        solution: &ContactSolution,
        unit: &[f64],
    ) -> f64 {
        if solution.inner_radius <= 0.0 || unit.len() != solution.displacement.len() {
            return 0.0;
        }
        let gaps = self.gaps(&self.bound(kind, depth), &solution.displacement);
        let rates: Vec<f64> = self
            .contact_nodes
            .iter()
            .map(|&n| -1.0 - unit[2 * n + 1])
            .collect();
        // The depth step that moves no free node's gap by more than 1e-3 of itself.
        let step = gaps
            .iter()
            .zip(&rates)
            .zip(active)
            .filter(|((&g, &rate), &a)| !a && g > 0.0 && rate != 0.0)
            .map(|((&g, &rate), _)| 1e-3 * g / rate.abs())
            .fold(f64::INFINITY, f64::min);
        if !step.is_finite() || step <= 0.0 {
            return 0.0;
        }
        // The root before its clamp: a located edge held at the clamp still moves with the depth
        // once the active set follows.
        let root = |sign: f64| {
            let moved: Vec<f64> = gaps
                .iter()
                .zip(&rates)
                .map(|(&g, &rate)| g + sign * step * rate)
                .collect();
            match self.extrapolated_inner_radius(active, &moved) {
                Extrapolated::Root { root, .. } => Some(root),
                _ => None,
            }
        };
        match (root(1.0), root(-1.0)) {
            (Some(up), Some(down)) if (up - down).is_finite() => (up - down) / (2.0 * step),
            _ => 0.0,
        }
    }

    /// Active set of a contact band `[inner, outer]` in units of `a` (to warm-start a contact
    /// with two free edges, [`Self::with_free_edges`]).
    pub fn active_set_between(&self, inner: f64, outer: f64) -> Vec<bool> {
        self.contact_nodes
            .iter()
            .map(|&n| (inner..=outer).contains(&(self.frame * self.mesh.nodes[n][0])))
            .collect()
    }

    /// Active set of a contact ring `[inner_radius, a]` (to warm-start the iteration).
    pub fn active_set_for_radius(&self, inner_radius: f64) -> Vec<bool> {
        self.contact_nodes
            .iter()
            .map(|&n| self.mesh.nodes[n][0] >= inner_radius)
            .collect()
    }
}

/// The inner edge of the ring of active nodes that reaches the end of `radii` (ascending), from
/// the free side: near a non-adhesive edge the gap grows like `(b - r)^{3/2}`, so
/// `q = gap^{2/3}` is nearly linear in `r`; `q` is interpolated by a quadratic through the three
/// free nodes next to the innermost active one (a line if only two exist), and its root is
/// returned with the element gap it lies in ([`ContactModel::locate_inner_radius`] clamps it).
fn extrapolated_edge(radii: &[f64], active: &[bool], gaps: &[f64], cubic: bool) -> Extrapolated {
    let r = |i: usize| radii[i];
    let q = |i: usize| gaps[i].max(0.0).powf(2.0 / 3.0);
    // Innermost node of the active ring that reaches the rim.
    let mut first = active.len() - 1;
    while first > 0 && active[first - 1] {
        first -= 1;
    }
    // A node on the axis carries no contact area (for quadratic elements even its consistent
    // reaction vanishes: the first moment of a vertex shape function is zero there), so a free
    // axis node alone does not open a hole.
    if first == 0 || (first == 1 && r(0) == 0.0) {
        return Extrapolated::NoHole;
    }
    let (i1, r_active) = (first - 1, r(first));
    let between = Extrapolated::Between(r(i1), r_active);
    // Cubic elements: the last free node lies in the element cut by the edge, where the
    // cubic cannot follow the `(b - r)^{3/2}` gap (its `q/(b - r)` is 30 % off, the nodes
    // before it 0.1-1 %), so the fit starts one node further out.
    let skip = usize::from(cubic && i1 >= 3);
    let end = i1 - skip;
    if end == 0 {
        return between;
    }
    let linear = {
        let (q1, q2) = (q(end), q(end - 1));
        if q2 <= q1 {
            return between;
        }
        r(end) + q1 * (r(end) - r(end - 1)) / (q2 - q1)
    };
    let estimate = if end >= 2 {
        // Newton form of the quadratic through (r3, q3), (r2, q2), (r1, q1); root near r1.
        let (x1, x2, x3) = (r(end), r(end - 1), r(end - 2));
        let (y1, y2, y3) = (q(end), q(end - 1), q(end - 2));
        let d12 = (y1 - y2) / (x1 - x2);
        let d23 = (y2 - y3) / (x2 - x3);
        let c = (d12 - d23) / (x1 - x3);
        // q(x) = y1 + (x - x1) (d12 + c (x - x2)) = 0, solved for t = x - x1 by Newton from
        // the linear estimate (the quadratic term is a small correction).
        let mut t = linear - x1;
        for _ in 0..20 {
            let value = y1 + t * (d12 + c * (t + x1 - x2));
            let slope = d12 + c * (2.0 * t + x1 - x2);
            if slope == 0.0 {
                break;
            }
            let step = value / slope;
            t -= step;
            if step.abs() < 1e-15 {
                break;
            }
        }
        let root = x1 + t;
        if root.is_finite() && root >= x1 && root <= r_active {
            root
        } else {
            linear
        }
    } else {
        linear
    };
    Extrapolated::Root {
        root: estimate,
        low: r(i1),
        high: r_active,
    }
}

/// Nodal pressure estimates along the contact line: the consistent reaction `λ_i` divided by the
/// node's weight `∫ N_i 2π r ds` over the contact edges (exact for a uniform pressure; for
/// quadratic elements an estimate). Returns `(r, p)` ascending in `r`.
pub fn nodal_pressure(mesh: &Mesh, reactions: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let nodes = {
        let mut n = mesh.boundary_nodes(tags::CONTACT);
        n.sort_by(|&a, &b| mesh.nodes[a][0].total_cmp(&mesh.nodes[b][0]));
        n
    };
    let position: std::collections::HashMap<usize, usize> =
        nodes.iter().enumerate().map(|(i, &n)| (n, i)).collect();
    let mut weights = vec![0.0; nodes.len()];
    let root = 0.6f64.sqrt();
    let gauss = [
        (0.5 - 0.5 * root, 5.0 / 18.0),
        (0.5, 8.0 / 18.0),
        (0.5 + 0.5 * root, 5.0 / 18.0),
    ];
    for edge in mesh.boundary.iter().filter(|e| e.tag == tags::CONTACT) {
        let (a, b) = (mesh.nodes[edge.nodes[0]], mesh.nodes[edge.nodes[1]]);
        let length = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
        for &(t, w) in &gauss {
            let r = a[0] + t * (b[0] - a[0]);
            let shape = match edge.nodes.len() {
                2 => vec![1.0 - t, t],
                3 => vec![
                    (1.0 - t) * (1.0 - 2.0 * t),
                    t * (2.0 * t - 1.0),
                    4.0 * t * (1.0 - t),
                ],
                // Cubic edge: ends, then the nodes at 1/3 and 2/3.
                _ => vec![
                    0.5 * (1.0 - t) * (2.0 - 3.0 * t) * (1.0 - 3.0 * t),
                    0.5 * t * (3.0 * t - 1.0) * (3.0 * t - 2.0),
                    4.5 * t * (1.0 - t) * (2.0 - 3.0 * t),
                    4.5 * t * (1.0 - t) * (3.0 * t - 1.0),
                ],
            };
            for (k, &node) in edge.nodes.iter().enumerate() {
                if let Some(&i) = position.get(&node) {
                    weights[i] += w * length * shape[k] * 2.0 * std::f64::consts::PI * r;
                }
            }
        }
    }
    reactions
        .iter()
        .zip(&weights)
        .filter(|(_, &w)| w > 1e-12)
        .map(|(&(r, lambda), &w)| (r, lambda / w))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_edge_secant_lands_on_the_limit_of_a_geometric_approach() {
        // Edges b - δ ρ^k approach b; two successive steps give b exactly (the geometric series'
        // sum), from below and from above.
        let (b, delta) = (0.4505, 3e-3);
        for ratio in [0.3, 0.5, 0.55] {
            for sign in [1.0, -1.0] {
                let x = |k: i32| b - sign * delta * f64::powi(ratio, k);
                let edge = ContactModel::edge_secant((x(0), x(1)), (x(1), x(2))).unwrap();
                assert!(
                    (edge - b).abs() < 1e-14,
                    "ratio {ratio}: {edge} against {b}"
                );
            }
        }
    }

    #[test]
    fn the_edge_secant_keeps_out_of_steps_that_are_not_a_geometric_approach() {
        // Ratio outside the window (0.7: slow, 0.1: the step after a jump), a reversal, a second
        // step not starting where the first ended, and no movement.
        assert_eq!(ContactModel::edge_secant((0.40, 0.44), (0.44, 0.468)), None);
        assert_eq!(ContactModel::edge_secant((0.40, 0.44), (0.44, 0.444)), None);
        assert_eq!(ContactModel::edge_secant((0.40, 0.44), (0.44, 0.43)), None);
        assert_eq!(ContactModel::edge_secant((0.40, 0.44), (0.45, 0.47)), None);
        assert_eq!(ContactModel::edge_secant((0.44, 0.44), (0.44, 0.45)), None);
    }
}
