//! JKR adhesion built on the ring BEM's converged non-adhesive solutions (paper section 3).
//!
//! Units: depths in `d0 = sqrt(2π a Δw / E*)`, forces in `F0 = sqrt(8π a³ E* Δw) = 2 E* a d0`
//! (Kendall's flat-faced punch). Stress intensities `K = E* L κ / sqrt(π a)` with `L` the depth
//! (flat) or `h` (concave); an edge of the adhesive contact is in equilibrium when
//! `G = K²/(2E*) = Δw`, i.e. `|κ| L = d0`.
//!
//! **Fixed annulus** (fixed contact): `κ_out² = γ - eps γ'` (rim), `κ_in² = -γ'/eps` (inner edge);
//! detachment at the outer edge at `d_c/d0 = -1/κ_out`, `F_c/F0 = -γ/κ_out` (paper 16-17), at the
//! inner edge at `d_c/d0 = -1/κ_in`, `F_c/F0 = -γ/κ_in` (paper 20); the smaller `|d_c|` governs.
//!
//! **Concave punches**, contact `[b, a]`, `eps = b/a`: the adhesive state adds to the non-adhesive
//! one a fixed-annulus displacement `-Δl` at fixed contact; the inner edge is in equilibrium for
//! `Δl = d0/κ_in(eps)` (paper 27-28, simplified with `γ2' = γ γ1'`), so
//! `d/h = γ1 - (d0/h)/κ_in`, `F/F0 = (h/d0) γ2 - γ/κ_in`.
//! The branch is stable under fixed grips where `dd/deps < 0` and under fixed load where
//! `dF/deps < 0` (the energy release rate at the inner edge falls as it advances); the critical
//! states (paper 29-30) are the minima of `d` and `F` along the stable branch. The sharp rim
//! detaches when its stress intensity, `κ_rim = (h/d0) κ_out^na - κ_out/κ_in` in units of
//! `d0`, reaches `-1` (tensile, `G = Δw`): the rim criterion, checked along the branch.
//! The **full-contact branch** (no hole; the disk with `w = d - h ĝ(r)`) has only the rim as an
//! edge: pull-off at `d_c = h κ_h - d0`, `F_c/F0 = (h/d0)(κ_h - c_F) - 1` with `κ_h` the rim
//! intensity of the profile and `F = 2 E* a (d - c_F h)` in full contact.

use serde::Serialize;

use crate::bem::ring::ContactRegion;
use crate::bem::ring_contact::{free_edge_floor, MAX_CONTACT_RATIO, MIN_CONTACT_RATIO};
use crate::error::{Error, Result};
use crate::methods::RingBem;
use crate::punch::collins_series;

mod any_punch;
mod concave;
mod free_band;
pub use any_punch::{jkr, refuse_other_family, Jkr};
pub use concave::{
    branch_point, branch_tolerance, concave, full_contact_constants, paper_fit_route, BranchPoint,
    ConcaveBranch, ConcaveJkr, Critical, EpsForce, FloorContact, FullContactBranch, D0H_RANGE,
};
use concave::{check_scale, minimum_in, stationary_point, VALUE_SCATTER};
pub use free_band::{band_jkr, plane_strain_pulloff, BandCritical, BandJkr};

const TOL: f64 = 1e-11;
const ROOT_PI: f64 = 1.772_453_850_905_516;

/// Fourth-order difference of `f` at `x` with step `h > 0`, evaluating `f` only inside
/// `[lo, hi]` (which holds `x`): the central one, `(-f(x+2h) + 8f(x+h) - 8f(x-h) + f(x-2h)) /
/// (12h)`, where its stencil fits, else the one-sided one toward the inside, `(-25f(x) +
/// 48f(x+s) - 36f(x+2s) + 16f(x+3s) - 3f(x+4s)) / (12s)` with `s = ±h` (error `h⁴ f⁽⁵⁾/5`
/// against `h⁴ f⁽⁵⁾/30`). At the ends of the ring BEM's validated range the central stencil
/// would ask for a contact ratio just outside it.
fn derivative(f: impl Fn(f64) -> Result<f64>, x: f64, h: f64, lo: f64, hi: f64) -> Result<f64> {
    if x - 2.0 * h >= lo && x + 2.0 * h <= hi {
        return Ok(
            (-f(x + 2.0 * h)? + 8.0 * f(x + h)? - 8.0 * f(x - h)? + f(x - 2.0 * h)?) / (12.0 * h),
        );
    }
    let s = if x + 4.0 * h <= hi { h } else { -h };
    Ok(
        (-25.0 * f(x)? + 48.0 * f(x + s)? - 36.0 * f(x + 2.0 * s)? + 16.0 * f(x + 3.0 * s)?
            - 3.0 * f(x + 4.0 * s)?)
            / (12.0 * s),
    )
}

