//! One configuration of a Maugis-Dugdale contact on the ring BEM: the contact `[c1, c2]`
//! (`c1 = 0`: a disk) inside the loaded region `[z1, z2]` (the contact and its cohesive zones).
//!
//! **Superposition.** The tension `σ0` is laid over the whole loaded region (its deflection in
//! closed form, [`super::uniform_load`]) and the contact carries the rest, `p + σ0`: on the
//! contact the ring BEM solves `w(r) = d - h ĝ(r) + σ0 U(r)` with `U` the deflection of a unit
//! pressure on `[z1, z2]`. `U` is analytic inside the contact (its kinks are at `z1`, `z2`), so
//! the collocation keeps its geometric convergence. By linearity the contact's field is
//! `d φ_1 - h φ_g + σ0 φ_U`, three right-hand sides of one factorisation; a free edge (a
//! cohesive zone beyond it) has a bounded stress, its singular coefficient zero.

use crate::bem::ring::{ContactRegion, RingField, RingSystem};
use crate::numerics::tanh_sinh::TanhSinhRule;

use super::law::DugdaleLaw;
use super::path::PathPoint;
use super::uniform_load::{annulus_deflection, disk_deflection};

/// The gap profile `ĝ = 0` of a flat face.
pub(crate) fn flat_face(_: f64) -> f64 {
    0.0
}

/// The face `b <= r <= a` (`b = 0`: the whole disk) of gap `h ĝ(r)` with no contact left, all
/// of it in tension `σ0`: the first such state (the surface just leaving the face where
/// `h ĝ - σ0 U` is least, `U` the deflection of a unit pressure on the face) and the last (the
/// largest gap at `δc`), when the gap's spread over the face is within `δc`; `None` otherwise.
/// The force is `-π (a² - b²) σ0` throughout.
pub(crate) fn whole_face_in_tension(
    law: DugdaleLaw,
    hole: f64,
    h: f64,
    profile: &dyn Fn(f64) -> f64,
) -> Option<[PathPoint; 2]> {
    let (sigma0, range) = (law.tension(), law.range());
    // The gap plus the depth: `g(r) + d = h ĝ(r) - σ0 U(r)`.
    let offset = |r: f64| h * profile(r) - sigma0 * annulus_deflection(hole, 1.0, r);
    let least = least_between(&offset, hole, 1.0, 1e-12);
    let most = least_between(&|r| -offset(r), hole, 1.0, 1e-12);
    let (first_depth, last_depth) = (offset(least), offset(most) - range);
    if last_depth > first_depth {
        return None;
    }
    let configuration = Configuration {
        inner: least,
        outer: least,
        zone_inner: hole,
        zone_outer: 1.0,
    };
    let force = -sigma0 * std::f64::consts::PI * (1.0 - hole * hole);
    let has_inner = hole > 0.0 || h > 0.0;
    let gaps = |depth: f64| {
        let [inner, outer] = [hole, 1.0].map(|r| (offset(r) - depth) / range);
        [if has_inner { inner } else { 0.0 }, outer]
    };
    Some([
        PathPoint::new(configuration, first_depth, force, gaps(first_depth)),
        PathPoint::new(configuration, last_depth, force, gaps(last_depth)),
    ])
}

/// Samples of an interval searched for the least value before it is refined.
const FACE_SAMPLES: usize = 64;

/// Where `f` is least on `[lo, hi]`: the least of [`FACE_SAMPLES`] samples refined by golden
/// section between its neighbours to `tolerance` (an end sample kept when it is least).
pub(crate) fn least_between(f: &dyn Fn(f64) -> f64, lo: f64, hi: f64, tolerance: f64) -> f64 {
    let at = |k: usize| lo + (hi - lo) * k as f64 / FACE_SAMPLES as f64;
    let values: Vec<f64> = (0..=FACE_SAMPLES).map(|k| f(at(k))).collect();
    let best = (0..=FACE_SAMPLES)
        .min_by(|&i, &j| values[i].total_cmp(&values[j]))
        .unwrap_or(0);
    let (lo, hi) = (at(best.saturating_sub(1)), at((best + 1).min(FACE_SAMPLES)));
    let inside = crate::numerics::golden::golden_section_max(|r| -f(r), lo, hi, tolerance);
    if f(inside) < values[best] {
        inside
    } else {
        at(best)
    }
}

/// The contact `[inner, outer]` (`inner = 0`: the disk `r <= outer`) and the loaded region
/// `[zone_inner, zone_outer]` around it, in units of `a`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Configuration {
    /// Inner contact edge `c1` (0 for a disk).
    pub inner: f64,
    /// Outer contact edge `c2`.
    pub outer: f64,
    /// Inner end `z1 <= c1` of the loaded region.
    pub zone_inner: f64,
    /// Outer end `z2 >= c2` of the loaded region.
    pub zone_outer: f64,
}

/// The three fields of a configuration on one collocation system.
pub(crate) struct Fields<'a> {
    configuration: Configuration,
    system: &'a RingSystem,
    /// Radii of the problem are `scale` times the system's (a disk of radius `c2` solved on the
    /// unit disk; 1 for a band).
    scale: f64,
    unit: RingField,
    profile: RingField,
    load: RingField,
}

/// The parts of a band's fields that its zones do not change, solved once per band system: the
/// unit depth's and the profile's fields, and the deflection at the collocation radii of a unit
/// pressure on the face `s <= a` (`disk_deflection(1, r)`: a zone reaching the rim loads
/// `[z, a]`, the disk less the disk `s < z`).
pub(crate) struct BandParts {
    unit: RingField,
    profile: RingField,
    rim_load: Vec<f64>,
}

