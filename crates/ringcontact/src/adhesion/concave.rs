//! The JKR analysis of a concave punch (rim at `r = a`, inner edge free): the non-adhesive
//! branch's points ([`BranchPoint`]), the critical states on the annular branch under fixed load
//! and fixed grips with the rim criterion, the full-contact branch by the method of
//! dimensionality reduction, and the paper's route on its fits. The formulas are in the parent
//! module's documentation.

use std::collections::HashMap;
use std::sync::Mutex;

use rayon::prelude::*;
use serde::Serialize;

use super::ROOT_PI;
use crate::bem::ring::{ContactRegion, RingSystem};
use crate::bem::ring_contact::{HOLE_OVERLAP_TOLERANCE, HOLE_PROBES};
use crate::error::{Error, Result};
use crate::methods::RingBem;
use crate::numerics::brent::brent_minimum;
use crate::numerics::tanh_sinh::TanhSinhRule;
use crate::punch::PunchKind;

/// The non-adhesive and fixed-annulus quantities at one contact ratio (h = 1, a = 1, E* = 1).
#[derive(Clone, Copy, Debug, Serialize, serde::Deserialize)]
pub struct BranchPoint {
    pub eps: f64,
    pub gamma1: f64,
    pub gamma2: f64,
    pub gamma: f64,
    /// Rim intensity of the non-adhesive concave state per unit `h`.
    pub kappa_out_na: f64,
    pub kappa_out: f64,
    pub kappa_in: f64,
    /// The ring BEM's error estimates of the concave state (`γ1`, `γ2`, relative) and of the
    /// fixed annulus (`γ`, relative).
    #[serde(default)]
    pub concave_error: f64,
    #[serde(default)]
    pub flat_error: f64,
    /// Clearance of the non-adhesive state's surface over the punch's floor in the hole,
    /// `w(r) - (d - g(r))` (units of `h`) at the radii of [`crate::bem::ring_contact::hole_probes`]
    /// (infinite where the profile cannot meet the floor, [`PunchKind::may_meet_hole_floor`]).
    #[serde(skip)]
    pub hole_clearance: [f64; HOLE_PROBES],
    /// The fixed annulus's lag at the same radii, `1 - w(r)` at unit depth (zero where not
    /// probed).
    #[serde(skip)]
    pub hole_lag: [f64; HOLE_PROBES],
}

impl BranchPoint {
    /// `d/h` on the adhesive branch with `s = d0/h`.
    pub fn depth(&self, s: f64) -> f64 {
        self.gamma1 - s / self.kappa_in
    }
    /// `F/F0` on the adhesive branch.
    pub fn force(&self, s: f64) -> f64 {
        self.gamma2 / s - self.gamma / self.kappa_in
    }
    /// Rim intensity in units of `d0` (the rim holds while it is above `-1`).
    pub fn rim_intensity(&self, s: f64) -> f64 {
        self.kappa_out_na / s - self.kappa_out / self.kappa_in
    }
    /// The adhesive state's least clearance over the punch's floor in the hole (units of `h`):
    /// it is the non-adhesive state's plus the fixed annulus's pulled by `δ = -s/κ_in`, so
    /// `min_r [c(r) + (s/κ_in)(1 - u(r))]`, with `c` the non-adhesive clearance and `1 - u` the
    /// fixed annulus's lag. Negative: the punch would rise into the surface, and the state is
    /// not an annular contact.
    pub fn floor_clearance(&self, s: f64) -> f64 {
        self.hole_clearance
            .iter()
            .zip(&self.hole_lag)
            .map(|(c, lag)| c + s / self.kappa_in * lag)
            .fold(f64::INFINITY, f64::min)
    }
    /// [`Self::floor_clearance`] plus the overlap the ring BEM tolerates (`HOLE_OVERLAP_TOLERANCE`
    /// times the depth, at least 1): negative where the state touches the floor.
    pub fn floor_margin(&self, s: f64) -> f64 {
        self.floor_clearance(s) + HOLE_OVERLAP_TOLERANCE * self.depth(s).abs().max(1.0)
    }
    /// Whether the adhesive state clears the hole's floor ([`Self::floor_margin`]).
    pub fn clears_floor(&self, s: f64) -> bool {
        self.floor_margin(s) >= 0.0
    }
}

/// Ring-BEM quantities at `eps` for a concave punch (tolerance [`branch_tolerance`]). A point
/// whose solves cannot meet it is taken at the first of [`FALLBACK_BRANCH_TOLERANCES`] they
/// meet, its estimates (carried into the critical states' error bounds) saying so.
pub fn branch_point(solver: &RingBem, kind: PunchKind, eps: f64) -> Result<BranchPoint> {
    let tolerance = branch_tolerance(&kind);
    let mut outcome = branch_point_at(solver, kind.clone(), eps, tolerance);
    for looser in FALLBACK_BRANCH_TOLERANCES {
        match outcome {
            Err(Error::NoConvergence { .. }) if looser > tolerance => {
                outcome = branch_point_at(solver, kind.clone(), eps, looser);
            }
            _ => break,
        }
    }
    outcome
}

