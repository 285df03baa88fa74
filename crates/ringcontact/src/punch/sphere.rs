//! The spherical (parabolic) concave punch, gap `h (1 - r²/a²)`: the power law with `n = 2`.

use super::{Contact, Profile, PunchName};

/// Spherical concave punch: its hole closes at `d = 3h`, `F = 2 E* h a · 8/3` (the MDR).
#[derive(Clone, Copy, Debug, Default)]
pub struct Sphere;

impl Profile for Sphere {
    fn name(&self) -> &str {
        "sphere"
    }
    fn builtin(&self) -> Option<PunchName> {
        Some(PunchName::Sphere)
    }
    fn contact(&self) -> Contact {
        Contact::RimAndFreeInner
    }
    fn gap(&self, rho: f64) -> f64 {
        1.0 - rho * rho
    }
    fn slope(&self, rho: f64) -> f64 {
        -2.0 * rho
    }
    fn power_law_exponent(&self) -> Option<f64> {
        Some(2.0)
    }
    fn closure(&self) -> Option<(f64, f64)> {
        Some((3.0, 8.0 / 3.0))
    }
    fn smooth_at_axis(&self) -> bool {
        true
    }
    fn may_meet_hole_floor(&self) -> bool {
        false
    }
}

/// What `verify references` says of this punch.
pub(crate) const SUMMARY: super::profile::Summary = super::profile::Summary {
    description: "Spherical (parabolic) concave punch, gap `h (1 - r²/a²)`",
    flags: "--punch sphere",
    gap: "h (1 - r²/a²)",
    edges: "rim at a, free inner edge",
    closed_forms: "full contact d >= 3h: F = 2 E* a (d - h/3)",
};
