//! The studies the report runs: methods against references ([`comparison`]), mesh and grid
//! convergence ([`convergence`]), speed against accuracy ([`speed_accuracy`]), stability where
//! methods fail ([`stability`]) and parameter sweeps ([`sweeps`]).

pub mod claims;
pub mod comparison;
pub mod convergence;
pub mod figures;
pub mod speed_accuracy;
pub mod stability;
pub mod sweeps;

use ringcontact::error::Result;
use ringcontact::fem::FemLoad;
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

/// The scene a FEM load describes, for a solve through [`ringcontact::methods::Method`]: punch
/// `kind`, `b/a = eps` (fixed annulus), depth `d/h` or force `F/(2 E* h a)` of a concave punch,
/// on the unit scene (`a = h = E* = 1`), with the tolerance if given.
pub(crate) fn scene_of_fem_load(
    kind: PunchKind,
    eps: f64,
    load: FemLoad,
    tolerance: Option<f64>,
) -> Result<Scene> {
    let spec = unit_spec(kind, eps);
    let spec = match load {
        FemLoad::Flat => spec,
        FemLoad::ConcaveDepth(depth) => spec.depth(depth),
        FemLoad::ConcaveForce(force) => spec.force(2.0 * force),
    };
    match tolerance {
        Some(t) => spec.tolerance(t).validate(),
        None => spec.validate(),
    }
}