/// The hole clearance of a branch point of a profile that cannot meet its hole's floor
/// ([`PunchKind::may_meet_hole_floor`]): not probed (the probes' 16 integrals took a quarter to a
/// third of a linear gap's or parabolic gap's JKR analysis), every state clears it.
const UNPROBED_CLEARANCE: [f64; HOLE_PROBES] = [f64::INFINITY; HOLE_PROBES];

/// Looser tolerances, tried in turn, for a branch point whose solves cannot meet
/// [`branch_tolerance`]: the widest rings of a steep-walled profile, where the pressure gathers
/// at the rim and the inner edge's small `φ(b)` loses digits to rounding (the power laws
/// `n = 30, 50` at `b = 0.004 a` settle to 4e-10 and 9e-10, the linear gap to 1e-13). The last is
/// a piecewise profile's own tolerance.
const FALLBACK_BRANCH_TOLERANCES: [f64; 2] = [1e-9, 1e-8];

/// Tolerance of the branch's ring-BEM solves: 1e-10; 1e-8 for a piecewise profile, whose edge
/// derivatives settle to about 1e-9 at the scan's smallest contact ratios (`docs/methods.md`).
pub fn branch_tolerance(kind: &PunchKind) -> f64 {
    if kind.piecewise().is_some() {
        1e-8
    } else {
        1e-10
    }
}

/// [`branch_point`] from ring-BEM solves at `tolerance`.
fn branch_point_at(
    solver: &RingBem,
    kind: PunchKind,
    eps: f64,
    tolerance: f64,
) -> Result<BranchPoint> {
    let probes =
        |v: Vec<f64>| -> [f64; HOLE_PROBES] { v.try_into().unwrap_or([f64::NAN; HOLE_PROBES]) };
    let (concave, flat, hole_clearance, hole_lag) = if kind.may_meet_hole_floor() {
        let (concave, clearance) = solver
            .engine()
            .free_inner_edge_clearance(&kind, eps, tolerance)?;
        let (flat, lag) = solver.engine().flat_hole_lag(eps, tolerance)?;
        (concave, flat, probes(clearance), probes(lag))
    } else {
        (
            solver
                .engine()
                .free_inner_edge_field(&kind, eps, tolerance)?,
            solver.flat(eps, tolerance)?,
            UNPROBED_CLEARANCE,
            [0.0; HOLE_PROBES],
        )
    };
    Ok(BranchPoint {
        eps,
        gamma1: concave.gamma1.unwrap_or(f64::NAN),
        gamma2: concave.gamma2.unwrap_or(f64::NAN),
        gamma: flat.gamma.unwrap_or(f64::NAN),
        kappa_out_na: concave.rim_stress_intensity * ROOT_PI,
        kappa_out: flat.rim_stress_intensity * ROOT_PI,
        kappa_in: flat.inner_stress_intensity * ROOT_PI,
        concave_error: concave.error_estimate,
        flat_error: flat.error_estimate,
        hole_clearance,
        hole_lag,
    })
}

/// A critical (pull-off) state.
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct Critical {
    pub eps: f64,
    /// `d/h`.
    pub depth: f64,
    /// `d/d0`.
    pub depth_over_d0: f64,
    /// `F/F0`.
    pub force: f64,
    /// `inner` (the hole's edge), `rim` (the sharp outer edge), or `rim (full contact)`.
    pub governing_edge: String,
    /// Bound on the error of `force` (F/F0, absolute), propagated from the ring BEM: the
    /// change of the branch's force when its non-adhesive quantities come from a solve at
    /// tolerance 1e-7 instead of 1e-10, plus the slope along the branch times the location's
    /// uncertainty in `eps` (see [`ConcaveBranch::bound_critical`]); 0 for the closed forms of
    /// full contact.
    #[serde(default)]
    pub error_bound: Option<f64>,
    /// The same for `depth` (d/h, absolute).
    #[serde(default)]
    pub depth_error_bound: Option<f64>,
}

/// Full-contact branch: the disk with `w = d - h ĝ(r)`.
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct FullContactBranch {
    /// `F = 2 E* a (d - c_F h)` in full contact.
    pub force_offset: f64,
    /// Rim intensity of the profile part per unit `h` (`κ_rim = d/d0 + (h/d0) κ_h`).
    pub kappa_h: f64,
    /// Depth `d/h` at which the hole of the annular branch closes (its maximum depth).
    pub closing_depth: Option<f64>,
    /// Pull-off from full contact (rim criterion), the same under fixed load and fixed grips.
    pub pulloff: Critical,
}

