//! Exact results, series and asymptotes for the flat annulus and the concave punches.

use std::f64::consts::PI;

use super::{Quantity, Reference, ReferenceKind, ReferenceValue};

/// Boussinesq's flat circular punch: `F = 2 E* a d`, so `γ(0) = 1` exactly.
fn boussinesq(_eps: f64) -> ReferenceValue {
    ReferenceValue {
        value: 1.0,
        error_bound: Some(0.0),
    }
}

/// Collins' small-`eps` series (paper eq. 21):
/// `γ = 1 - 4 eps³/(3π²) - 8 eps⁵/(15π²) - 16 eps⁶/(27π⁴) + O(eps⁷)`.
///
/// The error bound `eps⁷` is a conservative stand-in for the unknown `O(eps⁷)` coefficient: the
/// known coefficients shrink (0.135, 0.054, 0.0061), and at `eps = 0.3` the bound is 2.2e-4,
/// consistent with docs/conventions.md's "about 1e-5" there within a factor of 20.
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
/// Leading order only: the neglected terms are `O(δ² ln(16/δ))` relative to the leading term
/// (the next order of the thin-ring expansion). The bound `δ² ln(16/δ) γ` takes the unknown
/// coefficient as 1; the tests check that the difference to converged solutions shrinks at
/// this rate as `eps -> 1`.
pub fn narrow_ring(eps: f64) -> ReferenceValue {
    let delta = (1.0 - eps) / (1.0 + eps);
    let log = (16.0 / delta).ln();
    let value = PI * PI * (1.0 + eps) / (4.0 * log);
    ReferenceValue {
        value,
        error_bound: Some(delta * delta * log * value),
    }
}

/// Spherical concave punch at the onset of full contact: `d = 3h`, `F = 16/3 E* h a`.
fn sphere_onset_gamma1(_eps: f64) -> ReferenceValue {
    ReferenceValue {
        value: 3.0,
        error_bound: Some(0.0),
    }
}

fn sphere_onset_gamma2(_eps: f64) -> ReferenceValue {
    ReferenceValue {
        value: 8.0 / 3.0,
        error_bound: Some(0.0),
    }
}

pub(super) fn references() -> Vec<Reference> {
    vec![
        Reference {
            name: "boussinesq",
            source: "Boussinesq flat circular punch, F = 2 E* a d",
            quantity: Quantity::FlatGamma,
            eps_range: (0.0, 0.0),
            kind: ReferenceKind::Exact,
            eval: boussinesq,
        },
        Reference {
            name: "collins-series",
            source: "Collins (1963) small-eps series, paper eq. (21)",
            quantity: Quantity::FlatGamma,
            eps_range: (0.0, 0.3),
            kind: ReferenceKind::Series,
            eval: collins_series,
        },
        Reference {
            name: "narrow-ring",
            source: "Argatov et al. narrow-ring asymptote, paper eq. (22)",
            quantity: Quantity::FlatGamma,
            eps_range: (0.9, 1.0 - 1e-12),
            kind: ReferenceKind::Asymptote,
            eval: narrow_ring,
        },
        Reference {
            name: "sphere-full-contact",
            source: "Barber (1976) / MDR: full contact at d = 3h, F = 16/3 E* h a",
            quantity: Quantity::SphereGamma1,
            eps_range: (0.0, 0.0),
            kind: ReferenceKind::Exact,
            eval: sphere_onset_gamma1,
        },
        Reference {
            name: "sphere-full-contact",
            source: "Barber (1976) / MDR: full contact at d = 3h, F = 16/3 E* h a",
            quantity: Quantity::SphereGamma2,
            eps_range: (0.0, 0.0),
            kind: ReferenceKind::Exact,
            eval: sphere_onset_gamma2,
        },
    ]
}
