//! The face `b <= r <= a` of a fixed annulus ([`crate::punch::Contact::FixedAnnulus`]) under
//! the Dugdale law. Pulled, the contact `[c1, c2]` stays at a face edge while that edge's
//! stress is compressive, else both its edges are free; a cohesive zone runs from each free
//! edge to the face's edge (`[b, c1]`, `[c2, a]`) or to where the gap reaches `δc`. With no
//! contact left, the whole face in tension.

use crate::bem::ring::ContactRegion;
use crate::bem::ring_contact::RingBemSolver;
use crate::error::{Error, Result};
use crate::numerics::roots::find_root;

use super::configuration::{flat_face, whole_face_in_tension, Configuration, Fields};
use super::law::DugdaleLaw;
use super::path::{Family, PathPoint};
use super::METHOD;

/// Tolerance of a zone's end and of the contact's centre (units of `a`).
const POSITION_TOLERANCE: f64 = 1e-14;

/// Passes over the two zone ends (each solved with the other held) before they must agree.
const ZONE_PASSES: usize = 30;

/// Narrowest contact sampled, as a fraction of the face's width.
const NARROWEST_CONTACT: f64 = 1e-3;

fn not_converged(reason: String) -> Error {
    Error::NoConvergence {
        method: METHOD.into(),
        reason,
    }
}

/// The annular face's states at one node count.
pub(crate) struct AnnularFace<'a> {
    solver: &'a RingBemSolver,
    nodes: usize,
    law: DugdaleLaw,
    /// The face's inner radius `b/a`.
    hole: f64,
}

/// One contact's equilibrium with its zones, and the singular coefficient of the edge the depth
/// did not free (positive: compressive; zero where that edge is free too).
struct BandEquilibrium {
    point: PathPoint,
    other_coefficient: f64,
}

impl<'a> AnnularFace<'a> {
    pub fn new(solver: &'a RingBemSolver, nodes: usize, law: DugdaleLaw, hole: f64) -> Self {
        Self {
            solver,
            nodes,
            law,
            hole,
        }
    }

    /// The contact `[c1, c2]`, an edge at the face's edge (`c1 = b` or `c2 = a`) held there
    /// and the depth freeing the other (the outer where both are inside): its zones' ends
    /// found, the depth, the force, and the held (or inner) edge's coefficient.
    fn band(&self, c1: f64, c2: f64) -> Result<BandEquilibrium> {
        let free_outer = c2 < 1.0;
        let system = self.solver.system(
            ContactRegion::Band {
                inner: c1,
                outer: c2,
            },
            self.nodes,
        );
        let rule = self.solver.deflection_rule(self.nodes);
        let (sigma0, range) = (self.law.tension(), self.law.range());
        // Gap at `r` (off the contact) with the loaded region `[z1, z2]`, the depth freeing c2.
        let solve = |z1: f64, z2: f64| -> Result<(Fields, f64)> {
            let configuration = Configuration {
                inner: c1,
                outer: c2,
                zone_inner: z1,
                zone_outer: z2,
            };
            let fields = Fields::solve(configuration, &system, &flat_face).ok_or_else(|| {
                not_converged(format!("singular collocation matrix on [{c1}, {c2}]"))
            })?;
            let depth = fields.depth_freeing(free_outer, 0.0, sigma0);
            Ok((fields, depth))
        };
        let gap_at = |z1: f64, z2: f64, r: f64| -> Result<f64> {
            if (c1..=c2).contains(&r) {
                // The gap closes continuously at the contact's edges.
                return Ok(0.0);
            }
            let (fields, depth) = solve(z1, z2)?;
            let equilibrium = fields.at_depth(depth, 0.0, sigma0);
            fields
                .gap(&equilibrium, r, 0.0, sigma0, &flat_face, rule)
                .ok_or_else(|| not_converged(format!("no gap at r = {r} off [{c1}, {c2}]")))
        };
        let zone_end = |lo: f64, hi: f64, gap: &dyn Fn(f64) -> Result<f64>| -> Result<f64> {
            find_root(
                |z| gap(z).map(|g| g - range).map_err(|e| e.to_string()),
                lo,
                hi,
                0.5 * (lo + hi),
                POSITION_TOLERANCE,
                200,
            )
            .map(|root| root.x)
            .map_err(|e| not_converged(format!("a cohesive zone's end beside [{c1}, {c2}]: {e:?}")))
        };
        let (mut z1, mut z2) = (self.hole, 1.0);
        for _ in 0..ZONE_PASSES {
            let inner = if c1 <= self.hole || gap_at(self.hole, z2, self.hole)? <= range {
                self.hole
            } else {
                zone_end(self.hole, c1, &|z| gap_at(z, z2, z))?
            };
            let outer = if c2 >= 1.0 || gap_at(inner, 1.0, 1.0)? <= range {
                1.0
            } else {
                zone_end(c2, 1.0, &|z| gap_at(inner, z, z))?
            };
            let settled = (inner - z1).abs() <= POSITION_TOLERANCE
                && (outer - z2).abs() <= POSITION_TOLERANCE;
            (z1, z2) = (inner, outer);
            if settled {
                let (fields, depth) = solve(z1, z2)?;
                let equilibrium = fields.at_depth(depth, 0.0, sigma0);
                let edge_gap = |r: f64| {
                    fields
                        .gap(&equilibrium, r, 0.0, sigma0, &flat_face, rule)
                        .map(|g| g / range)
                        .unwrap_or(0.0)
                };
                let gaps = [
                    if c1 > self.hole {
                        edge_gap(self.hole)
                    } else {
                        0.0
                    },
                    if free_outer { edge_gap(1.0) } else { 0.0 },
                ];
                let point = PathPoint::new(fields.configuration(), depth, equilibrium.force, gaps);
                return Ok(BandEquilibrium {
                    point,
                    other_coefficient: fields.coefficient(&equilibrium, !free_outer),
                });
            }
        }
        Err(not_converged(format!(
            "the cohesive zones beside [{c1}, {c2}] did not settle in {ZONE_PASSES} passes"
        )))
    }