/// The JKR analysis of a concave punch for one `d0/h`.
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct ConcaveJkr {
    #[serde(flatten)]
    pub punch: PunchKind,
    pub d0_over_h: f64,
    /// Pull-off from the annular contact under fixed load (`dF/deps = 0` or rim), if a stable
    /// annular branch with the rim attached exists.
    pub fixed_load: Option<Critical>,
    /// Pull-off from the annular contact under fixed grips (`dd/deps = 0` or rim).
    pub fixed_grips: Option<Critical>,
    /// Why there is no annular pull-off state (fixed load), if there is none.
    pub fixed_load_note: Option<String>,
    /// Why there is no annular pull-off state (fixed grips), if there is none.
    pub fixed_grips_note: Option<String>,
    /// The paper's route (inner edge only, the rim ignored): fixed load and fixed grips.
    pub inner_edge_only_fixed_load: Option<Critical>,
    /// The paper's route evaluated with the paper's fitted formulas, `(eps, F/F0)`: fixed load.
    pub paper_fits_fixed_load: Option<(f64, f64)>,
    /// The same, fixed grips.
    pub paper_fits_fixed_grips: Option<(f64, f64)>,
    pub inner_edge_only_fixed_grips: Option<Critical>,
    /// The stable annular branch under fixed load, `[eps_lo, eps_hi]`.
    pub stable_branch_fixed_load: Option<(f64, f64)>,
    pub full_contact: FullContactBranch,
    /// Direct check at the fixed-load critical state: `G_in/Δw` from a fresh BEM solve of the
    /// adhesive contact (1 if the formula route is right).
    pub direct_inner_energy_ratio: Option<f64>,
    /// Direct check: rim intensity from the fresh solve minus the formula's (units `d0`).
    pub direct_rim_difference: Option<f64>,
    /// Where the annular branch grown from the rim ends because the surface in the hole meets
    /// the punch's floor (a profile flatter than `1 - ρ²` at the axis, as `1 - ρ^n`
    /// with `n > 2`): pressed further the contact is a disk or a ring and the annulus, which this
    /// analysis does not model. `None` where the hole closes first.
    #[serde(default)]
    pub floor_contact: Option<FloorContact>,
}

/// The adhesive state at which the annular branch's surface meets the hole's floor.
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct FloorContact {
    /// Contact ratio `b/a`, located to 1e-9.
    pub eps: f64,
    /// `d/h`.
    pub depth: f64,
    /// `F/F0`.
    pub force: f64,
}

/// A minimum of `f` in `[lo, hi]` and its value, located to [`LOCATION_TOLERANCE`] in the
/// argument by its values (Brent's search: [`brent_minimum`]).
pub(super) fn minimum_in(
    f: impl FnMut(f64) -> Result<f64>,
    lo: f64,
    hi: f64,
) -> Result<(f64, f64)> {
    brent_minimum(f, lo, hi, 0.25 * LOCATION_TOLERANCE)
}

/// The stationary point of `f` near its minimum `x` in `[lo, hi]` (from [`minimum_in`]) and the
/// uncertainty of its location. A minimum told by its values is uncertain by `sqrt(2δ/f'')`
/// when `f` is known to `δ`: on the concave branches the values scatter by 5e-14 to 3e-13
/// and the minimum by 6e-8 to 1.3e-7 in `eps`, a hundred times the search's tolerance. Told by
/// its slope it is uncertain by `δ/(h f'')` only: Newton steps on the central differences with
/// `h = 1e-3 (hi - lo)`, `x ← x - h (f(x+h) - f(x-h)) / (2 (f(x+h) - 2f(x) + f(x-h)))`, at most
/// three. The uncertainty is [`LOCATION_TOLERANCE`] (the differences' bias `f''' h²/(6f'')`
/// stays below it on the scan's brackets) plus twice the last step (the scatter left); where no
/// step can be taken (the curvature not positive, a step leaving `[lo, hi]`), `x` with the
/// uncertainty `h`.
pub(super) fn stationary_point(
    mut f: impl FnMut(f64) -> Result<f64>,
    x: f64,
    lo: f64,
    hi: f64,
) -> Result<(f64, f64)> {
    let h = 1e-3 * (hi - lo);
    let mut at = x;
    let mut last = None;
    for _ in 0..3 {
        if at - h < lo || at + h > hi {
            break;
        }
        let (below, here, above) = (f(at - h)?, f(at)?, f(at + h)?);
        let curvature = above - 2.0 * here + below;
        // Not a minimum there (or not a number): no step.
        if curvature.is_nan() || curvature <= 0.0 {
            break;
        }
        let step = -0.5 * h * (above - below) / curvature;
        if !(lo..=hi).contains(&(at + step)) {
            break;
        }
        at += step;
        last = Some(step.abs());
        if step.abs() <= 0.1 * LOCATION_TOLERANCE {
            break;
        }
    }
    Ok(match last {
        Some(step) => (at, LOCATION_TOLERANCE + 2.0 * step),
        None => (x, h),
    })
}

