//! Full contact of any concave punch `g(r) = h ĝ(r/a)` (`ĝ(0) = 1`, `ĝ(1) = 0`) by the method of
//! dimensionality reduction (MDR; Popov & Heß 2015, ch. 3), by quadrature: the closed
//! forms of `1 - ρ^n` ([`super::power_law`]) for a profile given by points.
//!
//! In full contact the deflection on the disk is `w = d - h ĝ(r)`. Its MDR profile is
//! `q(x) = d - h G(x)` with
//!
//! ```text
//! G(x) = ĝ(0) + x ∫_0^x ĝ'(r) / sqrt(x² - r²) dr = 1 + x ∫_0^{π/2} ĝ'(x sin θ) dθ,
//! G'(x) = ∫_0^{π/2} [ĝ'(x sin θ) + x sin θ ĝ''(x sin θ)] dθ,
//! ```
//!
//! so that (units `E* = a = h = 1`)
//!
//! ```text
//! F/(2 E* h a) = d/h - c_F,             c_F = ∫_0^1 G(x) dx,
//! rim intensity   d/h + κ_h,             κ_h = -G(1),
//! π p(r)/E* = (d/h - G(1))/sqrt(1 - r²) + ∫_r^1 G'(x)/sqrt(x² - r²) dx.
//! ```
//!
//! The contact is full (`p >= 0` on the disk) from `d_c/h = max_r P(r)` on,
//! `P(r) = G(1) - sqrt(1 - r²) ∫_0^{sqrt(1 - r²)} G'(x)/x du` (`x = sqrt(r² + u²)`). A profile
//! with a slope at the axis (`ĝ'(0) < 0`, a linear gap's apex) makes `P(0)` infinite: its hole
//! never closes. Every integral is split at the profile's breakpoints and done by 10-point
//! Gauss-Legendre quadrature on each piece (near rounding for a piecewise-polynomial `ĝ`, whose
//! pieces are smooth in `θ` and `u`); the parabolic gap's `c_F = 1/3`, `κ_h = 1`, `d_c = 3` and the
//! power laws' closed forms come out to 1e-12 (tests below). The cost grows as the square of the
//! number of pieces for `c_F` and as its square times the scan for `d_c`: about 0.1 s for a table
//! of 100 points.

use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};

use crate::numerics::gauss_legendre::gauss_legendre;
use crate::numerics::golden::golden_section_max;
use crate::punch::PiecewiseProfile;

/// A concave profile `ĝ(ρ)` on `0 <= ρ <= 1`, `ĝ(0) = 1`, `ĝ(1) = 0`, smooth between
/// breakpoints.
pub trait ConcaveProfile {
    /// `dĝ/dρ`.
    fn slope(&self, rho: f64) -> f64;
    /// `d²ĝ/dρ²`.
    fn curvature(&self, rho: f64) -> f64;
    /// The radii in `[0, 1]` where `ĝ` may lose smoothness (a table's points), ascending.
    fn breakpoints(&self) -> Vec<f64>;
}

/// The full-contact constants of a concave profile.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FullContact {
    /// `c_F`: `F/(2 E* h a) = d/h - c_F` in full contact.
    pub force_offset: f64,
    /// `κ_h`: the rim intensity is `d/h + κ_h` (units of `h`).
    pub kappa_h: f64,
    /// `d_c/h`, the depth from which the contact is the full disk; `None` where the hole never
    /// closes.
    pub closure_depth: Option<f64>,
    /// The radius `r/a` where the full-contact pressure first vanishes as the depth falls
    /// below `d_c` (0: the hole opens at the axis; `> 0`: a ring opens, the contact closes
    /// from a disk and an annulus).
    pub opening_radius: f64,
}

impl FullContact {
    /// `F/(2 E* h a)` at closure, `d_c/h - c_F`.
    pub fn closure_force(&self) -> Option<f64> {
        self.closure_depth.map(|d| d - self.force_offset)
    }
}

/// Gauss-Legendre points per piece.
const POINTS: usize = 10;
/// Radii scanned for the maximum of `P(r)` before a golden-section refinement.
const SCAN: usize = 48;

/// A Gauss-Legendre rule on `[0, 1]`, mapped to each piece.
struct Rule {
    nodes: Vec<f64>,
    weights: Vec<f64>,
}

