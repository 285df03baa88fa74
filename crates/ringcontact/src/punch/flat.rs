//! The flat circular punch (Boussinesq): contact is the whole face `r <= a`, gap 0.

use super::{Contact, Profile, PunchName, Quantity, Reference, ReferenceKind, ReferenceValue};

/// `γ(eps) = F/(2 E* d a)` of the flat punches (`eps = b/a`, 0 for the disk).
pub const GAMMA: Quantity = Quantity::new("flat_gamma", "gamma (flat punches)", 0);

/// Boussinesq's flat circular punch: `F = 2 E* a d`, so `γ(0) = 1` exactly.
pub fn boussinesq() -> Reference {
    Reference {
        name: "boussinesq",
        source: "Boussinesq flat circular punch, F = 2 E* a d",
        quantity: GAMMA,
        eps_range: (0.0, 0.0),
        kind: ReferenceKind::Exact,
        eval: |_| ReferenceValue::exact(1.0),
    }
}

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
    fn references(&self) -> Vec<Reference> {
        vec![boussinesq()]
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
