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
use super::uniform_load::annulus_deflection;

/// The gap profile `ĝ = 0` of a flat face.
pub(crate) fn flat_face(_: f64) -> f64 {
    0.0
}

/// A flat face `b <= r <= a` (`b = 0`: the whole disk) with no contact left, all of it in
/// tension `σ0`: the first such state (the surface just leaving the face where its lift
/// `σ0 U(r)` is highest, the centre of a disk) and the last (the first face edge's gap at
/// `δc`), when the edges hold at the first; `None` otherwise. The force is `-π (a² - b²) σ0`
/// throughout.
pub(crate) fn whole_face_in_tension(law: DugdaleLaw, hole: f64) -> Option<[PathPoint; 2]> {
    let (sigma0, range) = (law.tension(), law.range());
    let lift = |r: f64| annulus_deflection(hole, 1.0, r);
    let top = if hole == 0.0 {
        0.0
    } else {
        crate::numerics::golden::golden_section_max(lift, hole, 1.0, 1e-12)
    };
    let highest = lift(top);
    let edges = [lift(hole), lift(1.0)];
    let lowest_edge = if hole == 0.0 {
        edges[1]
    } else {
        edges[0].min(edges[1])
    };
    if sigma0 * (highest - lowest_edge) > range {
        return None;
    }
    let configuration = Configuration {
        inner: top,
        outer: top,
        zone_inner: hole,
        zone_outer: 1.0,
    };
    let force = -sigma0 * std::f64::consts::PI * (1.0 - hole * hole);
    let gaps = |depth: f64| {
        let [inner, outer] = edges.map(|lift| (-sigma0 * lift - depth) / range);
        [if hole == 0.0 { 0.0 } else { inner }, outer]
    };
    let (first_depth, last_depth) = (-sigma0 * highest, -range - sigma0 * lowest_edge);
    Some([
        PathPoint::new(configuration, first_depth, force, gaps(first_depth)),
        PathPoint::new(configuration, last_depth, force, gaps(last_depth)),
    ])
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
        Some(Self {
            configuration,
            system,
            scale,
            unit,
            profile: system.solve(&profile_target)?,
            load: system.solve(&load_target)?,
        })
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