/// A node mapped to a piece.
struct Node {
    position: f64,
    weight: f64,
}

impl Rule {
    fn new() -> Self {
        let (nodes, weights) = gauss_legendre(POINTS);
        Self { nodes, weights }
    }

    fn panel(&self, lo: f64, hi: f64) -> impl Iterator<Item = Node> + '_ {
        let width = hi - lo;
        self.nodes
            .iter()
            .zip(&self.weights)
            .map(move |(x, w)| Node {
                position: lo + width * x,
                weight: width * w,
            })
    }
}

/// The full-contact constants of `profile` by the MDR quadratures above.
pub fn full_contact(profile: &dyn ConcaveProfile) -> FullContact {
    let rule = Rule::new();
    let breaks = breakpoints(profile);
    let g_at_one = mdr_profile(profile, &breaks, &rule, 1.0);
    let force_offset = over_pieces(&breaks, 0.0, 1.0, &rule, |x| {
        mdr_profile(profile, &breaks, &rule, x)
    });
    let smooth_at_axis = profile.slope(0.0) == 0.0;
    let (closure_depth, opening_radius) = if smooth_at_axis {
        let p = |r: f64| opening_depth(profile, &breaks, &rule, g_at_one, r);
        let (r, value) = maximise(p);
        (Some(value), r)
    } else {
        (None, 0.0)
    };
    FullContact {
        force_offset,
        kappa_h: -g_at_one,
        closure_depth,
        opening_radius,
    }
}

/// A piecewise profile as the MDR's quadratures read it.
struct Pieces<'a>(&'a dyn PiecewiseProfile);

impl ConcaveProfile for Pieces<'_> {
    fn slope(&self, rho: f64) -> f64 {
        self.0.slope(rho)
    }
    fn curvature(&self, rho: f64) -> f64 {
        self.0.curvature(rho)
    }
    fn breakpoints(&self) -> Vec<f64> {
        self.0.break_points().to_vec()
    }
}

/// [`full_contact`] of a piecewise profile, computed once per content and process.
pub fn piecewise_full_contact(profile: &dyn PiecewiseProfile) -> FullContact {
    static CACHE: OnceLock<PerContent<FullContact>> = OnceLock::new();
    once_per_content(&CACHE, profile, || full_contact(&Pieces(profile)))
}

/// Values computed from a piecewise profile, by its content's key.
type PerContent<T> = Mutex<HashMap<String, T>>;

/// `compute()` for `profile`, kept in `cache` so each content's is computed once per process.
fn once_per_content<T: Copy>(
    cache: &OnceLock<PerContent<T>>,
    profile: &dyn PiecewiseProfile,
    compute: impl FnOnce() -> T,
) -> T {
    let cache = cache.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(known) = cache
        .lock()
        .ok()
        .and_then(|m| m.get(profile.content_key()).copied())
    {
        return known;
    }
    let computed = compute();
    if let Ok(mut map) = cache.lock() {
        map.insert(profile.content_key().to_string(), computed);
    }
    computed
}

/// Lower bounds of the closure depth and force, `(P(0), P(0) - c_F)`: the opening depth at the
/// axis is at most `d_c = max_r P(r)`, and `F/(2 E* h a) = d/h - c_F` at closure. Two
/// quadratures of [`full_contact`]'s hundred or so, so a state well short of closure is
/// recognised without the maximisation (about 0.1 s for a table of 21 points). `None` where the
/// hole never closes (a slope at the axis).
pub fn closure_lower_bounds(profile: &dyn ConcaveProfile) -> Option<(f64, f64)> {
    if profile.slope(0.0) != 0.0 {
        return None;
    }
    let rule = Rule::new();
    let breaks = breakpoints(profile);
    let g_at_one = mdr_profile(profile, &breaks, &rule, 1.0);
    let force_offset = over_pieces(&breaks, 0.0, 1.0, &rule, |x| {
        mdr_profile(profile, &breaks, &rule, x)
    });
    let at_axis = opening_depth(profile, &breaks, &rule, g_at_one, 0.0);
    Some((at_axis, at_axis - force_offset))
}