/// The sign change of `f` in `[lo, hi]` by bisection, to [`LOCATION_TOLERANCE`].
fn bisect(mut f: impl FnMut(f64) -> Result<f64>, mut lo: f64, mut hi: f64) -> Result<f64> {
    let f_lo = f(lo)?;
    for _ in 0..60 {
        if (hi - lo).abs() <= LOCATION_TOLERANCE {
            break;
        }
        let mid = 0.5 * (lo + hi);
        if (f(mid)? > 0.0) == (f_lo > 0.0) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(0.5 * (lo + hi))
}

/// Contact ratios of the branch scan: cosine-clustered on `[0.004, 0.99]`, then logarithmic in
/// `1 - eps` up to the ring BEM's limit 0.9999 (weak adhesion pulls off from narrow rings).
fn scan_ratios() -> Vec<f64> {
    let mut ratios: Vec<f64> = (0..160)
        .map(|k| {
            let t = k as f64 / 160.0;
            0.004 + 0.986 * 0.5 * (1.0 - (std::f64::consts::PI * t).cos())
        })
        .collect();
    ratios.extend((0..=40).map(|k| 1.0 - 10f64.powf(-2.0 - 2.0 * k as f64 / 40.0)));
    ratios
}

/// The pull-off state, the stable branch `(eps_lo, eps_hi)` and the uncertainty of the state's
/// `eps`, or why there is none.
type AnnularOutcome = std::result::Result<(Critical, (f64, f64), f64), String>;

/// Pull-off on the annular branch for one quantity `q` (`F/F0` or `d/h`). Unloading starts at
/// the first interior maximum of `q` against `eps` and follows the branch while `q` falls. At a
/// local minimum the state is unstable: where a later part of the branch reaches lower values,
/// the contact jumps (a narrower ring at the same `q`) and unloading goes on there, so the
/// pull-off is the lowest `q` after the maximum (the only minimum for the linear gap, the parabolic
/// gap and the power laws; a tabulated profile's curvature steps at its points can add others). The
/// path visits the ratios where `q` is at its running minimum; the rim may fail first on them.
fn annular_pulloff(
    branch: &ConcaveBranch,
    s: f64,
    value: fn(&BranchPoint, f64) -> f64,
    check_rim: bool,
) -> Result<AnnularOutcome> {
    let points = &branch.scan;
    let values: Vec<f64> = points.iter().map(|p| value(p, s)).collect();
    // Loading grows the ring from the rim until the hole closes or its surface meets the
    // punch's floor (the branch's first ratio, `cut`): a maximum at the cut is the state
    // unloading starts from.
    let (cut, touch) = branch.floor_touch(s)?;
    if cut + 1 >= values.len() {
        return Ok(Err(
            "no annular state clears the hole's floor in 0.004 <= eps <= 0.9999".into(),
        ));
    }
    let Some(max_k) = (cut.max(1)..values.len() - 1).find(|&k| {
        (touch.is_some() && k == cut || values[k] >= values[k - 1]) && values[k] >= values[k + 1]
    }) else {
        return Ok(Err(
            "no stable annular branch in 0.004 <= eps <= 0.9999".into()
        ));
    };
    // The lowest value after the maximum (the first of equal ones).
    let min_k =
        (max_k + 1..values.len()).fold(max_k, |m, k| if values[k] < values[m] { k } else { m });
    if min_k + 1 >= values.len() || min_k == max_k {
        return Ok(Err(format!(
            "the stable branch runs beyond eps = {:.4} (the ring BEM's limit): pull-off from a ring narrower than 1e-4 a, with |F|/F0 below {:.2e}",
            points[points.len() - 1].eps,
            value(&points[points.len() - 1], s).abs()
        )));
    }
    // The unloading path: the ratios at the running minimum from the maximum on. A value above
    // it by no more than the solves' tolerance (relative) is on the path: the scatter of a flat
    // stretch is not a jump (a piecewise profile's real bumps are 1e-3 relative).
    let visited = unloading_path(&values, max_k, min_k, branch_tolerance(&branch.kind));
    let eval = |e: f64| -> Result<f64> { Ok(value(&branch.at(e)?, s)) };
    let minimum_near = |k: usize| -> Result<(f64, f64)> {
        let bracket = (points[k - 1].eps, points[k + 1].eps);
        let (eps_min, _) = minimum_in(eval, bracket.0, bracket.1)?;
        stationary_point(eval, eps_min, bracket.0, bracket.1)
    };
    let (eps_min, min_located_to) = minimum_near(min_k)?;
    let eps_max = match touch {
        Some(eps) if max_k == cut => eps,
        _ => {
            minimum_in(
                |e| Ok(-eval(e)?),
                points[max_k - 1].eps,
                points[max_k + 1].eps,
            )?
            .0
        }
    };
    // Rim along the path (unloading: eps grows from eps_max to eps_min).
    let rim_margin = |e: f64| -> Result<f64> { Ok(branch.at(e)?.rim_intensity(s) + 1.0) };
    let mut critical_eps = eps_min;
    let mut located_to = min_located_to;
    let mut edge = "inner";
    if check_rim && rim_margin(eps_max)? < 0.0 {
        return Ok(Err(format!(
            "the rim is already detached at the start of the stable branch (eps = {eps_max:.4}): no annular state with the rim attached"
        )));
    }
    let rim_fails = (max_k..=min_k).find(|&k| visited[k] && points[k].rim_intensity(s) + 1.0 < 0.0);
    if let Some(k) = rim_fails.filter(|_| check_rim) {
        if k > max_k && !visited[k - 1] {
            // The rim fails on landing from a jump: the pull-off is the minimum the jump
            // starts from, the last ratio visited before it.
            // (The maximum itself is always visited.)
            let start = (max_k..k).rev().find(|&j| visited[j]).unwrap_or(max_k);
            let (e, at) = minimum_near(start)?;
            critical_eps = e;
            located_to = at;
            edge = "inner (the rim fails on the jump)";
        } else {
            let lo = if k > max_k {
                points[k - 1].eps.max(eps_max)
            } else {
                eps_max
            };
            let e = bisect(rim_margin, lo, points[k].eps.min(eps_min))?;
            if e < eps_min {
                critical_eps = e;
                located_to = LOCATION_TOLERANCE;
                edge = "rim";
            }
        }
    }
    let critical = critical_on_branch(branch, s, critical_eps, edge)?;
    Ok(Ok((critical, (eps_max, eps_min), located_to)))
}

/// The ratios `max_k..=min_k` the unloading path visits: those at the running minimum of
/// `values`, a value above it by no more than the solves' tolerance `slack` (relative) counted
/// as on it.
fn unloading_path(values: &[f64], max_k: usize, min_k: usize, slack: f64) -> Vec<bool> {
    let mut visited = vec![false; values.len()];
    let mut lowest = f64::INFINITY;
    for k in max_k..=min_k {
        if values[k] <= lowest + slack * (1.0 + lowest.abs()) {
            lowest = lowest.min(values[k]);
            visited[k] = true;
        }
    }
    visited
}

/// The branch's state at `eps` as a critical state governed by `edge` (its bounds are set by
/// the caller).
fn critical_on_branch(branch: &ConcaveBranch, s: f64, eps: f64, edge: &str) -> Result<Critical> {
    let p = branch.at(eps)?;
    Ok(Critical {
        eps,
        depth: p.depth(s),
        depth_over_d0: p.depth(s) / s,
        force: p.force(s),
        governing_edge: edge.into(),
        error_bound: None,
        depth_error_bound: None,
    })
}

/// Full-contact constants of a concave punch by the method of dimensionality reduction: with
/// the profile `w = d - h ĝ(r)` on the whole disk, `F = 2 E* a (d - c_F h)` and the rim intensity
/// is `κ = d + κ_h h` (units as above), `c_F = 1/3`, `κ_h = 1` (parabolic gap) and `c_F = 1 - π/4`,
/// `κ_h = π/2 - 1` (linear gap). (The disk BEM reproduces the parabolic gap's to 1e-12; the linear
/// gap's profile has a kink on the axis, where the disk basis converges slowly.) The gap
/// `h (1 - (r/a)^n)`: `c_F = 1 - κ_n/(n + 1)`, `κ_h = κ_n - 1` with `κ_n` of
/// [`crate::reference::power_law::kappa`] (`κ_1 = π/2`, `κ_2 = 2` give the linear gap's and the
/// parabolic gap's). A profile that is neither `1 - ρ^n` nor piecewise has none here (an error
/// naming it).
pub fn full_contact_constants(kind: &PunchKind) -> Result<(f64, f64)> {
    if let Some(pieces) = kind.piecewise() {
        let fc = crate::reference::mdr::piecewise_full_contact(pieces);
        return Ok((fc.force_offset, fc.kappa_h));
    }
    match kind.power_law_exponent() {
        Some(1.0) => Ok((
            1.0 - std::f64::consts::FRAC_PI_4,
            std::f64::consts::FRAC_PI_2 - 1.0,
        )),
        Some(2.0) => Ok((1.0 / 3.0, 1.0)),
        Some(n) => {
            let kappa = crate::reference::power_law::kappa(n);
            Ok((1.0 - kappa / (n + 1.0), kappa - 1.0))
        }
        None => Err(Error::invalid(
            "punch",
            format!(
                "the {kind} has no full-contact constants here (only the power laws and the \
                 tables have them)"
            ),
        )),
    }
}

/// Full-contact branch of a concave punch (MDR constants).
fn full_contact(kind: PunchKind, s: f64, closing_depth: Option<f64>) -> Result<FullContactBranch> {
    let (force_offset, kappa_h) = full_contact_constants(&kind)?;
    // Rim: κ = d/d0 + (h/d0) κ_h reaches -1 at d = -d0 - h κ_h.
    let depth = -s - kappa_h;
    Ok(FullContactBranch {
        force_offset,
        kappa_h,
        closing_depth,
        pulloff: Critical {
            eps: 0.0,
            depth,
            depth_over_d0: depth / s,
            force: (depth - force_offset) / s,
            governing_edge: "rim (full contact)".into(),
            // Closed forms (the method of dimensionality reduction).
            error_bound: Some(0.0),
            depth_error_bound: Some(0.0),
        },
    })
}

/// Scatter of the branch's force `F/F0` and depth `d/h` from one contact ratio to the next,
/// absolute and relative to the two terms each is the difference of (`γ2/s` and `γ/κ_in`, `γ1`
/// and `s/κ_in`): the solves' rounding, which no estimate of theirs holds; twice the largest
/// found (docs/decisions.md, "Where the constants come from").
pub(super) const VALUE_SCATTER: f64 = 3e-12;

/// Location tolerance in `eps` of a critical state (the minimum searches, [`minimum_in`], and the
/// rim's bisection stop at 1e-9).
const LOCATION_TOLERANCE: f64 = 1e-9;

/// Range of `d0/h` the concave JKR analysis accepts: six decades either side of the paper's
/// `d0/h` ~ 1 (its figures span 0.1 to 10).
pub const D0H_RANGE: (f64, f64) = (1e-6, 1e6);

/// The non-adhesive branch of a concave punch: its [`BranchPoint`] at the scan's contact ratios
/// and at every ratio a search visits, each solved once. The points do not depend on `d0/h`, so
/// one branch serves the JKR analysis at any number of `d0/h` ([`ConcaveBranch::jkr`]) and the
/// searches of one analysis share the points they have in common (the paper's route and the
/// full route minimise the same `F(eps)` and `d(eps)`).
pub struct ConcaveBranch<'a> {
    solver: &'a RingBem,
    kind: PunchKind,
    /// The points at [`scan_ratios`], in order.
    scan: Vec<BranchPoint>,
    /// Every point solved, by the bits of its `eps`.
    solved: Mutex<HashMap<u64, BranchPoint>>,
}

