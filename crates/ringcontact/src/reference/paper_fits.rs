//! The paper's fitted approximations (eqs. 3-4, 8-9, 10-11), reproduced as published.
//!
//! They are things to test, not to trust: no error bound is declared. Their declared range is the
//! open interval the paper plotted, `0 < eps < 1` (the cone's forms diverge at `eps = 0`).

use super::{Quantity, Reference, ReferenceKind, ReferenceValue};

/// Flat annulus, eq. (3)-(4): `γ ≈ (1 - eps^m)^n`, `m = 2.915`, `n = 0.147`.
pub fn flat_gamma(eps: f64) -> f64 {
    (1.0 - eps.powf(2.915)).powf(0.147)
}

/// Conical concave punch, eq. (8)-(9): `γ_i ≈ (-ln eps)^n_i (a_i + b_i eps + c_i eps²)`.
pub fn cone_gamma(i: usize, eps: f64) -> f64 {
    let (n, a, b, c) = if i == 1 {
        (0.874, 2.09, 0.54, 0.15)
    } else {
        (0.945, 1.85, 0.45, 0.12)
    };
    (-eps.ln()).powf(n) * (a + b * eps + c * eps * eps)
}

/// Spherical concave punch, eq. (10)-(11): `γ_i ≈ a_i (1 - eps^m_i)^n_i`.
pub fn sphere_gamma(i: usize, eps: f64) -> f64 {
    let (a, m, n) = if i == 1 {
        (3.0, 2.034, 0.91)
    } else {
        (8.0 / 3.0, 2.015, 1.03)
    };
    a * (1.0 - eps.powf(m)).powf(n)
}

fn unbounded(value: f64) -> ReferenceValue {
    ReferenceValue {
        value,
        error_bound: None,
    }
}

pub(super) fn references() -> Vec<Reference> {
    let open = (1e-12, 1.0 - 1e-12);
    vec![
        Reference {
            name: "paper-fit",
            source: "paper eq. (3)-(4)",
            quantity: Quantity::FlatGamma,
            eps_range: (0.0, 1.0 - 1e-12),
            kind: ReferenceKind::Fit,
            eval: |e| unbounded(flat_gamma(e)),
        },
        Reference {
            name: "paper-fit",
            source: "paper eq. (8)-(9)",
            quantity: Quantity::ConeGamma1,
            eps_range: open,
            kind: ReferenceKind::Fit,
            eval: |e| unbounded(cone_gamma(1, e)),
        },
        Reference {
            name: "paper-fit",
            source: "paper eq. (8)-(9)",
            quantity: Quantity::ConeGamma2,
            eps_range: open,
            kind: ReferenceKind::Fit,
            eval: |e| unbounded(cone_gamma(2, e)),
        },
        Reference {
            name: "paper-fit",
            source: "paper eq. (10)-(11)",
            quantity: Quantity::SphereGamma1,
            eps_range: (0.0, 1.0 - 1e-12),
            kind: ReferenceKind::Fit,
            eval: |e| unbounded(sphere_gamma(1, e)),
        },
        Reference {
            name: "paper-fit",
            source: "paper eq. (10)-(11)",
            quantity: Quantity::SphereGamma2,
            eps_range: (0.0, 1.0 - 1e-12),
            kind: ReferenceKind::Fit,
            eval: |e| unbounded(sphere_gamma(2, e)),
        },
    ]
}