/// [`closure_lower_bounds`] of a piecewise profile, computed once per content and process.
pub fn piecewise_closure_lower_bounds(profile: &dyn PiecewiseProfile) -> Option<(f64, f64)> {
    static CACHE: OnceLock<PerContent<Option<(f64, f64)>>> = OnceLock::new();
    once_per_content(&CACHE, profile, || closure_lower_bounds(&Pieces(profile)))
}

fn breakpoints(profile: &dyn ConcaveProfile) -> Vec<f64> {
    let mut breaks: Vec<f64> = profile
        .breakpoints()
        .into_iter()
        .filter(|r| (0.0..=1.0).contains(r))
        .collect();
    breaks.extend([0.0, 1.0]);
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    breaks
}

/// `∫_lo^hi f` split at the breakpoints inside, Gauss-Legendre on each piece.
fn over_pieces(breaks: &[f64], lo: f64, hi: f64, rule: &Rule, f: impl Fn(f64) -> f64) -> f64 {
    let mut cuts = vec![lo];
    cuts.extend(breaks.iter().copied().filter(|&b| b > lo && b < hi));
    cuts.push(hi);
    cuts.windows(2)
        .filter(|w| w[1] > w[0])
        .map(|w| {
            rule.panel(w[0], w[1])
                .map(|n| n.weight * f(n.position))
                .sum::<f64>()
        })
        .sum()
}

/// `∫_0^{π/2} f(x sin θ) dθ` split where `x sin θ` crosses a breakpoint.
fn over_angle(breaks: &[f64], x: f64, rule: &Rule, f: impl Fn(f64, f64) -> f64) -> f64 {
    let angles: Vec<f64> = breaks
        .iter()
        .filter(|&&b| b > 0.0 && b < x)
        .map(|&b| (b / x).asin())
        .collect();
    let mut cuts = vec![0.0];
    cuts.extend(angles);
    cuts.push(std::f64::consts::FRAC_PI_2);
    cuts.windows(2)
        .filter(|w| w[1] > w[0])
        .map(|w| {
            rule.panel(w[0], w[1])
                .map(|n| {
                    let s = n.position.sin();
                    n.weight * f(x * s, s)
                })
                .sum::<f64>()
        })
        .sum()
}

/// `G(x) = 1 + x ∫_0^{π/2} ĝ'(x sin θ) dθ`.
fn mdr_profile(profile: &dyn ConcaveProfile, breaks: &[f64], rule: &Rule, x: f64) -> f64 {
    1.0 + x * over_angle(breaks, x, rule, |r, _| profile.slope(r))
}

/// `G'(x) / x = ∫_0^{π/2} [ĝ'(x s)/x + s ĝ''(x s)] dθ` (finite at `x = 0` when `ĝ'(0) = 0`).
fn mdr_slope_over_x(profile: &dyn ConcaveProfile, breaks: &[f64], rule: &Rule, x: f64) -> f64 {
    over_angle(breaks, x, rule, |r, s| {
        profile.slope(r) / x + s * profile.curvature(r)
    })
}

/// `P(r) = G(1) - sqrt(1 - r²) ∫_0^{sqrt(1 - r²)} G'(x)/x du`, `x = sqrt(r² + u²)`: the depth
/// `d/h` at which the full-contact pressure at `r` vanishes.
fn opening_depth(
    profile: &dyn ConcaveProfile,
    breaks: &[f64],
    rule: &Rule,
    g_at_one: f64,
    r: f64,
) -> f64 {
    let top = (1.0 - r * r).max(0.0).sqrt();
    if top == 0.0 {
        return g_at_one;
    }
    // Breakpoints in x become u = sqrt(b² - r²).
    let u_breaks: Vec<f64> = breaks
        .iter()
        .filter(|&&b| b > r)
        .map(|&b| (b * b - r * r).sqrt())
        .collect();
    let integral = over_pieces(&u_breaks, 0.0, top, rule, |u| {
        mdr_slope_over_x(profile, breaks, rule, (r * r + u * u).sqrt())
    });
    g_at_one - top * integral
}

