//! JKR adhesion of a free band (a profile whose contact has two free edges): a contact band
//! `[b, c]` with a Griffith condition at both edges.
//!
//! Units as in the parent module: `d0 = sqrt(2π a Δw / E*)`, `F0 = 2 E* a d0`, `s = d0/h`. An edge is in equilibrium when its energy release rate `K²/(2E*)` equals `Δw`,
//! i.e. `K = -sqrt(2 E* Δw)`, which is `-s/sqrt(π)` in units of `E* h/sqrt(a)`. For a band
//! half-width `w` the ring BEM finds the band's centre and the depth `d` with that intensity at
//! both edges ([`RingBem::band_with_edge_intensity`]): the equilibrium curve
//! `(b(w), c(w), d(w), F(w))`, no fixed-annulus superposition (the band moves at both ends). The
//! width parametrises it (the inner edge does not: a narrow adhesive band drifts toward the
//! axis as it shrinks).
//!
//! Along the curve the contact shrinks as `w` falls. Under fixed load the branch is stable
//! while `dF/dw > 0` (a smaller contact carries less load) and the pull-off is the minimum of
//! `F`; under fixed grips it is stable while `dd/dw > 0` and the pull-off is at the minimum of
//! `d`, with the force there. Both minima are bracketed on a scan of `w` and located by Brent's
//! search, then by the slope's zero (`stationary_point`: a minimum told by its values alone
//! scatters by the square root of their noise).
//!
//! **Narrow limit.** For `d0/h -> 0` the pull-off band is narrow and sits where the band first
//! touches, `r0` ([`Profile::first_touch`](crate::punch::Profile::first_touch)), a plane-strain
//! cylinder of radius `ρ` (the gap's radius of curvature there) over the length `2π r0`: `P = π E* w²/(4ρ) - sqrt(2π E* Δw w)` per unit
//! length for the half-width `w` (Barquins 1988; the adhesive part is the flat strip's
//! `K = -P_a/sqrt(π w)`), with the fixed-load pull-off at `w_c = (2 ρ² Δw/(π E*))^(1/3)`,
//! `P_c = -(3/4) π E* w_c²/ρ`. [`plane_strain_pulloff`] gives it in the units above.

use std::f64::consts::PI;

use serde::Serialize;

use super::{check_scale, minimum_in, stationary_point, VALUE_SCATTER};
use crate::error::{Error, Result};
use crate::methods::{RingBem, RingState};
use crate::punch::PunchKind;

/// Tolerance of the equilibrium states that locate and report the critical ones.
const STATE_TOLERANCE: f64 = 1e-10;
/// Tolerance of the scan that brackets them.
const SCAN_TOLERANCE: f64 = 1e-7;
/// Points of the scan of half-widths, logarithmic over `[NARROWEST, WIDEST]`.
const SCAN_POINTS: usize = 48;
/// Narrowest half-width scanned (units of `a`): the ring BEM's narrowest band, `1e-4 a` wide.
const NARROWEST: f64 = 5e-5;
/// Widest half-width scanned (units of `a`): a band from about `0.4 a` to `2.4 a`.
const WIDEST: f64 = 1.0;
/// The widest band is halved down to this half-width in search of an equilibrium.
const MIN_WIDEST: f64 = 0.05;

/// A critical (pull-off) state of a free band.
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct BandCritical {
    /// Inner edge `b/a`.
    pub eps: f64,
    /// Outer edge `c/a`.
    pub outer: f64,
    /// `d/h`.
    pub depth: f64,
    /// `d/d0`.
    pub depth_over_d0: f64,
    /// `F/F0` (negative: tensile).
    pub force: f64,
    /// Bound on the error of `force` (`F/F0`, absolute): the ring BEM's estimate of the state
    /// times `|F|`, the values' scatter (`VALUE_SCATTER (1 + |F|)`, as the concave punches'),
    /// plus the force's change over the location's uncertainty in the half-width.
    pub error_bound: f64,
    /// Bound on the error of `depth` (`d/h`, absolute), made the same way.
    pub depth_error_bound: f64,
}

/// The JKR analysis of a free band for one `d0/h`.
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct BandJkr {
    #[serde(flatten)]
    pub punch: PunchKind,
    pub d0_over_h: f64,
    /// Pull-off under fixed load (the minimum of `F` along the equilibrium curve).
    pub fixed_load: Option<BandCritical>,
    /// Pull-off under fixed grips (the minimum of `d`, with its force).
    pub fixed_grips: Option<BandCritical>,
    /// Why there is no fixed-load pull-off state in the ring BEM's range, if there is none.
    pub fixed_load_note: Option<String>,
    /// Why there is no fixed-grips pull-off state in the ring BEM's range, if there is none.
    pub fixed_grips_note: Option<String>,
    /// The plane-strain JKR cylinder's fixed-load pull-off in the same units (`F/F0`): the
    /// narrow limit `d0/h -> 0`, an asymptote (no error bound); `None` for a profile that does
    /// not say where its band first touches.
    pub plane_strain_fixed_load: Option<f64>,
}

