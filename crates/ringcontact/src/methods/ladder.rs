//! The refinement ladder of a method, for convergence studies (solution verification): level 0
//! the coarsest discretisation of one state, each level finer, its value measured against the
//! ring BEM at 1e-11 ([`reference_value`]). Each refining method implements [`Ladder`] in its
//! own file; [`super::Method::ladder`] gives the one a method name stands for.

use crate::bem::ring_contact::RingBemSolver;
use crate::error::Result;
use crate::punch::PunchKind;

/// The state a convergence study refines.
#[derive(Clone, Debug)]
pub struct StudyCase {
    pub punch: PunchKind,
    /// `b/a` of the fixed annulus.
    pub eps: f64,
    /// `d/h` of a concave punch.
    pub depth: f64,
}

/// One level's solve: its label, representative size `h` (cell side for the grid BEM,
/// `1/sqrt(dofs)` for the FEM, `1/N` for the ring BEM), unknowns, value (`γ` of a flat-faced punch,
/// `γ2` of a concave one at its depth) and, for the FEM, the free edges it located.
#[derive(Clone, Debug)]
pub struct Rung {
    pub label: String,
    pub size: f64,
    pub unknowns: usize,
    pub value: f64,
    /// The free edge `b/a` the level located (the FEM on a concave punch or a free band).
    pub free_edge: Option<f64>,
    /// A free band's outer free edge `c/a`.
    pub outer_edge: Option<f64>,
}

/// The free edges the level below located (`b/a`, and a free band's `c/a`), around which the
/// next FEM level is refined; none before the first level and for the other methods.
#[derive(Clone, Copy, Debug, Default)]
pub struct LocatedEdges {
    pub inner: Option<f64>,
    pub outer: Option<f64>,
}

impl LocatedEdges {
    /// The edges `rung` located.
    pub fn of(rung: &Rung) -> Self {
        Self {
            inner: rung.free_edge,
            outer: rung.outer_edge,
        }
    }
}

/// A method's refinement ladder.
pub trait Ladder: Send + Sync {
    /// An error, before any level runs, when a study of `levels` levels of `case` cannot reach
    /// its finest level (too large a grid, more meshes than the family has).
    fn check_levels(&self, case: &StudyCase, levels: usize) -> Result<()>;

    /// Level `k` (from 0) of `case`, refined around the edges the level below `located`.
    fn level(&self, case: &StudyCase, k: usize, located: LocatedEdges) -> Result<Rung>;

    /// Whether level `k` of `case` needs the coarser levels solved first, for the edges they
    /// locate (the FEM on a concave punch refines around its free edge).
    fn refines_around_located_edges(&self, _case: &StudyCase) -> bool {
        false
    }

    /// The order at which the value converges in `h`, where one is known: the grid BEM's
    /// piecewise-constant pressure 1 (observed nearer 0.7 with the staircase edge), the FEM's
    /// force `2p` for elements of degree `p` on meshes graded toward the singular edges; the
    /// ring BEM converges faster than any power (none).
    fn expected_order(&self, _case: &StudyCase) -> Option<f64> {
        None
    }

    /// The relative error no level resolves (the FEM's unresolved component), which a bar from
    /// level differences cannot see; `None` when there is none.
    fn error_floor(&self) -> Option<f64> {
        None
    }
}

/// The value a study's levels are measured against: the ring BEM at tolerance 1e-11, `γ2` at the
/// depth of a concave punch, `γ` of a flat one.
pub fn reference_value(case: &StudyCase) -> Result<f64> {
    let ring = RingBemSolver::new();
    Ok(if case.punch.is_concave() {
        ring.concave_at_depth(&case.punch, case.depth, 1e-11)?
            .gamma2
            .unwrap_or(f64::NAN)
    } else {
        ring.flat(case.eps, 1e-11)?.gamma.unwrap_or(f64::NAN)
    })
}
