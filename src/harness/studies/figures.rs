//! The data behind the report's charts that the methods compute: the dimensionless functions
//! against `eps` ([`FunctionCurves`]), the pressure profile of one state by three methods
//! ([`PressureProfiles`]) and the JKR route's adhesive annular branch ([`annular_jkr_branch`]).
//! The report only draws them.

use serde::{Deserialize, Serialize};

use super::UnitLoad;
use crate::harness::cases::{self, report_profile_punches, REPORT_TABLE_SAMPLES};
use ringcontact::error::Result;
use ringcontact::methods::Degree;
use ringcontact::methods::FarField;
use ringcontact::methods::{GridBem, GridState, RingBem};
use ringcontact::punch::PunchKind;

/// A curve or a set of points `(x, y)`.
pub(crate) type Points = Vec<(f64, f64)>;

/// `b/a` of the fixed annulus's curve: 61 points on `[0, 0.99]`.
pub(crate) fn flat_ratios() -> Vec<f64> {
    (0..=60).map(|k| 0.99 * k as f64 / 60.0).collect()
}

/// `b/a` of the concave punches' curves: 50 points on `(0.05, 0.95]`.
pub(crate) fn concave_ratios() -> Vec<f64> {
    (1..=50).map(|k| 0.05 + 0.9 * k as f64 / 50.0).collect()
}

fn is_power(punch: &PunchKind) -> bool {
    punch.exponent_parameter().is_some()
}

/// `gamma1 = d/h` and `gamma2 = F/(2 E* h a)` of one concave punch against `b/a` by the ring BEM.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub(crate) struct ConcaveCurves {
    #[serde(flatten)]
    pub punch: PunchKind,
    pub gamma1: Points,
    pub gamma2: Points,
    /// The outer edge `c/a` at the same `b/a` (a free band only; the others' is the rim).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub outer: Points,
    /// The report's table only: `(d/h, gamma2)` of the punch it samples
    /// ([`REPORT_TABLE_SAMPLES`]) at the table's depths `gamma1`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sampled_at_depth: Points,
    /// The report's table only: the largest difference of its gap `g/h` from the sampled
    /// punch's ([`largest_gap_difference`]), which bounds the difference of `gamma2` at one depth.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gap_difference: Option<f64>,
}

/// The largest difference of two punches' gaps `g/h` over `0 <= r/a <= 1`, sampled at 20 001
/// radii. The contact problem is monotone in the gap: a profile within `δ h` of another's is
/// pressed between that punch's states at depths `d ∓ δ h`, and the force's slope in the depth
/// is at most the full disk's `2 E* a`, so their `gamma2` at one depth differ by at most `δ`.
pub(crate) fn largest_gap_difference(one: PunchKind, other: PunchKind) -> f64 {
    (0..=20_000)
        .map(|k| k as f64 / 20_000.0)
        .map(|rho| (one.gap_shape(rho) - other.gap_shape(rho)).abs())
        .fold(0.0, f64::max)
}

/// The dimensionless functions against `eps` that the methods compute for the report's charts.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub(crate) struct FunctionCurves {
    /// `gamma = F/(2 E* d a)` of the fixed annulus by the ring BEM at [`flat_ratios`].
    pub flat_ring_bem: Points,
    /// The same by the grid BEM on 128² at `b/a` = 0, 0.5, 0.9 (those that solved).
    pub flat_grid_bem: Points,
    /// The functions of [`report_profile_punches`] at [`concave_ratios`] (where one annulus).
    pub concave: Vec<ConcaveCurves>,
    /// `(d/h, gamma2)` of the free band by the grid BEM at [`BAND_GRID_DEPTHS`] (128², its own
    /// square; those that solved). The JSON key names the built-in free band.
    #[serde(default, rename = "torus_grid_bem")]
    pub band_grid_bem: Points,
}

/// Depths `d/h` at which the report's free-band chart shows the grid BEM.
pub(crate) const BAND_GRID_DEPTHS: [f64; 3] = [0.1, 0.5, 2.0];