impl BandParts {
    /// The parts on a band's `system` for the face's `profile` (`ĝ`); `None` where the
    /// collocation matrix is singular.
    pub fn new(system: &RingSystem, profile: &dyn Fn(f64) -> f64) -> Option<Self> {
        let radii = system.radii();
        let profile_target: Vec<f64> = radii.iter().map(|&r| profile(r)).collect();
        Some(Self {
            unit: system.solve(&vec![1.0; radii.len()])?,
            profile: system.solve(&profile_target)?,
            rim_load: radii.iter().map(|&r| disk_deflection(1.0, r)).collect(),
        })
    }
}

/// A configuration's equilibrium: depth, force and the field that makes it.
pub(crate) struct Equilibrium {
    /// Depth `d / a` (positive into the solid).
    pub depth: f64,
    /// Force `F / (E* a²)`, positive in compression.
    pub force: f64,
    field: RingField,
}

impl<'a> Fields<'a> {
    /// Solve the configuration on `system` (the unit disk for a disk contact, the band's own
    /// system otherwise) for a punch of gap `h ĝ(r)` (`profile` = `ĝ`, `h` applied later).
    /// `None` where the collocation matrix is singular.
    pub fn solve(
        configuration: Configuration,
        system: &'a RingSystem,
        profile: &dyn Fn(f64) -> f64,
    ) -> Option<Self> {
        let scale = match system.region() {
            ContactRegion::Disk => configuration.outer,
            _ => 1.0,
        };
        let radii: Vec<f64> = system.radii().iter().map(|r| r * scale).collect();
        let (z1, z2) = (configuration.zone_inner, configuration.zone_outer);
        let unit = system.solve(&vec![1.0 / scale; radii.len()])?;
        let profile_target: Vec<f64> = radii.iter().map(|&r| profile(r) / scale).collect();
        let load_target: Vec<f64> = radii
            .iter()
            .map(|&r| annulus_deflection(z1, z2, r) / scale)
            .collect();
        let profile = system.solve(&profile_target)?;
        Self::with_load(configuration, system, scale, [unit, profile], &load_target)
    }

    /// The fields from the unit depth's and the profile's, the loaded region's solved for its
    /// `load_target` on `system`.
    fn with_load(
        configuration: Configuration,
        system: &'a RingSystem,
        scale: f64,
        [unit, profile]: [RingField; 2],
        load_target: &[f64],
    ) -> Option<Self> {
        Some(Self {
            configuration,
            system,
            scale,
            unit,
            profile,
            load: system.solve(load_target)?,
        })
    }

    /// [`Self::solve`] on a band's system with the `parts` its zones do not change.
    pub fn solve_on_band(
        configuration: Configuration,
        system: &'a RingSystem,
        parts: &BandParts,
    ) -> Option<Self> {
        let (z1, z2) = (configuration.zone_inner, configuration.zone_outer);
        let load_target: Vec<f64> = system
            .radii()
            .iter()
            .zip(&parts.rim_load)
            .map(|(&r, &rim)| {
                if z2 == 1.0 {
                    rim - disk_deflection(z1, r)
                } else {
                    annulus_deflection(z1, z2, r)
                }
            })
            .collect();
        let fields = [parts.unit.clone(), parts.profile.clone()];
        Self::with_load(configuration, system, 1.0, fields, &load_target)
    }

    /// The configuration solved.
    pub fn configuration(&self) -> Configuration {
        self.configuration
    }

    /// The singular coefficient of the contact's pressure at its outer (`true`) or inner edge
    /// at an equilibrium (positive: compressive).
    pub fn coefficient(&self, equilibrium: &Equilibrium, outer: bool) -> f64 {
        if outer {
            equilibrium.field.rim_coefficient
        } else {
            equilibrium.field.inner_coefficient
        }
    }

    /// The depth at which the outer edge's (`outer = true`) or inner edge's singular
    /// coefficient vanishes: `d φ_1(c) - h φ_g(c) + σ0 φ_U(c) = 0`.
    pub fn depth_freeing(&self, outer: bool, h: f64, sigma0: f64) -> f64 {
        let pick = |f: &RingField| {
            if outer {
                f.rim_coefficient
            } else {
                f.inner_coefficient
            }
        };
        (h * pick(&self.profile) - sigma0 * pick(&self.load)) / pick(&self.unit)
    }

    /// The equilibrium at depth `depth`.
    pub fn at_depth(&self, depth: f64, h: f64, sigma0: f64) -> Equilibrium {
        let field = self
            .unit
            .combined(depth, &self.profile, -h)
            .combined(1.0, &self.load, sigma0);
        let (z1, z2) = (self.configuration.zone_inner, self.configuration.zone_outer);
        let loaded_area = std::f64::consts::PI * (z2 * z2 - z1 * z1);
        Equilibrium {
            depth,
            force: self.scale * self.scale * field.force - sigma0 * loaded_area,
            field,
        }
    }

    /// The gap `w(r) - d + h ĝ(r)` between the surface and the punch at a radius `r` off the
    /// contact (beyond it or in its hole); `None` on the contact.
    pub fn gap(
        &self,
        equilibrium: &Equilibrium,
        r: f64,
        h: f64,
        sigma0: f64,
        profile: &dyn Fn(f64) -> f64,
        rule: &TanhSinhRule,
    ) -> Option<f64> {
        let scaled = r / self.scale;
        let contact = if r > self.configuration.outer {
            self.system
                .deflection_beyond(&equilibrium.field, scaled, rule)?
        } else {
            self.system
                .deflection_in_hole(&equilibrium.field, scaled, rule)?
        };
        let (z1, z2) = (self.configuration.zone_inner, self.configuration.zone_outer);
        let load = -sigma0 * annulus_deflection(z1, z2, r);
        Some(self.scale * contact + load - equilibrium.depth + h * profile(r))
    }
}
