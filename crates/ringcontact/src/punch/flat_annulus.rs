//! The flat annular punch: contact is the fixed annulus `b <= r <= a`, gap 0 on it (the inner
//! radius `b` is the punch's parameter, [`super::Punch::inner_radius`]).

use super::{Contact, Profile, PunchName};

/// Flat annular punch: `F = 2 E* d a γ(b/a)`, both edges sharp.
#[derive(Clone, Copy, Debug, Default)]
pub struct FlatAnnulus;

impl Profile for FlatAnnulus {
    fn name(&self) -> &str {
        "flat-annulus"
    }
    fn builtin(&self) -> Option<PunchName> {
        Some(PunchName::FlatAnnulus)
    }
    fn contact(&self) -> Contact {
        Contact::FixedAnnulus
    }
    fn gap(&self, _rho: f64) -> f64 {
        0.0
    }
    fn slope(&self, _rho: f64) -> f64 {
        0.0
    }
    fn smooth_at_axis(&self) -> bool {
        false
    }
    fn may_meet_hole_floor(&self) -> bool {
        false
    }
}

/// What `verify references` says of this punch.
pub(crate) const SUMMARY: super::profile::Summary = super::profile::Summary {
    description: "Flat annular punch: contact is the fixed annulus `b <= r <= a` (give `--eps \
                  b/a`)",
    flags: "--punch flat-annulus --eps B",
    gap: "0 on [b, a], hole inside",
    edges: "rims at b and a",
    closed_forms: "Collins series, narrow-ring asymptote",
};