/// Compute the function curves (ring BEM to 1e-10, grid BEM on 128²).
pub(crate) fn function_curves(ring: &RingBem) -> Result<FunctionCurves> {
    let flat_ring_bem = flat_ratios()
        .into_iter()
        .map(|e| Ok((e, ring.flat(e, 1e-10)?.gamma.unwrap_or(f64::NAN))))
        .collect::<Result<_>>()?;
    let mut flat_grid_bem = Vec::new();
    for e in [0.0, 0.5, 0.9] {
        if let Ok(s) = grid_alone(cases::flat_punch(e), e, UnitLoad::Flat, 128) {
            flat_grid_bem.push((e, s.gamma.unwrap_or(f64::NAN)));
        }
    }
    let mut concave = Vec::new();
    for punch in report_profile_punches() {
        let (mut gamma1, mut gamma2, mut outer) = (Vec::new(), Vec::new(), Vec::new());
        for e in concave_ratios() {
            let s = match ring.concave_at_ratio(&punch, e, 1e-10) {
                Ok(s) => s,
                // A profile flatter at the axis than `r²` has one annulus only for the wider
                // holes (docs/conventions.md fact 8): the curve stops where the ring BEM refuses.
                Err(_) if is_power(&punch) || punch.piecewise().is_some() => continue,
                Err(e) => return Err(e),
            };
            gamma1.push((e, s.gamma1.unwrap_or(f64::NAN)));
            gamma2.push((e, s.gamma2.unwrap_or(f64::NAN)));
            if !punch.has_rim() {
                outer.push((e, s.outer_edge));
            }
        }
        let (mut sampled_at_depth, mut gap_difference) = (Vec::new(), None);
        if punch.piecewise().is_some() {
            for &(_, depth) in &gamma1 {
                let s = ring.concave_at_depth(&REPORT_TABLE_SAMPLES, depth, 1e-10)?;
                sampled_at_depth.push((depth, s.gamma2.unwrap_or(f64::NAN)));
            }
            gap_difference = Some(largest_gap_difference(punch.clone(), REPORT_TABLE_SAMPLES));
        }
        concave.push(ConcaveCurves {
            punch,
            gamma1,
            gamma2,
            outer,
            sampled_at_depth,
            gap_difference,
        });
    }
    let band_grid_bem = crate::harness::cases::free_bands()
        .into_iter()
        .take(1)
        .flat_map(|band| BAND_GRID_DEPTHS.map(|d| (band.clone(), d)))
        .filter_map(|(band, d)| {
            grid_alone(band, 0.0, UnitLoad::Depth(d), 128)
                .ok()
                .and_then(|s| Some((d, s.gamma2?)))
        })
        .collect();
    Ok(FunctionCurves {
        flat_ring_bem,
        flat_grid_bem,
        concave,
        band_grid_bem,
    })
}

/// Contact pressure `p a/(E* h)` against `r/a` at [`cases::PRESSURE_PROFILE`] by three methods.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub(crate) struct PressureProfiles {
    /// The ring BEM's nodal pressures.
    pub ring_bem: Points,
    /// The grid BEM on 256², averaged over 64 rings of width `a/64`.
    pub grid_bem: Points,
    /// The FEM's (P2, tolerance 1e-3) nodal estimates where positive, `r < 0.99 a`.
    pub fem: Points,
}

/// Compute the pressure profiles at [`cases::PRESSURE_PROFILE`].
pub(crate) fn pressure_profiles(ring: &RingBem) -> Result<PressureProfiles> {
    let (kind, depth) = cases::PRESSURE_PROFILE;
    let state = ring.concave_at_depth(&kind, depth, 1e-10)?;
    let ring_bem = state.pressure.iter().map(|&(r, p)| (r, p)).collect();
    let grid_bem =
        grid_alone(kind.clone(), 0.0, UnitLoad::Depth(depth), 256)?.ring_averaged_pressure(64);
    let fem = ringcontact::methods::Fem {
        degree: Some(Degree::Quadratic),
        far_field: Some(FarField::Boussinesq),
        ..crate::harness::settings::fem()
    };
    let scene = super::unit_scene(kind, 0.0, UnitLoad::Depth(depth), Some(1e-3))?;
    // Nodal estimates in the contact, clipped near the rim singularity.
    let fem = fem
        .state(&scene)?
        .contact_pressure()
        .into_iter()
        .filter(|&(r, p)| p > 0.0 && r < 0.99)
        .collect();
    Ok(PressureProfiles {
        ring_bem,
        grid_bem,
        fem,
    })
}

/// The grid BEM's state of `kind` under `load` on `n²` cells alone (the paper's method as its
/// peers run it: no coarser levels, residual 1e-10).
fn grid_alone(kind: PunchKind, eps: f64, load: UnitLoad, n: usize) -> Result<GridState> {
    let grid = GridBem {
        cells: n,
        with_estimate: false,
        ..GridBem::default()
    };
    grid.state(&super::unit_scene(kind, eps, load, None)?)
}

/// The pulled part of the JKR route's adhesive annular branch of `punch` at `d0/h`, from the
/// ring BEM at `b/a` = 0.30-0.995 (`d/h = γ1 - (d0/h)/κ_in`, `F/F0 = (h/d0) γ2 - γ/κ_in`), as
/// `(d/d0, F/F0)`: from its fixed-grips end (the most negative depth) back toward smaller
/// `b/a` while the depth rises, up to `d = 0`.
pub(crate) fn annular_jkr_branch(ring: &RingBem, punch: PunchKind, d0_over_h: f64) -> Points {
    // b/a = 0.30-0.96 by 0.01, then 0.965-0.995 by 0.005 (at small d0/h the annulus lets go
    // near the rim: at b/a = 0.98 for the linear gap at d0/h = 0.3).
    let ratios = (0..=66)
        .map(|k| 0.30 + 0.01 * k as f64)
        .chain((1..=7).map(|k| 0.96 + 0.005 * k as f64));
    let x = d0_over_h;
    let all: Vec<(f64, f64)> = ratios
        .filter_map(|ratio| {
            let p = ringcontact::adhesion::branch_point(ring, punch.clone(), ratio)
                .ok()
                .filter(|p| p.clears_floor(x))?;
            let point = (p.depth(x) / x, p.force(x));
            (point.0.is_finite() && point.1.is_finite()).then_some(point)
        })
        .collect();
    let mut jkr: Vec<(f64, f64)> = Vec::new();
    if let Some(end) = (0..all.len()).min_by(|&i, &j| all[i].0.total_cmp(&all[j].0)) {
        for point in all[..=end].iter().rev() {
            if point.0 > 0.0 || jkr.last().is_some_and(|last| point.0 < last.0) {
                break;
            }
            jkr.push(*point);
        }
    }
    jkr
}
