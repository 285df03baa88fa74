//! The studies the report runs: methods against references ([`comparison`]), mesh and grid
//! convergence ([`convergence`]), speed against accuracy ([`speed_accuracy`]), stability where
//! methods fail ([`stability`]) and parameter sweeps ([`sweeps`]).

pub mod claims;
pub mod comparison;
pub mod convergence;
pub mod dugdale_sweep;
pub mod figures;
pub mod speed_accuracy;
pub mod stability;
pub mod sweeps;

use ringcontact::error::Result;
use ringcontact::punch::PunchKind;
use ringcontact::scene::{Scene, SceneSpec};

/// The punch `kind` on the unit scene (`a = h = E* = 1`): a free band's tube radius `a/2` (its
/// `h = a²/(2ρ) = a`), a fixed annulus's hole `b/a = eps`; the load still to be given.
pub(crate) fn unit_spec(kind: PunchKind, eps: f64) -> SceneSpec {
    let spec = SceneSpec::default().shape(kind.clone());
    if kind.is_free_band() {
        spec.tube_radius(0.5)
    } else if kind.has_fixed_hole() {
        spec.inner_ratio(eps)
    } else {
        spec
    }
}

/// A state of the unit scene (`a = h = E* = 1`): a flat-faced punch (its depth is the unit of
/// its answer `γ`), or a concave punch at the depth `d/h`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum UnitLoad {
    /// A flat-faced punch: `γ = F/(2 E* d a)` whatever the depth.
    Flat,
    /// A concave punch pressed to `d/h`.
    Depth(f64),
}

impl UnitLoad {
    /// A concave punch at `depth`, or a flat-faced one (`None`).
    pub(crate) fn of_depth(depth: Option<f64>) -> Self {
        depth.map_or(UnitLoad::Flat, UnitLoad::Depth)
    }
}

/// The unit scene of punch `kind`, `b/a = eps` (fixed annulus) under `load`, with the tolerance
/// if given, for a solve through [`ringcontact::methods`].
pub(crate) fn unit_scene(
    kind: PunchKind,
    eps: f64,
    load: UnitLoad,
    tolerance: Option<f64>,
) -> Result<Scene> {
    let spec = unit_spec(kind, eps);
    let spec = match load {
        UnitLoad::Flat => spec,
        UnitLoad::Depth(depth) => spec.depth(depth),
    };
    match tolerance {
        Some(t) => spec.tolerance(t).validate(),
        None => spec.validate(),
    }
}
