//! A flat face `r <= a` in contact ([`crate::punch::Contact::Disk`]) under the Dugdale law:
//! contact on the disk `r <= c`, the cohesive zone `c < r < m` inside the face, `m = a` (the
//! zone reaches the rim, whose gap is below `δc`) or `m < a` where the gap reaches `δc`; with no
//! contact left, the whole face in tension.

use crate::bem::ring::{ContactRegion, RingSystem};
use crate::bem::ring_contact::RingBemSolver;
use crate::error::{Error, Result};
use crate::numerics::roots::find_root;

use super::configuration::{flat_face, whole_face_in_tension, Configuration, Fields};
use super::law::DugdaleLaw;
use super::path::{Beyond, Family, PathPoint};
use super::METHOD;

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
        let fields = Fields::solve(configuration, self.system, &flat_face).ok_or_else(|| {
            Error::Implausible {
                method: METHOD.into(),
                state: format!("contact radius {c}"),
                reason: "singular collocation matrix".into(),
            }
        })?;
        let depth = fields.depth_freeing(true, 0.0, sigma0);
        let equilibrium = fields.at_depth(depth, 0.0, sigma0);
        let rule = self.solver.deflection_rule(self.system.unknowns());
        let gap = fields
            .gap(&equilibrium, m, 0.0, sigma0, &flat_face, rule)
            .unwrap_or(0.0);
        Ok((
            PathPoint::new(
                configuration,
                depth,
                equilibrium.force,
                [0.0, gap / self.law.range()],
            ),
            gap,
        ))
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
}

impl Family for FlatDisk<'_> {
    /// `t = ln(1 - c/a)` from where the zone is a fiftieth of its JKR-limit length `a/λ²` to
    /// [`SMALLEST_CONTACT`].
    fn parameter_range(&self) -> (f64, f64) {
        let first = (0.02 * self.law.zone_length()).clamp(1e-7, 0.5).ln();
        (first, (1.0 - SMALLEST_CONTACT).ln())
    }

    fn at(&self, t: f64) -> Result<PathPoint> {
        self.state(1.0 - t.exp())
    }

    fn beyond_contact(&self, _: &PathPoint, ceased: bool) -> Beyond {
        let whole_face = whole_face_in_tension(self.law, 0.0, 0.0, &flat_face);
        Beyond::exact(whole_face.map(Vec::from).unwrap_or_default(), ceased)
    }
}
