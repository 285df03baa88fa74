//! The concave gap `g(r) = h (1 - (r/a)^n)` in full contact, in closed form by the
//! method of dimensionality reduction (MDR; Popov & Heß, *Method of Dimensionality Reduction in
//! Contact Mechanics and Friction*, 2015, ch. 3).
//!
//! In full contact the surface deflection on the disk `r <= a` is `w(r) = (d - h) + h (r/a)^n`.
//! The MDR's equivalent profile of `h (r/a)^n` is `-κ_n h (x/a)^n` with
//!
//! ```text
//! κ_n = n ∫_0^1 t^(n-1) / sqrt(1 - t²) dt = (n √π / 2) Γ(n/2) / Γ((n+1)/2)
//! ```
//!
//! (`κ_1 = π/2`, `κ_2 = 2`), which gives the force and the pressure at the axis:
//!
//! ```text
//! F = 2 E* a [ (d - h) + κ_n h / (n + 1) ],         i.e. γ2 = γ1 - 1 + κ_n / (n + 1),
//! p(0) = (E* / (π a)) [ (d - h) + κ_n h - κ_n h n / (n - 1) ]     (n > 1).
//! ```
//!
//! Away from the axis the full-contact pressure is
//!
//! ```text
//! p(r) = (E* / (π a sqrt(1 - r²))) [ (d - h) + κ_n h - κ_n h n sqrt(1 - r²) I_n(r) ],
//! I_n(r) = ∫_r^1 x^(n-1) / sqrt(x² - r²) dx = ∫_0^sqrt(1-r²) (r² + u²)^((n-2)/2) du,
//! ```
//!
//! so the contact is full (`p >= 0` everywhere) from the depth
//! `d_c = h [1 + κ_n max_r (n sqrt(1 - r²) I_n(r) - 1)]` on. For `1 < n <= 2` the maximum is at
//! the axis, `d_c = h (1 + κ_n / (n - 1))` (`d_c = 3 h` for the parabolic gap,
//! `docs/conventions.md` fact 4). For `n > 2` it moves off the axis (`r = 0.5 a` for `n = 4`, where
//! `d_c = 7h/3`): the pressure first fails on a ring, the contact closes from a disk and an
//! annulus, not by a shrinking hole. For `n <= 1` the integral for `p(0)` diverges to tension: the
//! hole never closes.

use std::collections::HashMap;
use std::f64::consts::PI;
use std::sync::{Mutex, OnceLock};

use crate::numerics::tanh_sinh::TanhSinhRule;

