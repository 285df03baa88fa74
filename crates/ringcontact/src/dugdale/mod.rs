//! Adhesion at any Tabor parameter: the Maugis-Dugdale law on the ring BEM.
//!
//! The law ([`law`]): a tension `σ0` wherever the gap between punch and surface is in
//! `(0, δc]`, `δc = Δw/σ0`, contact where it closes. An equilibrium is a contact with cohesive
//! zones beside its free edges ([`configuration`]): the zones' tension in closed form
//! ([`uniform_load`]), the contact's pressure by the ring BEM with its free edges' singular
//! coefficients zero and each zone ending where the gap reaches `δc` (or at the face's edge).
//! The pull-off is the first extremum met along the path ([`path`]; on a recess, the lowest after
//! where pressing from the rim stops), under fixed load or fixed grips, refined on the node
//! ladder until its last two changes are within the tolerance.
//!
//! Units as `verify jkr`'s: depths in `d0 = sqrt(2π a Δw / E*)`, forces in Kendall's
//! `F0 = sqrt(8π E* Δw a³)` (negative: tensile); the Tabor parameter
//! `λ = 2 σ0 sqrt(a / (π E* Δw))`.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use serde::Serialize;

use crate::adhesion::D0H_RANGE;
use crate::bem::ring::{ContactRegion, RingSystem};
use crate::bem::ring_contact::RingBemSolver;
use crate::error::{Error, Result};
use crate::punch::{Contact, PunchKind, PunchName};

mod annulus;
pub mod configuration;
mod flat_disk;
pub mod law;
pub mod path;
mod recess;
mod suspended;
pub mod uniform_load;

pub use law::DugdaleLaw;
pub use path::{Control, PathPoint};

/// The method's name in errors and JSON.
pub const METHOD: &str = "ring-bem-dugdale";

/// Rounding floor of a pull-off's force and depth (units of `F0`, `d0`): node counts that agree
/// better are not taken as proof of a smaller error.
const ROUNDING_FLOOR: f64 = 1e-12;

/// Node counts climbed until the pull-off of two consecutive counts agree.
/// (Beyond 192 the disk's rows are not integrated to the accuracy the nodes could give.)
const NODE_LADDER: [usize; 8] = [16, 24, 32, 48, 64, 96, 128, 192];

/// The ladder starts at this many nodes per unit of the Tabor parameter: the Chebyshev nodes'
/// spacing at the contact's edge, about `1/N²` of `a²`, then resolves the zone of length `a/λ²`.
const NODES_PER_TABOR: f64 = 2.0;

/// Which edge of the contact lets go at the pull-off.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum DetachingEdge {
    /// The inner edge (the hole's side).
    Inner,
    /// The outer edge (the rim's side).
    Outer,
    /// Both at once.
    Both,
}

impl DetachingEdge {
    /// The name in JSON and text.
    pub fn name(self) -> &'static str {
        match self {
            DetachingEdge::Inner => "inner",
            DetachingEdge::Outer => "outer",
            DetachingEdge::Both => "both",
        }
    }
}

/// What a face needs beyond its profile: `b/a` of a fixed annulus, `d0/h` of a recessed face
/// (the concave punches; `h` the recess's depth, `d0 = sqrt(2π a Δw / E*)`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FaceParameters {
    /// `b/a` of a fixed annulus.
    pub eps: Option<f64>,
    /// `d0/h` of a recessed face.
    pub d0_over_h: Option<f64>,
}

impl FaceParameters {
    /// A fixed annulus's `b/a`.
    pub fn hole(eps: f64) -> Self {
        Self {
            eps: Some(eps),
            d0_over_h: None,
        }
    }

    /// A recessed face's `d0/h`.
    pub fn recess(d0_over_h: f64) -> Self {
        Self {
            eps: None,
            d0_over_h: Some(d0_over_h),
        }
    }
}