/// Maximum of `f` on `[0, 1)`: a scan of [`SCAN`] radii, then golden section around the best.
fn maximise(f: impl Fn(f64) -> f64) -> (f64, f64) {
    let at = |i: usize| i as f64 / SCAN as f64;
    let values: Vec<f64> = (0..SCAN).map(|i| f(at(i))).collect();
    let best = (0..SCAN)
        .max_by(|&i, &j| values[i].total_cmp(&values[j]))
        .unwrap_or(0);
    let r = golden_section_max(&f, at(best.saturating_sub(1)), at(best + 1), 1e-10);
    let refined = f(r);
    if refined >= values[best] {
        (r, refined)
    } else {
        (at(best), values[best])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::power_law;

    /// The gap `1 - ρ^n`, whose constants have closed forms.
    struct PowerLaw(f64);

    impl ConcaveProfile for PowerLaw {
        fn slope(&self, rho: f64) -> f64 {
            if rho == 0.0 {
                return if self.0 > 1.0 { 0.0 } else { -self.0 };
            }
            -self.0 * rho.powf(self.0 - 1.0)
        }
        fn curvature(&self, rho: f64) -> f64 {
            -self.0 * (self.0 - 1.0) * rho.powf(self.0 - 2.0)
        }
        fn breakpoints(&self) -> Vec<f64> {
            vec![0.5]
        }
    }

    #[test]
    fn sphere_and_power_laws_match_their_closed_forms() {
        for n in [2.0, 3.0, 4.0] {
            let fc = full_contact(&PowerLaw(n));
            let kappa = power_law::kappa(n);
            let scale = 1.0;
            assert!(
                (fc.force_offset - (1.0 - kappa / (n + 1.0))).abs() < 1e-12 * scale,
                "{n}"
            );
            assert!((fc.kappa_h - (kappa - 1.0)).abs() < 1e-12, "{n}");
            let closure = power_law::closure_depth(n).unwrap();
            assert!(
                (fc.closure_depth.unwrap() - closure).abs() < 1e-9,
                "n = {n}: {fc:?} vs {closure}"
            );
        }
        let parabolic = full_contact(&PowerLaw(2.0));
        assert!((parabolic.closure_depth.unwrap() - 3.0).abs() < 1e-12);
        assert!(parabolic.opening_radius < 1e-6);
        // n = 4: the pressure first fails on the ring r = a/2, at d = 7h/3.
        let quartic = full_contact(&PowerLaw(4.0));
        assert!((quartic.opening_radius - 0.5).abs() < 1e-4);
        assert!((quartic.closure_depth.unwrap() - 7.0 / 3.0).abs() < 1e-10);
    }

    /// The lower bounds of the closure are the closed forms where the hole opens at the axis
    /// (the parabolic gap: `d_c = 3h`, `F/(2 E* h a) = 3 - 1/3`) and bounds below them where it
    /// opens on a ring (`n = 4`, at `r = a/2`); none where the hole never closes.
    #[test]
    fn the_closure_bounds_bound_the_closure() {
        let (depth, force) = closure_lower_bounds(&PowerLaw(2.0)).unwrap();
        assert!((depth - 3.0).abs() < 1e-12, "{depth}");
        assert!((force - 8.0 / 3.0).abs() < 1e-12, "{force}");
        for n in [2.5, 3.0, 4.0, 8.0] {
            let (depth, force) = closure_lower_bounds(&PowerLaw(n)).unwrap();
            let closure = power_law::closure_depth(n).unwrap();
            let closure_force = power_law::full_contact_gamma2(n, closure).unwrap();
            assert!(depth <= closure + 1e-12, "n = {n}: {depth} > {closure}");
            assert!(
                force <= closure_force + 1e-12,
                "n = {n}: {force} > {closure_force}"
            );
        }
        let (quartic, _) = closure_lower_bounds(&PowerLaw(4.0)).unwrap();
        assert!(quartic < 7.0 / 3.0 - 1e-3, "{quartic}");
        assert!(closure_lower_bounds(&PowerLaw(1.0)).is_none());
    }

    #[test]
    fn a_slope_at_the_axis_never_closes() {
        let linear = full_contact(&PowerLaw(1.0));
        assert!(linear.closure_depth.is_none());
        assert!((linear.force_offset - (1.0 - std::f64::consts::FRAC_PI_4)).abs() < 1e-12);
    }
}
