//! Boussinesq's punch (a flat face of radius `a`, [`crate::punch::Contact::Disk`]): its
//! Maugis-Dugdale pull-off in closed form: an independent reference for the
//! ring-BEM solution of [`crate::dugdale`].
//!
//! **Derivation** (Sneddon's representation of the axisymmetric half-space, the route of Maugis,
//! *J. Colloid Interface Sci.* 150, 1992, for a paraboloid). With `E* = 1`, a surface traction
//! written through `g(t)` gives the deflection `w(r) = (2/π) ∫_0^r g(t) / sqrt(r² - t²) dt` and
//! the force `F = 2 ∫_0^∞ g(t) dt`. The flat face of radius `a = 1` at depth `d` is in contact
//! on `r < c`, where `g = d`; a Dugdale zone `c < r < m` carries the tension `σ0`, where
//! `g(t) = -2 σ0 sqrt(m² - t²)`; the stress is bounded at `c` (no crack tip: `g` continuous), so
//! `d = -2 σ0 sqrt(m² - c²)`. The gap at the zone's end, `w(m) - d`, is then
//! `(4 σ0 / π) [sqrt(m² - c²) arccos(c/m) - (m - c)]`, and
//! `F = -2 σ0 [c sqrt(m² - c²) + m² arccos(c/m)]`.
//!
//! While the zone reaches the rim (`m = 1`) the tension grows as `c` falls; it stops where the
//! gap at the rim reaches `δc = Δw/σ0`, i.e. at `q(c) = sqrt(1 - c²) arccos c + c - 1 = 1/λ²`
//! (with `λ = 2 σ0 sqrt(a/(π E* Δw))`). Beyond, the zone ends inside the face, `m < 1`, and the
//! tension falls (`|F| ∝ (c s + arccos c)/q(c)²` in `c/m`), so the pull-off, under either control,
//! is that state:
//! `F_c = -2 σ0 a² [c sqrt(1 - c²) + arccos c]`, `d_c = -2 σ0 a sqrt(1 - c²) / E*`.
//! Since `q` falls from `π/2 - 1` at `c = 0` to 0 at `c = 1`, below `λ* = (π/2 - 1)^{-1/2}` the
//! rim's gap never reaches `δc` while in contact: the face lets go whole, at `F_c = -π a² σ0`.
//! As `λ -> ∞`, `1 - c ≈ 1/λ²` and `F_c -> -sqrt(8π E* Δw a³)`: Kendall's force.

use std::f64::consts::PI;

/// Tabor parameter `λ* = (π/2 - 1)^{-1/2}` below which the flat face's pull-off is
/// `π a² σ0`.
pub fn whole_face_limit() -> f64 {
    1.0 / (PI / 2.0 - 1.0).sqrt()
}

/// The flat face's pull-off in closed form.
#[derive(Clone, Copy, Debug)]
pub struct FlatPulloff {
    /// `F_c/F0`, Kendall's `F0 = sqrt(8π E* Δw a³)` (negative: tensile); either control.
    pub force: f64,
    /// `d_c/d0` under fixed load, `d0 = sqrt(2π a Δw / E*)`: where the tension first peaks.
    pub load_depth: f64,
    /// `d_c/d0` under fixed grips: the most negative depth held, which below
    /// [`whole_face_limit`] is where the rim's gap reaches `δc`, `d = -δc - 4 σ0 a/(π E*)`.
    pub grips_depth: f64,
    /// Contact radius `c/a` at the pull-off (0 below [`whole_face_limit`]).
    pub contact: f64,
}

/// The flat face's pull-off at Tabor parameter `tabor`; `None` for a Tabor parameter that is
/// not finite and positive.
pub fn pulloff(tabor: f64) -> Option<FlatPulloff> {
    if !(tabor.is_finite() && tabor > 0.0) {
        return None;
    }
    // σ0 in units of E* with a = 1 and Δw = 1/(2π) (d0 = 1, F0 = 2).
    let sigma0 = tabor / (2.0 * 2f64.sqrt());
    let target = 1.0 / (tabor * tabor);
    let q = |c: f64| (1.0 - c * c).sqrt() * c.acos() + c - 1.0;
    if target >= q(0.0) {
        let range = 1.0 / (2.0 * PI * sigma0);
        return Some(FlatPulloff {
            force: -PI * sigma0 / 2.0,
            load_depth: -2.0 * sigma0,
            grips_depth: -range - 4.0 * sigma0 / PI,
            contact: 0.0,
        });
    }
    // q falls monotonically on [0, 1] (q' = -c arccos c / sqrt(1 - c²)): bisection to rounding.
    let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if q(mid) > target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let c = 0.5 * (lo + hi);
    let s = (1.0 - c * c).sqrt();
    let force = -2.0 * sigma0 * (c * s + c.acos());
    Some(FlatPulloff {
        force: force / 2.0,
        load_depth: -2.0 * sigma0 * s,
        grips_depth: -2.0 * sigma0 * s,
        contact: c,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_limits_are_the_uniform_stress_and_kendall() {
        // Small λ: π a² σ0 = (π/(4 sqrt 2)) λ F0.
        let small = pulloff(0.5).unwrap();
        assert_eq!(small.contact, 0.0);
        assert!((small.force + PI * 0.5 / (4.0 * 2f64.sqrt())).abs() < 1e-15);
        // Large λ: Kendall's -F0, approached as the zone (length a/λ²) shrinks.
        let large = pulloff(1e4).unwrap();
        assert!((large.force + 1.0).abs() < 1e-3, "{large:?}");
        assert!((large.load_depth + 1.0).abs() < 1e-3, "{large:?}");
        // Continuous at λ*.
        let lambda = whole_face_limit();
        let below = pulloff(lambda * (1.0 - 1e-9)).unwrap();
        let above = pulloff(lambda * (1.0 + 1e-9)).unwrap();
        assert!((below.force - above.force).abs() < 1e-6);
        assert!((below.grips_depth - above.grips_depth).abs() < 1e-6);
    }
}