/// The pull-off of one punch under one control, in the units of `verify jkr`.
#[derive(Clone, Debug, Serialize)]
pub struct DugdalePulloff {
    /// The punch's name.
    pub punch: String,
    /// The adhesion law (`dugdale`).
    pub law: &'static str,
    /// Tabor parameter `λ = 2 σ0 sqrt(a / (π E* Δw))`.
    pub tabor: f64,
    /// `d0/h` of a recessed face (the concave punches).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub d0_over_h: Option<f64>,
    /// Fixed load or fixed grips.
    pub control: Control,
    /// Pull-off force `F/F0` (negative: tensile).
    pub pulloff_force: f64,
    /// Bound of its error (the change between the last two node counts), units of `F0`.
    pub pulloff_force_error: f64,
    /// Depth `d/d0` at the pull-off.
    pub pulloff_depth: f64,
    /// Bound of its error, units of `d0`.
    pub pulloff_depth_error: f64,
    /// The edge that lets go.
    pub detaching_edge: DetachingEdge,
    /// Contact `[c1, c2] / a` at the pull-off (`c1 = 0`: a disk; `c1 = c2`: none left, the
    /// whole face in tension).
    pub contact: [f64; 2],
    /// Loaded region (contact and cohesive zones) `[z1, z2] / a` at the pull-off.
    pub loaded_region: [f64; 2],
    /// Depths `d/d0` along the path as the punch is pulled (to the pull-off and beyond).
    pub path_depth: Vec<f64>,
    /// Forces `F/F0` along the path.
    pub path_force: Vec<f64>,
    /// Collocation nodes of the finer count.
    pub nodes: usize,
    /// Tolerance the estimate met.
    pub tolerance: f64,
}

/// The Maugis-Dugdale solver: the ring BEM and the unit disk's systems it has assembled (every
/// disk contact is that disk scaled, so a sweep assembles each node count once).
#[derive(Default)]
pub struct DugdaleSolver {
    ring: RingBemSolver,
    disks: Mutex<HashMap<usize, Arc<RingSystem>>>,
}

impl DugdaleSolver {
    /// A solver with the ring BEM's default quadrature.
    pub fn new() -> Self {
        Self::default()
    }

    /// The unit disk's system at `nodes` unknowns.
    fn disk(&self, nodes: usize) -> Arc<RingSystem> {
        let mut disks = self
            .disks
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        disks
            .entry(nodes)
            .or_insert_with(|| Arc::new(self.ring.system(ContactRegion::Disk, nodes)))
            .clone()
    }