impl<'a> ConcaveBranch<'a> {
    /// Solve the branch of `kind` at the scan's contact ratios (`0.004 ..= 0.9999`, 201 ratios),
    /// the ratios in parallel. Refuses a punch without a rim or not concave.
    pub fn new(solver: &'a RingBem, kind: PunchKind) -> Result<Self> {
        check_concave(kind.clone())?;
        // A ratio the ring BEM cannot resolve (the widest rings of a steep-walled profile) stops
        // the analysis: the error names the ratio and the scan.
        let scan: Vec<BranchPoint> = scan_ratios()
            .into_par_iter()
            .map(|e| {
                branch_point(solver, kind.clone(), e).map_err(|err| match err {
                    Error::NoConvergence { method, reason } => Error::NoConvergence {
                        method,
                        reason: format!(
                            "the JKR branch's scan of contact ratios 0.004 to 0.9999, at \
                             eps = {}: {reason}",
                            crate::error::show(e)
                        ),
                    },
                    other => other,
                })
            })
            .collect::<Result<_>>()?;
        let solved = scan.iter().map(|p| (p.eps.to_bits(), *p)).collect();
        Ok(Self {
            solver,
            kind,
            scan,
            solved: Mutex::new(solved),
        })
    }

    /// Where the adhesive branch for `d0/h = s` grown from the rim meets the hole's floor: the
    /// index of the widest scan ratio on it (the first of the run of states that clear the
    /// floor up to the narrowest ring; 0 where all do) and the ratio of the touch, located by
    /// bisection between that ratio and the one before (`None` where all clear the floor).
    fn floor_touch(&self, s: f64) -> Result<(usize, Option<f64>)> {
        let Some(last_touching) = self.scan.iter().rposition(|p| !p.clears_floor(s)) else {
            return Ok((0, None));
        };
        let cut = last_touching + 1;
        if cut >= self.scan.len() {
            return Ok((cut, None));
        }
        let eps = bisect(
            |e| Ok(self.at(e)?.floor_margin(s)),
            self.scan[last_touching].eps,
            self.scan[cut].eps,
        )?;
        Ok((cut, Some(eps)))
    }