    /// The equilibrium whose contact is `width` wide: held at the face's inner edge while that
    /// edge's stress stays compressive, else at the outer edge while that one's does, else
    /// with both edges free (its centre found where the inner edge's coefficient vanishes too).
    fn state(&self, width: f64) -> Result<PathPoint> {
        let at_hole = self.band(self.hole, self.hole + width)?;
        if at_hole.other_coefficient >= 0.0 {
            return Ok(at_hole.point);
        }
        let at_rim = self.band(1.0 - width, 1.0)?;
        if at_rim.other_coefficient >= 0.0 {
            return Ok(at_rim.point);
        }
        let half = 0.5 * width;
        let (lo, hi) = (self.hole + half, 1.0 - half);
        let margin = 1e-9 * (hi - lo).max(1e-300);
        let root = find_root(
            |centre| {
                self.band(centre - half, centre + half)
                    .map(|b| b.other_coefficient)
                    .map_err(|e| e.to_string())
            },
            lo + margin,
            hi - margin,
            0.5 * (lo + hi),
            POSITION_TOLERANCE,
            200,
        )
        .map_err(|e| {
            not_converged(format!(
                "no contact {width} wide with both edges free on the face [{}, 1]: {e:?}",
                self.hole
            ))
        })?;
        Ok(self.band(root.x - half, root.x + half)?.point)
    }
}

impl Family for AnnularFace<'_> {
    /// `t = ln(1 - width/(a - b))`, the zones' share of the face, from a fiftieth of the
    /// JKR-limit zone length `a/λ²` to all but [`NARROWEST_CONTACT`].
    fn parameter_range(&self) -> (f64, f64) {
        let face = 1.0 - self.hole;
        let first = (0.02 * self.law.zone_length() / face).clamp(1e-7, 0.5).ln();
        (first, (1.0 - NARROWEST_CONTACT).ln())
    }

    fn at(&self, t: f64) -> Result<PathPoint> {
        self.state((1.0 - self.hole) * (1.0 - t.exp()))
    }

    fn beyond_contact(&self) -> Vec<PathPoint> {
        whole_face_in_tension(self.law, self.hole)
            .map(Vec::from)
            .unwrap_or_default()
    }
}