/// The fixed-load pull-off of the plane-strain JKR cylinder carried over the ring's length
/// `2π r0`, in units of `F0` for `s = d0/h` (see the module docs), for a band first touching at
/// `r0` (units of `a`) where the gap's curvature is `κ = a² g''(r0)/h`: with `h = 1`,
/// `ρ = 1/κ`, `Δw = s²/(2π)`, `w_c = (s²/(π² κ²))^(1/3)` and
/// `F_c = 2π r0 P_c = -(3/2) π² κ r0 w_c²`, so `F_c/F0 = -3π² κ r0 w_c²/(4s)`.
pub fn plane_strain_pulloff(s: f64, r0: f64, curvature: f64) -> f64 {
    let w = (s * s / (PI * PI * curvature * curvature)).cbrt();
    -3.0 * PI * PI * curvature * r0 * w * w / (4.0 * s)
}

/// The JKR pull-off of a free band `kind` under fixed load and fixed grips for `d0/h = s`.
pub fn band_jkr(solver: &RingBem, kind: &PunchKind, s: f64) -> Result<BandJkr> {
    check_scale(s)?;
    if !kind.is_free_band() {
        return Err(Error::Unsupported {
            method: "jkr".into(),
            reason: format!(
                "the {} has a rim: its JKR analysis is the concave punches' or the fixed \
                 annulus's, not a free band's",
                kind.name()
            ),
        });
    }
    let branch = Branch {
        solver,
        kind,
        s,
        intensity: -s / PI.sqrt(),
    };
    let (widest, first) = branch.widest_equilibrium()?;
    let (curve, end_note) = branch.trace(widest, &first);
    let fixed_load = branch.locate(&curve, |p| p.force, "force", widest, &end_note)?;
    let fixed_grips = branch.locate(&curve, |p| p.depth, "depth", widest, &end_note)?;
    Ok(BandJkr {
        punch: kind.clone(),
        d0_over_h: s,
        fixed_load_note: fixed_load.as_ref().err().cloned(),
        fixed_grips_note: fixed_grips.as_ref().err().cloned(),
        fixed_load: fixed_load.ok(),
        fixed_grips: fixed_grips.ok(),
        plane_strain_fixed_load: kind
            .first_touch()
            .map(|(r0, curvature)| plane_strain_pulloff(s, r0, curvature)),
    })
}

/// One equilibrium of the branch: the half-width `w`, `d/h`, `F/(2E*ha)` and the band's centre.
#[derive(Clone, Copy)]
struct BranchPoint {
    width: f64,
    depth: f64,
    force: f64,
    centre: f64,
}

impl BranchPoint {
    fn of(width: f64, st: &RingState) -> Self {
        BranchPoint {
            width,
            depth: st.gamma1.unwrap_or(f64::NAN),
            force: st.gamma2.unwrap_or(f64::NAN),
            centre: 0.5 * (st.eps + st.outer_edge),
        }
    }
}

/// A free band's JKR equilibrium branch at `d0/h = s`: both edges at the intensity `K = -s/√π`.
struct Branch<'a> {
    solver: &'a RingBem,
    kind: &'a PunchKind,
    s: f64,
    intensity: f64,
}