    /// The branch's point at `eps` ([`branch_point`]), solved at most once.
    pub fn at(&self, eps: f64) -> Result<BranchPoint> {
        let known = self
            .solved
            .lock()
            .ok()
            .and_then(|m| m.get(&eps.to_bits()).copied());
        if let Some(p) = known {
            return Ok(p);
        }
        let p = branch_point(self.solver, self.kind.clone(), eps)?;
        if let Ok(mut m) = self.solved.lock() {
            m.insert(eps.to_bits(), p);
        }
        Ok(p)
    }

    /// JKR analysis of the punch for `d0/h = s` on this branch.
    pub fn jkr(&self, s: f64) -> Result<ConcaveJkr> {
        check_scale(s)?;
        let (solver, kind) = (self.solver, self.kind.clone());
        let split = |r: AnnularOutcome| match r {
            Ok(v) => (Some(v), None),
            Err(note) => (None, Some(note)),
        };
        let (load, load_note) = split(annular_pulloff(self, s, |p, s| p.force(s), true)?);
        let (grips, grips_note) = split(annular_pulloff(self, s, |p, s| p.depth(s), true)?);
        let paper_load = annular_pulloff(self, s, |p, s| p.force(s), false)?
            .ok()
            .map(|(c, _, at)| (c, at));
        let paper_grips = annular_pulloff(self, s, |p, s| p.depth(s), false)?
            .ok()
            .map(|(c, _, at)| (c, at));
        let floor_contact = match self.floor_touch(s)? {
            (_, Some(eps)) => {
                let p = self.at(eps)?;
                Some(FloorContact {
                    eps,
                    depth: p.depth(s),
                    force: p.force(s),
                })
            }
            _ => None,
        };
        // The hole closes at the branch's deepest state, unless its floor is met first.
        let closing = self
            .scan
            .iter()
            .map(|p| p.depth(s))
            .fold(f64::NEG_INFINITY, f64::max);
        let closing = (closing.is_finite() && floor_contact.is_none()).then_some(closing);
        let paper_fits = paper_fit_route(kind.clone(), s);
        let full = full_contact(kind.clone(), s, closing)?;
        // Direct route at the fixed-load critical state: solve the adhesive contact itself.
        let (ratio, rim_diff) = match &load {
            Some((c, _, _)) => {
                let (kin, krim) = direct_intensities(solver, kind.clone(), c)?;
                let (kin, krim) = (kin * ROOT_PI / s, krim * ROOT_PI / s);
                let formula = self.at(c.eps)?.rim_intensity(s);
                (Some(kin * kin), Some(krim - formula))
            }
            None => (None, None),
        };
        let bound = |c: Option<(Critical, f64)>| -> Result<Option<Critical>> {
            c.map(|(c, located_to)| self.bound_critical(s, &c, located_to))
                .transpose()
        };
        let paper_load = bound(paper_load)?;
        let paper_grips = bound(paper_grips)?;
        Ok(ConcaveJkr {
            punch: kind,
            d0_over_h: s,
            stable_branch_fixed_load: load.as_ref().map(|(_, b, _)| *b),
            fixed_load: bound(load.map(|(c, _, at)| (c, at)))?,
            fixed_grips: bound(grips.map(|(c, _, at)| (c, at)))?,
            fixed_load_note: load_note,
            fixed_grips_note: grips_note,
            inner_edge_only_fixed_load: paper_load,
            paper_fits_fixed_load: paper_fits.0,
            paper_fits_fixed_grips: paper_fits.1,
            inner_edge_only_fixed_grips: paper_grips,
            full_contact: full,
            floor_contact,
            direct_inner_energy_ratio: ratio,
            direct_rim_difference: rim_diff,
        })
    }

