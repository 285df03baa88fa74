//! A flat face `r <= a` in contact ([`crate::punch::Contact::Disk`]) under the Dugdale law: contact on the disk `r <= c`, the cohesive
//! zone `c < r < m` inside the face, `m = a` (the zone reaches the rim, whose gap is below `δc`)
//! or `m < a` where the gap reaches `δc`; with no contact left, the whole face in tension.

use crate::bem::ring::{ContactRegion, RingSystem};
use crate::bem::ring_contact::RingBemSolver;
use crate::error::{Error, Result};
use crate::numerics::roots::find_root;

use super::configuration::{Configuration, Fields};
use super::law::DugdaleLaw;
use super::path::{self, Control, PathPoint};
use super::uniform_load::disk_deflection;
use super::METHOD;

/// Path samples, spaced geometrically in the distance `1 - c/a` of the contact's edge from the
/// rim.
const PATH_SAMPLES: usize = 40;

/// Smallest contact radius `c/a` sampled before the whole face is in tension.
const SMALLEST_CONTACT: f64 = 1e-3;

/// Tolerance of the zone's end `m/a` (its root of `g(m) = δc`).
const ZONE_END_TOLERANCE: f64 = 1e-14;

/// The flat face's states at one node count.
pub(crate) struct FlatDisk<'a> {
    solver: &'a RingBemSolver,
    system: &'a RingSystem,
    law: DugdaleLaw,
}

fn flat(_: f64) -> f64 {
    0.0
}

impl<'a> FlatDisk<'a> {
    /// The states on `system`, the unit disk's (every contact radius is this disk scaled).
    pub fn new(solver: &'a RingBemSolver, system: &'a RingSystem, law: DugdaleLaw) -> Self {
        debug_assert_eq!(system.region(), ContactRegion::Disk);
        Self {
            solver,
            system,
            law,
        }
    }

    /// The equilibrium with the contact `r <= c` and the zone's end at `m`: its point and the
    /// gap at `m` (the rim's when `m = 1`).
    fn with_zone_end(&self, c: f64, m: f64) -> Result<(PathPoint, f64)> {
        let sigma0 = self.law.tension();
        let configuration = Configuration {
            inner: 0.0,
            outer: c,
            zone_inner: 0.0,
            zone_outer: m,
        };
        let fields =
            Fields::solve(configuration, self.system, &flat).ok_or_else(|| Error::Implausible {
                method: METHOD.into(),
                state: format!("contact radius {c}"),
                reason: "singular collocation matrix".into(),
            })?;
        let depth = fields.depth_freeing(true, 0.0, sigma0);
        let equilibrium = fields.at_depth(depth, 0.0, sigma0);
        let rule = self.solver.deflection_rule(self.system.unknowns());
        let gap = fields
            .gap(&equilibrium, m, 0.0, sigma0, &flat, rule)
            .unwrap_or(0.0);
        Ok((PathPoint::new(configuration, depth, equilibrium.force), gap))
    }

    /// The state with contact radius `c` (`0 < c < 1`).
    pub fn state(&self, c: f64) -> Result<PathPoint> {
        let range = self.law.range();
        let (clipped, rim_gap) = self.with_zone_end(c, 1.0)?;
        if rim_gap <= range {
            return Ok(clipped);
        }
        let root = find_root(
            |m| {
                self.with_zone_end(c, m)
                    .map(|(_, gap)| gap - range)
                    .map_err(|e| e.to_string())
            },
            c,
            1.0,
            0.5 * (c + 1.0),
            ZONE_END_TOLERANCE,
            200,
        )
        .map_err(|e| Error::NoConvergence {
            method: METHOD.into(),
            reason: format!("the cohesive zone's end at contact radius {c}: {e:?}"),
        })?;
        Ok(self.with_zone_end(c, root.x)?.0)
    }

    /// With no contact left and the whole face in tension: the first such state (the surface
    /// just leaving the face's centre) and the last (the rim's gap at `δc`), where the rim's gap
    /// is within the range when the centre lets go; `None` otherwise.
    pub fn whole_face_in_tension(&self) -> Option<[PathPoint; 2]> {
        let sigma0 = self.law.tension();
        let (centre, rim) = (disk_deflection(1.0, 0.0), disk_deflection(1.0, 1.0));
        if sigma0 * (centre - rim) > self.law.range() {
            return None;
        }
        let configuration = Configuration {
            inner: 0.0,
            outer: 0.0,
            zone_inner: 0.0,
            zone_outer: 1.0,
        };
        let force = -sigma0 * std::f64::consts::PI;
        Some([
            PathPoint::new(configuration, -sigma0 * centre, force),
            PathPoint::new(configuration, -self.law.range() - sigma0 * rim, force),
        ])
    }

    /// The path parameter `t = ln(1 - c/a)` of the first sample (where the zone is a fiftieth
    /// of its JKR-limit length `a/λ²`) and of the last ([`SMALLEST_CONTACT`]), and their spacing.
    fn parameter_range(&self) -> (f64, f64, f64) {
        let first = (0.02 * self.law.zone_length()).clamp(1e-7, 0.5).ln();
        let last = (1.0 - SMALLEST_CONTACT).ln();
        (first, last, (last - first) / (PATH_SAMPLES - 1) as f64)
    }

    /// The state at path parameter `t = ln(1 - c/a)`.
    fn at(&self, t: f64) -> Result<PathPoint> {
        self.state(1.0 - t.exp())
    }

    /// The path as the punch is pulled: contact radii from near the rim down to
    /// [`SMALLEST_CONTACT`], then the whole face in tension if its rim holds; each state with
    /// its path parameter (infinite for the whole face in tension).
    pub fn path(&self) -> Result<Vec<(f64, PathPoint)>> {
        let (first, _, step) = self.parameter_range();
        let mut samples = Vec::with_capacity(PATH_SAMPLES + 2);
        for k in 0..PATH_SAMPLES {
            let t = first + step * k as f64;
            samples.push((t, self.at(t)?));
        }
        if let Some(tension) = self.whole_face_in_tension() {
            for point in tension {
                samples.push((f64::INFINITY, point));
            }
        }
        Ok(samples)
    }

    /// The pull-off under `control` and its path parameter: refined by golden section within
    /// two sample spacings of `near` (a coarser node count's), else found along the whole path.
    pub fn pulloff(&self, control: Control, near: Option<f64>) -> Result<(f64, PathPoint)> {
        let held = |p: &PathPoint| control.held(p);
        let (first, last, step) = self.parameter_range();
        let inside_path =
            |t: &f64| t.is_finite() && *t - 2.0 * step >= first && *t + 2.0 * step <= last;
        if let Some(t) = near.filter(inside_path) {
            let bracket: Vec<(f64, PathPoint)> = [t - 2.0 * step, t, t + 2.0 * step]
                .into_iter()
                .map(|t| self.at(t).map(|p| (t, p)))
                .collect::<Result<_>>()?;
            let inside = held(&bracket[1].1) < held(&bracket[0].1).min(held(&bracket[2].1));
            if inside {
                return path::first_minimum(&bracket, held, |t| self.at(t));
            }
        }
        path::first_minimum(&self.path()?, held, |t| self.at(t))
    }
}