    /// The pull-off of `kind` (with its `parameters`: `b/a` of a fixed annulus, `d0/h` of a
    /// recessed face) under the Dugdale law at `law`'s Tabor parameter, held by `control`,
    /// refined on the node ladder until its last two changes are within `tolerance` (units of
    /// `F0` and `d0`).
    pub fn pulloff(
        &self,
        kind: &PunchKind,
        parameters: FaceParameters,
        law: DugdaleLaw,
        control: Control,
        tolerance: f64,
    ) -> Result<DugdalePulloff> {
        if !(tolerance.is_finite() && tolerance > 0.0) {
            return Err(Error::invalid(
                "tol",
                format!(
                    "must be a finite number > 0; got {}",
                    crate::error::show(tolerance)
                ),
            ));
        }
        let face = Face::of(kind, parameters)?;
        let units = |p: &PathPoint| (p.depth, p.force / law::KENDALL_FORCE);
        let first = NODE_LADDER
            .iter()
            .position(|&n| n as f64 >= NODES_PER_TABOR * law.tabor)
            .unwrap_or(NODE_LADDER.len())
            .min(NODE_LADDER.len() - 3);
        let mut history: Vec<(f64, f64)> = Vec::new();
        let mut bracket: Option<f64> = None;
        let mut last_change = f64::INFINITY;
        for &nodes in &NODE_LADDER[first..] {
            let answer = face.with_family(self, kind, nodes, law, &mut |family| {
                let located = path::pulloff(family, control, bracket, tolerance)?;
                let pulloff = located.point;
                bracket = Some(located.parameter);
                history.push(units(&pulloff));
                let [.., (d2, f2), (d1, f1), (d0, f0)] = history[..] else {
                    return Ok(None);
                };
                // The larger of the last two changes: the ladder's convergence is geometric only
                // once the zone is resolved, and a single change can pass through zero before then.
                // Plus what locating the pull-off on its path leaves open.
                let [depth_spread, force_spread] = located.spread;
                let depth_error =
                    (d0 - d1).abs().max((d1 - d2).abs()).max(ROUNDING_FLOOR) + depth_spread;
                let force_error = (f0 - f1).abs().max((f1 - f2).abs()).max(ROUNDING_FLOOR)
                    + force_spread / law::KENDALL_FORCE;
                last_change = depth_error.max(force_error);
                if last_change > tolerance {
                    return Ok(None);
                }
                let configuration = pulloff.configuration;
                let path = path::path(family)?.samples;
                Ok(Some(DugdalePulloff {
                    punch: kind.name().to_string(),
                    law: "dugdale",
                    tabor: law.tabor,
                    d0_over_h: parameters.d0_over_h,
                    control,
                    pulloff_force: f0,
                    pulloff_force_error: force_error,
                    pulloff_depth: d0,
                    pulloff_depth_error: depth_error,
                    detaching_edge: face.detaching_edge(&pulloff),
                    contact: [configuration.inner, configuration.outer],
                    loaded_region: [configuration.zone_inner, configuration.zone_outer],
                    path_depth: path.iter().map(|(_, p)| units(p).0).collect(),
                    path_force: path.iter().map(|(_, p)| units(p).1).collect(),
                    nodes,
                    tolerance,
                }))
            })?;
            if let Some(answer) = answer {
                return Ok(answer);
            }
        }
        Err(Error::NoConvergence {
            method: METHOD.into(),
            reason: format!(
                "the pull-off at Tabor parameter {} changes by {last_change:.1e} over the node \
             counts up to N = {}, above the tolerance {tolerance:.1e} (the cohesive zone, about \
             a/λ² long, is too short for the ring's nodes)",
                crate::error::show(law.tabor),
                NODE_LADDER[NODE_LADDER.len() - 1]
            ),
        })
    }
}

/// Whether the Dugdale law is solved for `kind` with its `parameters`: an error naming what is
/// missing, invalid or not solved yet.
pub fn check_face(kind: &PunchKind, parameters: FaceParameters) -> Result<()> {
    Face::of(kind, parameters).map(|_| ())
}

/// The punch's face as the Dugdale solver sees it.
#[derive(Clone, Copy)]
enum Face {
    /// The whole face `r <= a` ([`Contact::Disk`]).
    Disk,
    /// The annular face `b <= r <= a` ([`Contact::FixedAnnulus`]).
    Annulus { hole: f64 },
    /// The recessed face `r <= a` of gap `h ĝ(r)` ([`Contact::RimAndFreeInner`]), `h = d0/s`.
    Recess { d0_over_h: f64 },
}