/// `ln Γ(x)` for `x > 0` (Lanczos, `g = 7`, nine coefficients; relative error about 1e-15).
fn ln_gamma(x: f64) -> f64 {
    const G: f64 = 7.0;
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        // Reflection: Γ(x) Γ(1 - x) = π / sin(πx).
        return (PI / (PI * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let t = x + G + 0.5;
    let series = C
        .iter()
        .enumerate()
        .skip(1)
        .fold(C[0], |acc, (i, c)| acc + c / (x + i as f64));
    0.5 * (2.0 * PI).ln() + (x + 0.5) * t.ln() - t + series.ln()
}

/// The MDR factor `κ_n = (n √π / 2) Γ(n/2) / Γ((n+1)/2)` of the profile `(r/a)^n`.
pub fn kappa(n: f64) -> f64 {
    0.5 * n * PI.sqrt() * (ln_gamma(0.5 * n) - ln_gamma(0.5 * (n + 1.0))).exp()
}

/// `n sqrt(1 - r²) I_n(r) - 1`: the depth `(d - h)/(κ_n h)` at which the full-contact pressure
/// at `r` is zero (`r > 0`; tanh-sinh quadrature of `I_n`, which handles the endpoint
/// singularity of `u^(n-2)` as `r -> 0`).
fn zero_pressure_depth(n: f64, r: f64, rule: &TanhSinhRule) -> f64 {
    let top = (1.0 - r * r).sqrt();
    let integral: f64 = rule
        .panel(0.0, top)
        .map(|node| node.weight * (r * r + node.position * node.position).powf(0.5 * (n - 2.0)))
        .sum();
    n * top * integral - 1.0
}

/// Depth `d_c / h` from which the gap `1 - ρ^n` is in full contact (the full-contact
/// pressure nonnegative everywhere): `1 + κ_n / (n - 1)` for `1 < n <= 2`, and for `n > 2`
/// `1 + κ_n max_r (n sqrt(1 - r²) I_n(r) - 1)`, the maximum found by a scan of 256 radii and a
/// golden-section refinement (to 1e-10 in `r`, so to about 1e-15 in the value at a smooth
/// maximum). `None` for `n <= 1` (the hole never closes).
pub fn closure_depth(n: f64) -> Option<f64> {
    if n <= 1.0 {
        return None;
    }
    // The scan costs about 1 ms for n > 2, and every state of the punch asks for it: computed
    // once per exponent and process.
    static KNOWN: OnceLock<Mutex<HashMap<u64, Option<f64>>>> = OnceLock::new();
    let known = KNOWN.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(&depth) = known
        .lock()
        .ok()
        .and_then(|m| m.get(&n.to_bits()).copied())
        .as_ref()
    {
        return depth;
    }
    let depth = closure_depth_uncached(n);
    if let Ok(mut m) = known.lock() {
        m.insert(n.to_bits(), depth);
    }
    depth
}

fn closure_depth_uncached(n: f64) -> Option<f64> {
    let kappa = kappa(n);
    if n <= 2.0 {
        return Some(1.0 + kappa / (n - 1.0));
    }
    let rule = TanhSinhRule::new(1.0 / 32.0);
    let f = |r: f64| zero_pressure_depth(n, r, &rule);
    const SCAN: usize = 256;
    let at = |i: usize| i as f64 / SCAN as f64;
    let best = (1..SCAN)
        .max_by(|&i, &j| f(at(i)).total_cmp(&f(at(j))))
        .unwrap_or(1);
    let top = crate::numerics::golden::golden_section_max(f, at(best - 1), at(best + 1), 1e-10);
    let interior = f(top);
    Some(1.0 + kappa * interior.max(1.0 / (n - 1.0)))
}

/// `γ2 = F / (2 E* h a) = γ1 - 1 + κ_n / (n + 1)` in full contact, `γ1 = d/h >= d_c/h`;
/// `None` below the closure depth (the contact is an annulus there) or for `n <= 1`.
pub fn full_contact_gamma2(n: f64, depth_over_hole: f64) -> Option<f64> {
    let closure = closure_depth(n)?;
    (depth_over_hole >= closure).then(|| depth_over_hole - 1.0 + kappa(n) / (n + 1.0))
}

/// `γ1 = d/h` in full contact at `γ2 = F/(2 E* h a)` (the inverse of
/// [`full_contact_gamma2`]); `None` below the closing force.
pub fn full_contact_gamma1(n: f64, gamma2: f64) -> Option<f64> {
    let closure = closure_depth(n)?;
    let depth = gamma2 + 1.0 - kappa(n) / (n + 1.0);
    (depth >= closure).then_some(depth)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Known values of Γ: Γ(1/2) = √π, Γ(5) = 24, Γ(1/3) = 2.678938534707747633 (DLMF 5.4.i).
    #[test]
    fn ln_gamma_matches_known_values() {
        let cases = [
            (0.5, PI.sqrt()),
            (5.0, 24.0),
            (1.0 / 3.0, 2.678_938_534_707_747_6),
        ];
        for (x, gamma) in cases {
            let err = (ln_gamma(x).exp() - gamma).abs() / gamma;
            assert!(err < 2e-15, "Γ({x}): {err:e}");
        }
    }

    /// `κ_1 = π/2` (the linear gap's MDR factor) and `κ_2 = 2` (the paraboloid's), and for integer
    /// `n` the Wallis recursion `κ_{n+2} = κ_n (n + 2) / (n + 1)`.
    #[test]
    fn kappa_matches_the_cone_the_sphere_and_wallis() {
        assert!((kappa(1.0) - PI / 2.0).abs() < 1e-14);
        assert!((kappa(2.0) - 2.0).abs() < 1e-14);
        for n in 1..8 {
            let n = n as f64;
            let wallis = kappa(n) * (n + 2.0) / (n + 1.0);
            assert!((kappa(n + 2.0) - wallis).abs() < 1e-14 * wallis);
        }
    }

    /// For `n > 2` the full-contact pressure first vanishes off the axis. For `n = 4` by hand:
    /// `I_4(r) = r² T + T³/3` with `T = sqrt(1 - r²)`, so `4 T I_4 = (4/3)(1 + t - 2t²)` with
    /// `t = r²`, largest at `t = 1/4` (`r = a/2`) where it is `3/2`; with `κ_4 = 8/3` this gives
    /// `d_c = h (1 + (8/3)(1/2)) = 7h/3`, against `1 + κ_4/3 = 17h/9` from the axis alone.
    #[test]
    fn the_closure_of_n_4_is_off_the_axis() {
        assert!((kappa(4.0) - 8.0 / 3.0).abs() < 1e-14);
        let got = closure_depth(4.0).unwrap();
        assert!(
            (got - 7.0 / 3.0).abs() < 1e-12,
            "d_c/h = {got}, expected 7/3"
        );
    }

    /// The parabolic gap closes at `d = 3h` with `F = 2 E* a (d - h/3)` (docs/conventions.md fact
    /// 4).
    #[test]
    fn the_sphere_is_the_power_law_with_n_2() {
        assert!((closure_depth(2.0).unwrap() - 3.0).abs() < 1e-14);
        assert!((full_contact_gamma2(2.0, 4.0).unwrap() - (4.0 - 1.0 / 3.0)).abs() < 1e-14);
        assert!(closure_depth(1.0).is_none());
        assert!(full_contact_gamma2(2.0, 2.9).is_none());
    }
}