impl Branch<'_> {
    /// The equilibrium of half-width `w`, its centre search started at `hint`.
    fn state(&self, w: f64, tol: f64, hint: Option<f64>) -> Result<RingState> {
        self.solver
            .band_with_edge_intensity(self.kind, w, self.intensity, tol, hint)
    }

    /// The widest band in equilibrium: [`WIDEST`] halved until one is; at strong adhesion none
    /// is (the band would close toward a disk, which this analysis does not model).
    fn widest_equilibrium(&self) -> Result<(f64, RingState)> {
        let mut widest = WIDEST;
        loop {
            match self.state(widest, SCAN_TOLERANCE, None) {
                Ok(st) => return Ok((widest, st)),
                Err(e) if widest < 2.0 * MIN_WIDEST => {
                    return Err(Error::OutOfRange {
                        method: "jkr".into(),
                        reason: format!(
                            "the {} at d0/h = {}: no band of half-width {MIN_WIDEST} a or \
                             more was found in equilibrium with both edges at G = dw ({e}); at \
                             strong adhesion the contact may close toward a disk, which the \
                             band's JKR analysis does not model (checked for d0/h <= 1)",
                            self.kind.name(),
                            crate::error::show(self.s)
                        ),
                    })
                }
                Err(_) => widest *= 0.5,
            }
        }
    }

    /// The branch followed from the widest band down to the narrowest on a logarithmic scan,
    /// each state's centre search starting from the previous one's (one connected branch);
    /// ascending in `w` (the contact growing), with a note where it ended early.
    fn trace(&self, widest: f64, first: &RingState) -> (Vec<BranchPoint>, Option<String>) {
        let scan = (0..SCAN_POINTS).map(|k| {
            let t = k as f64 / (SCAN_POINTS - 1) as f64;
            widest * (NARROWEST / widest).powf(t)
        });
        let mut curve = vec![BranchPoint::of(widest, first)];
        let mut end_note = None;
        for w in scan.skip(1) {
            let hint = curve.last().map(|p| p.centre);
            match self.state(w, SCAN_TOLERANCE, hint) {
                Ok(st) => curve.push(BranchPoint::of(w, &st)),
                Err(e) => {
                    end_note = Some(format!("the branch ends at half-width {w:.3e} a: {e}"));
                    break;
                }
            }
        }
        curve.reverse();
        (curve, end_note)
    }

    /// The minimum of `pick` (the force under fixed load, the depth under fixed grips) along
    /// the branch: bracketed on the scan, located by Brent's search and then the slope's zero;
    /// a note instead where the scan holds no minimum.
    fn locate(
        &self,
        curve: &[BranchPoint],
        pick: fn(&BranchPoint) -> f64,
        quantity: &str,
        widest: f64,
        end_note: &Option<String>,
    ) -> Result<std::result::Result<BandCritical, String>> {
        let values: Vec<f64> = curve.iter().map(pick).collect();
        let Some(k) = (1..values.len() - 1)
            .find(|&k| values[k] <= values[k - 1] && values[k] <= values[k + 1])
        else {
            let narrowest = values[0] < values[values.len() - 1];
            return Ok(Err(format!(
                "no minimum of the {quantity} on the branch of half-widths [{:.3e}, {:.3e}] a: \
                 it lies in a band {}",
                curve[0].width,
                curve[curve.len() - 1].width,
                if narrowest {
                    format!(
                        "narrower than the branch reaches{}",
                        end_note
                            .as_ref()
                            .map(|n| format!(" ({n})"))
                            .unwrap_or_default()
                    )
                } else {
                    format!("wider than {widest:.3e} a")
                }
            )));
        };
        let hint = Some(curve[k].centre);
        let value = |w: f64| -> Result<f64> {
            let st = self.state(w, STATE_TOLERANCE, hint)?;
            Ok(pick(&BranchPoint::of(w, &st)))
        };
        let bracket = (curve[k - 1].width, curve[k + 1].width);
        let (w, _) = minimum_in(value, bracket.0, bracket.1)?;
        let (w, located_to) = stationary_point(value, w, bracket.0, bracket.1)?;
        self.critical_at(w, located_to, hint).map(Ok)
    }

    /// The critical state at the half-width `w` located to `located_to`: a quantity's change
    /// over that is second order where it is the minimum, first order (its slope in `w`) for
    /// the other one; both bounds carry it.
    fn critical_at(&self, w: f64, located_to: f64, hint: Option<f64>) -> Result<BandCritical> {
        let s = self.s;
        let st = self.state(w, STATE_TOLERANCE, hint)?;
        let (g1, g2) = (st.gamma1.unwrap_or(f64::NAN), st.gamma2.unwrap_or(f64::NAN));
        let step = 1e-9 * w.max(1e-3);
        let beside = self.state(w + step, STATE_TOLERANCE, hint)?;
        let force_slope = (beside.gamma2.unwrap_or(f64::NAN) - g2) / step;
        let depth_slope = (beside.gamma1.unwrap_or(f64::NAN) - g1) / step;
        let force = g2 / s;
        Ok(BandCritical {
            eps: st.eps,
            outer: st.outer_edge,
            depth: g1,
            depth_over_d0: g1 / s,
            force,
            error_bound: st.error_estimate * force.abs()
                + VALUE_SCATTER * (1.0 + force.abs())
                + (force_slope * located_to / s).abs(),
            depth_error_bound: st.error_estimate * g1.abs()
                + VALUE_SCATTER * (1.0 + g1.abs())
                + (depth_slope * located_to).abs(),
        })
    }
}
