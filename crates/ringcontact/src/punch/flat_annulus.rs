//! The flat annular punch: contact is the fixed annulus `b <= r <= a`, gap 0 on it (the inner
//! radius `b` is the punch's parameter, [`super::Punch::inner_radius`]).

use std::f64::consts::PI;

use super::flat::{boussinesq, GAMMA};
use super::{Contact, Profile, PunchName, Reference, ReferenceKind, ReferenceValue};

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
    fn references(&self) -> Vec<Reference> {
        vec![
            boussinesq(),
            Reference {
                name: "collins-series",
                source: "Collins (1963) small-eps series, paper eq. (21)",
                quantity: GAMMA,
                eps_range: (0.0, 0.3),
                kind: ReferenceKind::Series,
                eval: collins_series,
            },
            Reference {
                name: "narrow-ring",
                source: "Argatov et al. narrow-ring asymptote, paper eq. (22)",
                quantity: GAMMA,
                eps_range: (0.9, 1.0 - 1e-12),
                kind: ReferenceKind::Asymptote,
                eval: narrow_ring,
            },
            Reference {
                name: "paper-fit",
                source: "paper eq. (3)-(4)",
                quantity: GAMMA,
                eps_range: (0.0, 1.0 - 1e-12),
                kind: ReferenceKind::Fit,
                eval: |e| ReferenceValue::unbounded(paper_fit(e)),
            },
        ]
    }
}

/// Collins' small-`eps` series (paper eq. 21):
/// `γ = 1 - 4 eps³/(3π²) - 8 eps⁵/(15π²) - 16 eps⁶/(27π⁴) + O(eps⁷)`.
///
/// The error bound `eps⁷` stands in for the unknown `O(eps⁷)` coefficient: the known
/// coefficients shrink (0.135, 0.054, 0.0061).
pub fn collins_series(eps: f64) -> ReferenceValue {
    let pi2 = PI * PI;
    let value = 1.0
        - 4.0 * eps.powi(3) / (3.0 * pi2)
        - 8.0 * eps.powi(5) / (15.0 * pi2)
        - 16.0 * eps.powi(6) / (27.0 * pi2 * pi2);
    ReferenceValue {
        value,
        error_bound: Some(eps.powi(7)),
    }
}

/// Narrow-ring asymptote, `δ = (1 - eps)/(1 + eps) -> 0`:
/// `γ ~ π² (1 + eps) / (4 ln(16/δ))` (Argatov et al., paper eq. 22 with `F = 2E* d a γ`).
///
/// Leading order only: the neglected terms are `O(δ² ln(16/δ))` relative to the leading term.
/// The bound `δ² ln(16/δ) γ` takes the unknown coefficient as 1; the tests check that the
/// difference to converged solutions shrinks at this rate as `eps -> 1`.
pub fn narrow_ring(eps: f64) -> ReferenceValue {
    let delta = (1.0 - eps) / (1.0 + eps);
    let log = (16.0 / delta).ln();
    let value = PI * PI * (1.0 + eps) / (4.0 * log);
    ReferenceValue {
        value,
        error_bound: Some(delta * delta * log * value),
    }
}

/// The paper's fit, eq. (3)-(4): `γ ≈ (1 - eps^m)^n`, `m = 2.915`, `n = 0.147`.
pub fn paper_fit(eps: f64) -> f64 {
    (1.0 - eps.powf(2.915)).powf(0.147)
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
