//! The conical concave punch, gap `h (1 - r/a)`: the power law with `n = 1`.

use super::{Contact, Profile, PunchName};

/// Conical concave punch: its apex (a kink) keeps a hole open at every depth.
#[derive(Clone, Copy, Debug, Default)]
pub struct Cone;

impl Profile for Cone {
    fn name(&self) -> &str {
        "cone"
    }
    fn builtin(&self) -> Option<PunchName> {
        Some(PunchName::Cone)
    }
    fn contact(&self) -> Contact {
        Contact::RimAndFreeInner
    }
    fn gap(&self, rho: f64) -> f64 {
        1.0 - rho
    }
    fn slope(&self, _rho: f64) -> f64 {
        -1.0
    }
    fn power_law_exponent(&self) -> Option<f64> {
        Some(1.0)
    }
    fn smooth_at_axis(&self) -> bool {
        false
    }
    fn may_meet_hole_floor(&self) -> bool {
        false
    }
}