/// Fixed-annulus quantities at `eps`: `γ`, `γ'` (difference of converged values), and the edge
/// intensities `κ` both from the force derivative (fact 7) and read directly off the BEM pressure.
#[derive(Clone, Copy, Debug, Serialize, serde::Deserialize)]
pub struct AnnulusEdges {
    pub eps: f64,
    pub gamma: f64,
    pub gamma_prime: f64,
    pub kappa_out: f64,
    pub kappa_in: f64,
    pub kappa_out_direct: f64,
    pub kappa_in_direct: f64,
}

/// `γ`, `γ'` and the edge intensities of the fixed annulus at `eps`.
pub fn annulus_edges(solver: &RingBem, eps: f64) -> Result<AnnulusEdges> {
    let gamma = |e: f64| -> Result<f64> { Ok(solver.flat(e, TOL)?.gamma.unwrap_or(f64::NAN)) };
    // The state first: a contact ratio outside the ring BEM's range is refused as given.
    let state = solver.flat(eps, TOL)?;
    let step = 1e-3 * eps.min(1.0 - eps);
    let gamma_prime = derivative(gamma, eps, step, MIN_CONTACT_RATIO, MAX_CONTACT_RATIO)?;
    let g = state.gamma.unwrap_or(f64::NAN);
    Ok(AnnulusEdges {
        eps,
        gamma: g,
        gamma_prime,
        kappa_out: (g - eps * gamma_prime).sqrt(),
        kappa_in: (-gamma_prime / eps).sqrt(),
        kappa_out_direct: state.rim_stress_intensity * ROOT_PI,
        kappa_in_direct: state.inner_stress_intensity * ROOT_PI,
    })
}

/// Critical depth and force of one edge (units `d0`, `F0`).
#[derive(Clone, Copy, Debug, Serialize, serde::Deserialize)]
pub struct EdgeCritical {
    pub depth: f64,
    pub force: f64,
}

/// JKR detachment of the fixed annulus (paper Fig. 7-8 recomputed).
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct FixedAnnulusJkr {
    pub eps: f64,
    pub gamma: f64,
    pub gamma_prime: f64,
    /// `d_c/d0` and `F_c/F0` for detachment at `r = a`.
    pub dc_outer: f64,
    pub fc_outer: f64,
    /// `d_c/d0` and `F_c/F0` for detachment at `r = b`.
    pub dc_inner: f64,
    pub fc_inner: f64,
    /// `outer` or `inner`: the edge with the smaller `|d_c|`.
    pub governing_edge: String,
    /// Relative difference of `κ_out`, `κ_in` read off the pressure field and from `γ'`.
    pub kappa_consistency: f64,
    /// Collins' series (paper 21) in (16)-(17), where valid (`eps <= 0.3`).
    pub collins: Option<EdgeCritical>,
    /// Argatov's narrow-ring asymptote (paper 22), where valid (`eps >= 0.85`).
    pub argatov: Option<EdgeCritical>,
    /// Error bounds of `dc_outer`, `fc_outer`, `dc_inner`, `fc_inner` (absolute, the same
    /// units), propagated from the ring BEM's estimates ([`FixedAnnulusBounds`]).
    #[serde(default)]
    pub error_bounds: Option<FixedAnnulusBounds>,
}

/// Error bounds of the fixed annulus' critical states, propagated from the ring BEM: `δγ` its
/// estimate; `δγ'` the change of the differenced `γ'` when its step is doubled plus the
/// stencil's amplification of `δγ` (`1.5 δγ / h`); `δκ_out = (δγ + eps δγ') / (2 κ_out)`;
/// `δκ_in` the change of the field's inner intensity between tolerances 1e-11 and 1e-8 (at
/// least the estimate and the inner edge's rounding floor `5e-14 a/b` relative); then
/// `δd_c = δκ/κ²`, `δF_c = δγ/κ + γ δκ/κ²`.
#[derive(Clone, Copy, Debug, Serialize, serde::Deserialize)]
pub struct FixedAnnulusBounds {
    pub dc_outer: f64,
    pub fc_outer: f64,
    pub dc_inner: f64,
    pub fc_inner: f64,
}