    /// `c` with its error bounds. The non-adhesive inputs' share is the larger of two: the ring
    /// BEM's own estimates propagated through the branch (`d/h = γ1 - s/κ_in`,
    /// `F/F0 = γ2/s - γ/κ_in`: `δF = γ2 e_c/s + γ e_f/κ_in + γ δκ_in/κ_in²`,
    /// `δd = γ1 e_c + s δκ_in/κ_in²`, with `e_c`, `e_f` the concave and flat states' relative
    /// estimates and `δκ_in` the change of the inner intensity between tolerances 1e-10 (1e-8
    /// for a piecewise profile, [`branch_tolerance`]) and 1e-7, never below `e_f κ_in`), and the
    /// change of the branch's force and depth when every input comes from the solves at 1e-7. Added
    /// to it: the values' scatter ([`VALUE_SCATTER`] times one plus the two terms' sizes) and each
    /// quantity's slope along the branch times `located_to`, the uncertainty of the state's `eps`
    /// ([`stationary_point`] for a minimum, [`LOCATION_TOLERANCE`] for a rim crossing; the term is
    /// near zero for the quantity that is stationary, the fixed-load force or the fixed-grips
    /// depth, not for the other one).
    pub fn bound_critical(&self, s: f64, c: &Critical, located_to: f64) -> Result<Critical> {
        let p = self.at(c.eps)?;
        let looser = branch_point_at(self.solver, self.kind.clone(), c.eps, 1e-7)?;
        let d_kappa_in = (looser.kappa_in - p.kappa_in)
            .abs()
            .max(p.flat_error * p.kappa_in);
        let k2 = p.kappa_in * p.kappa_in;
        let propagated_force = p.gamma2 * p.concave_error / s
            + p.gamma * p.flat_error / p.kappa_in
            + p.gamma * d_kappa_in / k2;
        let propagated_depth = p.gamma1 * p.concave_error + s * d_kappa_in / k2;
        let step = 1e-6 * c.eps.min(1.0 - c.eps);
        let nearby = self.at(c.eps + step)?;
        let slope_force = ((nearby.force(s) - p.force(s)) / step).abs();
        let slope_depth = ((nearby.depth(s) - p.depth(s)) / step).abs();
        let force_scatter =
            VALUE_SCATTER * (1.0 + (p.gamma2 / s).abs() + (p.gamma / p.kappa_in).abs());
        let depth_scatter = VALUE_SCATTER * (1.0 + p.gamma1.abs() + (s / p.kappa_in).abs());
        Ok(Critical {
            error_bound: Some(
                propagated_force.max((looser.force(s) - p.force(s)).abs())
                    + force_scatter
                    + slope_force * located_to,
            ),
            depth_error_bound: Some(
                propagated_depth.max((looser.depth(s) - p.depth(s)).abs())
                    + depth_scatter
                    + slope_depth * located_to,
            ),
            ..c.clone()
        })
    }
}

/// Refuse a punch the concave JKR analysis does not apply to.
fn check_concave(kind: PunchKind) -> Result<()> {
    if !kind.is_concave() {
        return Err(Error::invalid(
            "punch",
            format!(
                "the concave JKR analysis applies to the punches with a rim and a free inner \
                 edge ({})",
                crate::punch::PunchName::names(Some(crate::punch::Contact::RimAndFreeInner), ", ")
            ),
        ));
    }
    if !kind.has_rim() {
        return Err(Error::Unsupported {
            method: "jkr".into(),
            reason: format!(
                "the {kind}'s contact has two free edges and no rim: its JKR analysis is \
                 `adhesion::band_jkr` (`verify jkr --punch {kind}`)"
            ),
        });
    }
    Ok(())
}

