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
    /// The ring radius, where `ĝ = (1 - ρ)²` has the curvature 2.
    fn first_touch(&self) -> Option<(f64, f64)> {
        Some((1.0, 2.0))
    }
    /// `ĝ = (1 - ρ)² = d/h` at `ρ = 1 ± √(d/h)` (the inner one continued past the axis).
    fn rigid_half_widths(&self, depth: f64) -> (f64, f64) {
        (depth.sqrt(), depth.sqrt())
    }
    /// The larger of two approximants of the ring BEM's curves. Narrow: the ring as a
    /// plane-strain cylinder of half-width `w = 1 - eps` (`ρ = a/2` when `h = 1`),
    /// `γ2 ≈ π² w²/2` (Hertz, `P = π E* w²/(4ρ)` per unit length over the length `2πa`) and
    /// `γ1 ≈ w² (ln(16/w) - 1)` (the ring's logarithmic approach). Wide: powers of
    /// `L = ln(a/b)` through the ring BEM's curves (`γ1 = 15.6, 49.7, 163` and
    /// `γ2 = 41.9, 205, 1109` at `b = 0.1, 0.01, 1e-4 a`), `γ1 ≈ 3.8 L^1.7`, `γ2 ≈ 5.8 L^2.35`.
    fn approximate_gamma(&self, eps: f64, depth_controlled: bool) -> Option<f64> {
        let (w, log) = (1.0 - eps, (1.0 / eps).ln());
        Some(if depth_controlled {
            (w * w * ((16.0 / w).ln() - 1.0)).max(3.8 * log.powf(1.7))
        } else {
            (0.5 * std::f64::consts::PI.powi(2) * w * w).max(5.8 * log.powf(2.35))
        })
    }
}

/// What `verify references` says of this punch.
pub(crate) const SUMMARY: super::profile::Summary = super::profile::Summary {
    description: "Torus: a convex ring of radius `a` with parabolic section, gap `(r - a)²/(2ρ)`, \
                  both contact edges free (`verify solve` and `verify table` take `--tube-radius \
                  ρ`; the other commands work in units of `h = a²/(2ρ)` and need none)",
    flags: "--punch torus --tube-radius RHO",
    gap: "(r - a)²/(2 rho) = h (1 - r/a)², h = a²/(2 rho)",
    edges: "both free, b < a < c (never closes)",
    closed_forms: "narrow limit: plane-strain Hertz cylinder (asymptote, tested)",
};