/// [`FixedAnnulusBounds`] at `eps` from the edges `e` computed at tolerance [`TOL`].
fn flat_annulus_bounds(
    solver: &RingBem,
    e: &AnnulusEdges,
    kappa_out: f64,
    kappa_in: f64,
) -> Result<FixedAnnulusBounds> {
    let eps = e.eps;
    let gamma = |x: f64| -> Result<f64> { Ok(solver.flat(x, TOL)?.gamma.unwrap_or(f64::NAN)) };
    let state = solver.flat(eps, TOL)?;
    let d_gamma = state.error_estimate.max(f64::EPSILON) * e.gamma;
    let step = 1e-3 * eps.min(1.0 - eps);
    let doubled = derivative(gamma, eps, 2.0 * step, MIN_CONTACT_RATIO, MAX_CONTACT_RATIO)?;
    let d_gamma_prime = (doubled - e.gamma_prime).abs() + 1.5 * d_gamma / step;
    let d_kappa_out = (d_gamma + eps * d_gamma_prime) / (2.0 * kappa_out);
    // The change between two tolerances, floored at the solve's own relative estimate and at
    // the inner edge's rounding floor (5e-14 a/b, as for a free edge: the intensity at the
    // inner edge scatters by that much between node counts whatever the edge; at b/a = 0.0099
    // it moved by 3e-13 of itself when the rows' sums were reordered, above the estimate's
    // 1e-13): where both ladders stop at the same discretisation the change is exactly 0,
    // which bounds nothing.
    let looser = solver.flat(eps, 1e-8)?;
    let floor = free_edge_floor(ContactRegion::Annulus { eps });
    let d_kappa_in = (looser.inner_stress_intensity * ROOT_PI - kappa_in)
        .abs()
        .max(state.error_estimate.max(floor) * kappa_in.abs());
    let of = |kappa: f64, d_kappa: f64| {
        (
            d_kappa / (kappa * kappa),
            d_gamma / kappa + e.gamma * d_kappa / (kappa * kappa),
        )
    };
    let (dc_outer, fc_outer) = of(kappa_out, d_kappa_out);
    let (dc_inner, fc_inner) = of(kappa_in, d_kappa_in);
    Ok(FixedAnnulusBounds {
        dc_outer,
        fc_outer,
        dc_inner,
        fc_inner,
    })
}

/// JKR detachment of the fixed annulus at `eps`: `d_c/d0 = -1/κ`, `F_c/F0 = -γ/κ` at each edge,
/// each `κ` by the route that keeps its digits. The rim's by the energy route, `κ_out² = γ -
/// eps γ'` (fact 7, `γ'` by differences; the difference term is small where it is least
/// accurate). The inner edge's as the ring BEM reads it off its pressure field (as for the
/// concave punches' [`branch_point`]): the energy route's `κ_in² = -γ'/eps` loses digits where
/// `γ'` is small against `γ` (`γ' ≈ -4 eps²/π²`); at `eps = 1e-4` it was 24 % off Collins'
/// `2 sqrt(eps)/π`, the field's within 4e-7 of it. `kappa_consistency`
/// compares the two routes at both edges.
pub fn fixed_annulus(solver: &RingBem, eps: f64) -> Result<FixedAnnulusJkr> {
    if !(0.0 < eps && eps < 1.0) {
        return Err(Error::invalid(
            "eps",
            format!(
                "must satisfy 0 < b/a < 1 for an annulus (got {})",
                crate::error::show(eps)
            ),
        ));
    }
    let e = annulus_edges(solver, eps)?;
    let (kappa_out, kappa_in) = (e.kappa_out, e.kappa_in_direct);
    let consistency = ((e.kappa_out_direct - e.kappa_out) / e.kappa_out)
        .abs()
        .max(((e.kappa_in_direct - e.kappa_in) / e.kappa_in).abs());
    let collins = (eps <= 0.3).then(|| {
        let pi2 = std::f64::consts::PI.powi(2);
        let g = collins_series(eps).value;
        let gp = -4.0 * eps * eps / pi2
            - 8.0 * eps.powi(4) / (3.0 * pi2)
            - 32.0 * eps.powi(5) / (9.0 * pi2 * pi2);
        let k = (g - eps * gp).sqrt();
        EdgeCritical {
            depth: -1.0 / k,
            force: -g / k,
        }
    });
    let argatov = (eps >= 0.85).then(|| {
        let delta = (1.0 - eps) / (1.0 + eps);
        let log = (16.0 / delta).ln();
        let pi = std::f64::consts::PI;
        EdgeCritical {
            depth: -std::f64::consts::SQRT_2 * log * ((1.0 + eps) * delta).sqrt() / pi,
            force: -pi * ((1.0 + eps).powi(3) * delta).sqrt() / (2.0 * std::f64::consts::SQRT_2),
        }
    });
    Ok(FixedAnnulusJkr {
        eps,
        gamma: e.gamma,
        gamma_prime: e.gamma_prime,
        dc_outer: -1.0 / kappa_out,
        fc_outer: -e.gamma / kappa_out,
        dc_inner: -1.0 / kappa_in,
        fc_inner: -e.gamma / kappa_in,
        governing_edge: if kappa_out >= kappa_in {
            "outer"
        } else {
            "inner"
        }
        .into(),
        kappa_consistency: consistency,
        collins,
        argatov,
        error_bounds: Some(flat_annulus_bounds(solver, &e, kappa_out, kappa_in)?),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_difference_is_fourth_order_and_evaluates_only_inside_the_range() {
        // d/dx sin x = cos x, at the middle and at both ends of [0.2, 0.8].
        for x in [0.5, 0.2, 0.8, 0.2 + 1e-4, 0.8 - 1e-4] {
            let inside = std::cell::Cell::new(true);
            let f = |t: f64| {
                inside.set(inside.get() && (0.2..=0.8).contains(&t));
                Ok(t.sin())
            };
            let slope = derivative(f, x, 1e-3, 0.2, 0.8).unwrap();
            assert!((slope - x.cos()).abs() < 1e-11, "x = {x}: {slope}");
            assert!(inside.get(), "x = {x}: evaluated outside [0.2, 0.8]");
        }
    }
}
