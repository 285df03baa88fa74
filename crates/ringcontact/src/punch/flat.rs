//! The flat circular punch (Boussinesq): contact is the whole face `r <= a`, gap 0.

use super::{Contact, Profile, PunchName};

/// Flat circular punch: `F = 2 E* d a`, the pressure `E* d / (π sqrt(a² - r²))`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Flat;

impl Profile for Flat {
    fn name(&self) -> &str {
        "flat"
    }
    fn builtin(&self) -> Option<PunchName> {
        Some(PunchName::Flat)
    }
    fn contact(&self) -> Contact {
        Contact::Disk
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
    description: "Flat circular punch (Boussinesq): contact is the full disk",
    flags: "--punch flat",
    gap: "0",
    edges: "rim at a (disk)",
    closed_forms: "Boussinesq F = 2 E* a d",
};
