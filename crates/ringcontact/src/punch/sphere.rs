//! The spherical (parabolic) concave punch, gap `h (1 - r²/a²)`: `h (1 - (r/a)^n)` with `n = 2`.

use super::{Contact, Profile, PunchName, Quantity, Reference, ReferenceKind, ReferenceValue};

/// `γ1 = d/h` of this punch.
pub const GAMMA1: Quantity = Quantity::new("sphere_gamma1", "gamma1 (sphere)", 1);
/// `γ2 = F/(2 E* h a)` of this punch.
pub const GAMMA2: Quantity = Quantity::new("sphere_gamma2", "gamma2 (sphere)", 2);

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
    fn references(&self) -> Vec<Reference> {
        let onset = "Barber (1976) / MDR: full contact at d = 3h, F = 16/3 E* h a";
        let fit = "paper eq. (10)-(11)";
        let whole = (0.0, 1.0 - 1e-12);
        vec![
            Reference {
                name: "sphere-full-contact",
                source: onset,
                quantity: GAMMA1,
                eps_range: (0.0, 0.0),
                kind: ReferenceKind::Exact,
                eval: |_| ReferenceValue::exact(3.0),
            },
            Reference {
                name: "sphere-full-contact",
                source: onset,
                quantity: GAMMA2,
                eps_range: (0.0, 0.0),
                kind: ReferenceKind::Exact,
                eval: |_| ReferenceValue::exact(8.0 / 3.0),
            },
            Reference {
                name: "paper-fit",
                source: fit,
                quantity: GAMMA1,
                eps_range: whole,
                kind: ReferenceKind::Fit,
                eval: |e| ReferenceValue::unbounded(paper_fit(1, e)),
            },
            Reference {
                name: "paper-fit",
                source: fit,
                quantity: GAMMA2,
                eps_range: whole,
                kind: ReferenceKind::Fit,
                eval: |e| ReferenceValue::unbounded(paper_fit(2, e)),
            },
        ]
    }
}

/// The paper's fit, eq. (10)-(11): `γ_i ≈ a_i (1 - eps^m_i)^n_i`.
pub fn paper_fit(i: usize, eps: f64) -> f64 {
    let (a, m, n) = if i == 1 {
        (3.0, 2.034, 0.91)
    } else {
        (8.0 / 3.0, 2.015, 1.03)
    };
    a * (1.0 - eps.powf(m)).powf(n)
}

/// What `verify references` says of this punch.
pub(crate) const SUMMARY: super::profile::Summary = super::profile::Summary {
    description: "Spherical (parabolic) concave punch, gap `h (1 - r²/a²)`",
    flags: "--punch sphere",
    gap: "h (1 - r²/a²)",
    edges: "rim at a, free inner edge",
    closed_forms: "full contact d >= 3h: F = 2 E* a (d - h/3)",
};