/// Refuse a `d0/h` outside [`D0H_RANGE`] (the concave punches' and the free bands' analyses).
pub(super) fn check_scale(s: f64) -> Result<()> {
    if !(s.is_finite() && s > 0.0) {
        return Err(Error::invalid(
            "d0h",
            format!("must be a positive number (got {})", crate::error::show(s)),
        ));
    }
    if !(D0H_RANGE.0..=D0H_RANGE.1).contains(&s) {
        return Err(Error::invalid(
            "d0h",
            format!(
                "must lie in [{:e}, {:e}] (got {}): the critical depths and forces scale with \
                 powers of d0/h and lose all meaning, then overflow, beyond",
                D0H_RANGE.0,
                D0H_RANGE.1,
                crate::error::show(s)
            ),
        ));
    }
    Ok(())
}

/// JKR analysis of a concave punch for `d0/h = s` (its branch solved for this `s` alone; for
/// many `d0/h`, solve the [`ConcaveBranch`] once and call [`ConcaveBranch::jkr`]).
pub fn concave(solver: &RingBem, kind: PunchKind, s: f64) -> Result<ConcaveJkr> {
    check_concave(kind.clone())?;
    check_scale(s)?;
    ConcaveBranch::new(solver, kind)?.jkr(s)
}

/// Both edges' intensities (units `E* h / sqrt(a)`) of the adhesive contact at a critical
/// state, solved directly: the annulus `[eps, 1]` pressed to the state's depth, collocated at 40
/// nodes (a piecewise profile: its band through the flat band's fields, refined to 1e-9).
fn direct_intensities(solver: &RingBem, kind: PunchKind, c: &Critical) -> Result<(f64, f64)> {
    if kind.piecewise().is_some() {
        let band = solver
            .engine()
            .punch_band(&kind, c.eps, 1.0, c.depth, 1e-9)?;
        return Ok((band.inner_stress_intensity, band.outer_stress_intensity));
    }
    let rule = TanhSinhRule::new(1.0 / 16.0);
    let n = 40;
    let system = RingSystem::assemble(ContactRegion::Annulus { eps: c.eps }, n, &rule);
    let target: Vec<f64> = system
        .radii()
        .iter()
        .map(|&r| c.depth - kind.gap_shape(r))
        .collect();
    let field = system.solve(&target).ok_or_else(|| Error::NoConvergence {
        method: "ring-bem".into(),
        reason: "singular system".into(),
    })?;
    Ok((
        system.inner_stress_intensity(&field),
        system.rim_stress_intensity(&field),
    ))
}

/// `(eps, F/F0)` of a critical state.
pub type EpsForce = (f64, f64);

/// The paper's route evaluated with the paper's own fitted `γ1`, `γ2` (eqs. 8-11), as the paper
/// did: `Δl_c = d0 sqrt(eps γ1'² / (γ1''γ2' - γ2''γ1'))` (28), `k/(2E*a) = γ2'/γ1'` (25), inner
/// edge only; the critical states are the interior minima of `F(eps)` (29, fixed load) and `d(eps)`
/// (30, fixed grips). Derivatives by central differences of the fits. Returns
/// `(fixed load, fixed grips)` as `(eps, F/F0)`, each `None` where the fitted branch has no
/// interior minimum.
pub fn paper_fit_route(kind: PunchKind, s: f64) -> (Option<EpsForce>, Option<EpsForce>) {
    // The fits the profile declares (the paper fitted two concave punches).
    let (Some(fit1), Some(fit2)) = (
        crate::reference::fit_of(&kind, 1),
        crate::reference::fit_of(&kind, 2),
    ) else {
        return (None, None);
    };
    let g = |i: usize, e: f64| {
        let fit = if i == 1 { &fit1 } else { &fit2 };
        (fit.eval)(e).value
    };
    let d1 = |i: usize, e: f64| {
        let h = 1e-6 * e.min(1.0 - e);
        (g(i, e + h) - g(i, e - h)) / (2.0 * h)
    };
    let d2 = |i: usize, e: f64| {
        let h = 1e-4 * e.min(1.0 - e);
        (g(i, e + h) - 2.0 * g(i, e) + g(i, e - h)) / (h * h)
    };
    // (d/h, F/F0) on the fitted adhesive branch.
    let state = |e: f64| -> (f64, f64) {
        let (g1p, g2p) = (d1(1, e), d1(2, e));
        let shift = s * (e * g1p * g1p / (d2(1, e) * g2p - d2(2, e) * g1p)).sqrt();
        (g(1, e) - shift, g(2, e) / s - (g2p / g1p) * shift / s)
    };
    let ratios: Vec<f64> = (1..2000)
        .map(|k| 0.01 + 0.985 * k as f64 / 2000.0)
        .collect();
    let first_minimum = |pick: fn((f64, f64)) -> f64| -> Option<(f64, f64)> {
        let v: Vec<f64> = ratios.iter().map(|&e| pick(state(e))).collect();
        let k =
            (1..v.len() - 1).find(|&k| v[k].is_finite() && v[k] <= v[k - 1] && v[k] <= v[k + 1])?;
        let (e, _) = minimum_in(|e| Ok(pick(state(e))), ratios[k - 1], ratios[k + 1]).ok()?;
        Some((e, state(e).1))
    };
    (first_minimum(|(_, f)| f), first_minimum(|(d, _)| d))
}
