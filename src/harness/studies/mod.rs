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

/// The scene a FEM load describes, for a solve through [`ringcontact::methods::Method`]: punch
/// `kind`, `b/a = eps` (flat annulus), depth `d/h` or force `F/(2 E* h a)` of a concave punch,
/// on the unit scene (`a = h = E* = 1`), with the tolerance if given.
pub(crate) fn scene_of_fem_load(
    kind: PunchKind,
    eps: f64,
    load: FemLoad,
    tolerance: Option<f64>,
) -> Result<Scene> {
    let spec = SceneSpec::default().shape(kind.clone());
    // A free band of the dimensionless problem: `h = a²/(2ρ) = a`.
    let spec = if kind.is_free_band() {
        spec.tube_radius(0.5)
    } else {
        spec
    };
    let spec = match load {
        FemLoad::Flat if kind.has_fixed_hole() => spec.inner_ratio(eps),
        FemLoad::Flat => spec,
        FemLoad::ConcaveDepth(depth) => spec.depth(depth),
        FemLoad::ConcaveForce(force) => spec.force(2.0 * force),
    };
    match tolerance {
        Some(t) => spec.tolerance(t).validate(),
        None => spec.validate(),
    }
}