impl Face {
    /// The face of `kind` (with its `b/a = eps` for a fixed annulus); an error for a punch the
    /// law is not solved for yet, or a missing or invalid `eps`.
    fn of(kind: &PunchKind, parameters: FaceParameters) -> Result<Self> {
        let FaceParameters { eps, d0_over_h } = parameters;
        let unexpected = |flag: &str, what: &str| {
            Err(Error::invalid(
                flag,
                format!("{what}; the {} punch has none", kind.name()),
            ))
        };
        let contact = kind.contact();
        if eps.is_some() && contact != Contact::FixedAnnulus {
            return unexpected("eps", "fixes the hole of a fixed annulus");
        }
        if d0_over_h.is_some() && contact != Contact::RimAndFreeInner {
            return unexpected("d0h", "scales a recess's depth h");
        }
        match contact {
            Contact::Disk => Ok(Face::Disk),
            Contact::FixedAnnulus => {
                let hole = eps.ok_or_else(|| {
                    Error::invalid(
                        "eps",
                        format!("is needed: the {}'s b/a (0 < b/a < 1)", kind.name()),
                    )
                })?;
                if !(hole.is_finite() && hole > 0.0 && hole < 1.0) {
                    return Err(Error::invalid(
                        "eps",
                        format!(
                            "b/a must satisfy 0 < b/a < 1; got {}",
                            crate::error::show(hole)
                        ),
                    ));
                }
                Ok(Face::Annulus { hole })
            }
            Contact::RimAndFreeInner => {
                let s = d0_over_h.ok_or_else(|| {
                    Error::invalid(
                        "d0h",
                        format!(
                            "is needed: d0/h of the {} punch (its recess's depth h in units \
                             of d0 = sqrt(2 pi a dw / E*))",
                            kind.name()
                        ),
                    )
                })?;
                let (lo, hi) = D0H_RANGE;
                if !(s.is_finite() && (lo..=hi).contains(&s)) {
                    return Err(Error::invalid(
                        "d0h",
                        format!(
                            "must lie in [{lo:e}, {hi:e}]; got {}",
                            crate::error::show(s)
                        ),
                    ));
                }
                Ok(Face::Recess { d0_over_h: s })
            }
            Contact::FreeBand => Err(Error::Unsupported {
                method: METHOD.into(),
                reason: format!(
                    "the Dugdale law is solved so far for faces with a rim (the {} punches); \
                     the {} punch's band with two free edges is not yet",
                    [
                        Contact::Disk,
                        Contact::FixedAnnulus,
                        Contact::RimAndFreeInner
                    ]
                    .map(|c| PunchName::names(Some(c), ", "))
                    .join(", "),
                    kind.name()
                ),
            }),
        }
    }

    /// Run `work` on the face's family of equilibria at `nodes` unknowns.
    fn with_family<T>(
        self,
        solver: &DugdaleSolver,
        kind: &PunchKind,
        nodes: usize,
        law: DugdaleLaw,
        work: &mut dyn FnMut(&dyn path::Family) -> Result<T>,
    ) -> Result<T> {
        match self {
            Face::Disk => {
                let system = solver.disk(nodes);
                work(&flat_disk::FlatDisk::new(&solver.ring, &system, law))
            }
            Face::Annulus { hole } => {
                work(&annulus::AnnularFace::new(&solver.ring, nodes, law, hole))
            }
            Face::Recess { d0_over_h } => {
                let profile = |r: f64| kind.gap_shape(r);
                let face = annulus::AnnularFace::recessed(
                    &solver.ring,
                    nodes,
                    law,
                    1.0 / d0_over_h,
                    &profile,
                    kind.profile().may_meet_hole_floor(),
                );
                let suspended = suspended::SuspendedStates::new(law, 1.0 / d0_over_h, &profile);
                work(&recess::RecessedFace::new(face, suspended))
            }
        }
    }

    /// The edge that lets go at `pulloff`: those whose gap has reached `δc` (to 1e-6), else the
    /// one nearest to it.
    fn detaching_edge(self, pulloff: &PathPoint) -> DetachingEdge {
        let [inner, outer] = pulloff.edge_gaps;
        match self {
            Face::Disk => DetachingEdge::Outer,
            // The inner edge's zone always ends in the recess; the rim lets go when its gap
            // reaches `δc` (the JKR limit's rim failure), else the inner edge governs.
            Face::Recess { .. } if outer >= 1.0 - 1e-6 => DetachingEdge::Outer,
            Face::Recess { .. } => DetachingEdge::Inner,
            Face::Annulus { .. } => {
                let reached = |gap: f64| gap >= 1.0 - 1e-6;
                match (reached(inner), reached(outer)) {
                    (true, true) => DetachingEdge::Both,
                    (true, false) => DetachingEdge::Inner,
                    (false, true) => DetachingEdge::Outer,
                    (false, false) if inner > outer => DetachingEdge::Inner,
                    (false, false) => DetachingEdge::Outer,
                }
            }
        }
    }
}
