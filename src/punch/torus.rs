//! The torus: a convex ring of radius `a` with parabolic section, gap `(r - a)²/(2ρ)`, written
//! `h (1 - r/a)²` with `h = a²/(2ρ)` (one dimensionless shape for every tube radius `ρ`, which
//! only sets the depth scale). Its contact band `[b(d), c(d)]` has two free edges and no rim.

use super::{Contact, Profile, PunchName};

/// Torus of parabolic section: gap `(1 - ρ)²` in units of `h`, defined on both sides of `a`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Torus;

impl Profile for Torus {
    fn name(&self) -> &str {
        "torus"
    }
    fn builtin(&self) -> Option<PunchName> {
        Some(PunchName::Torus)
    }
    fn contact(&self) -> Contact {
        Contact::FreeBand
    }
    fn gap(&self, rho: f64) -> f64 {
        (1.0 - rho) * (1.0 - rho)
    }
    fn slope(&self, rho: f64) -> f64 {
        -2.0 * (1.0 - rho)
    }
    fn smooth_at_axis(&self) -> bool {
        false
    }
    fn may_meet_hole_floor(&self) -> bool {
        false
    }
}
