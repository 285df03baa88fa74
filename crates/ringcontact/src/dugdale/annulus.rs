//! An annular contact under the Dugdale law: on the face `b <= r <= a` of a fixed annulus
//! ([`crate::punch::Contact::FixedAnnulus`]), or on a recessed face `r <= a` of gap `h ĝ(r)`
//! ([`crate::punch::Contact::RimAndFreeInner`], `b = 0`, its inner edge always free). Pulled, the
//! contact `[c1, c2]` stays at a face edge while that edge's stress is compressive, else both
//! its edges are free; a cohesive zone runs from each free edge to the face's edge (`[b, c1]`,
//! `[c2, a]`) or to where the gap reaches `δc`. With no contact left, the whole face in tension.

use std::cell::Cell;

use crate::bem::ring::{ContactRegion, RingSystem};
use crate::bem::ring_contact::RingBemSolver;
use crate::error::{Error, Result};
use crate::numerics::roots::{find_root, find_root_with_slope, Root, RootError};
use crate::numerics::tanh_sinh::TanhSinhRule;

use super::configuration::{flat_face, whole_face_in_tension, BandParts, Configuration, Fields};
use super::law::DugdaleLaw;
use super::path::{Beyond, Family, PathPoint};
use super::METHOD;

/// Tolerance of a zone's end and of the contact's centre (units of `a`).
const POSITION_TOLERANCE: f64 = 1e-14;

/// Change of both zone ends between passes below which they have settled (units of `a`; a few
/// times [`POSITION_TOLERANCE`], the passes' own rounding).
const SETTLED_ZONES: f64 = 1e-13;

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

/// Radii probed in a recess for the surface meeting its floor (a negative gap).
const FLOOR_PROBES: usize = 8;

/// Overlap of the surface and the recess's floor (units of `a`) taken as rounding, not contact.
const FLOOR_OVERLAP: f64 = 1e-12;

/// The annular face's states at one node count.
pub(crate) struct AnnularFace<'a> {
    solver: &'a RingBemSolver,
    nodes: usize,
    law: DugdaleLaw,
    /// The face's inner radius `b/a` (0 for a recessed face).
    hole: f64,
    /// The recess's depth `h/a` (0 for a flat face).
    h: f64,
    /// Its shape `ĝ(r)`.
    profile: &'a dyn Fn(f64) -> f64,
    /// Whether the surface in the recess may meet its floor, so that each state is probed.
    probe_floor: bool,
    /// The last contact centre found with both edges free and its coefficient's slope there:
    /// the next search starts from it (the path's states are met in order, and close).
    centre_hint: Cell<Option<(f64, f64)>>,
}

/// One contact's equilibrium with its zones, and the singular coefficient of the edge the depth
/// did not free (positive: compressive; zero where that edge is free too).
struct BandEquilibrium {
    point: PathPoint,
    /// Where the surface in a recess meets its floor, if it does (probed where it may).
    floor_touch: Option<f64>,
    other_coefficient: f64,
}

impl<'a> AnnularFace<'a> {
    /// The fixed annulus's flat face `b <= r <= a` (`hole = b/a`).
    pub fn new(solver: &'a RingBemSolver, nodes: usize, law: DugdaleLaw, hole: f64) -> Self {
        Self {
            solver,
            nodes,
            law,
            hole,
            h: 0.0,
            profile: &flat_face,
            probe_floor: false,
            centre_hint: Cell::new(None),
        }
    }

    /// A recessed face `r <= a` of gap `h ĝ(r)` (`ĝ(1) = 0` at the rim), its surface in the
    /// recess probed for meeting the floor when `probe_floor`.
    pub fn recessed(
        solver: &'a RingBemSolver,
        nodes: usize,
        law: DugdaleLaw,
        h: f64,
        profile: &'a dyn Fn(f64) -> f64,
        probe_floor: bool,
    ) -> Self {
        Self {
            solver,
            nodes,
            law,
            hole: 0.0,
            h,
            profile,
            probe_floor,
            centre_hint: Cell::new(None),
        }
    }

    /// The contact `[c1, c2]` at the depth freeing its inner edge (`free_inner`, or when
    /// `c2 = a`) or else its outer one: its zones' ends found, the depth, the force, and the
    /// other edge's coefficient.
    fn band(&self, c1: f64, c2: f64, free_inner: bool) -> Result<BandEquilibrium> {
        let system = self.solver.system(
            ContactRegion::Band {
                inner: c1,
                outer: c2,
            },
            self.nodes,
        );
        let parts = BandParts::new(&system, self.profile)
            .ok_or_else(|| not_converged(format!("singular collocation matrix on [{c1}, {c2}]")))?;
        let band = Band {
            face: self,
            c1,
            c2,
            free_outer: !free_inner && c2 < 1.0,
            system: &system,
            parts: &parts,
            rule: self.solver.deflection_rule(self.nodes),
        };
        let (z1, z2) = band.settled_zones()?;
        band.equilibrium(z1, z2)
    }

    /// The equilibrium whose contact is `width` wide: held at the face's inner edge while that
    /// edge's stress stays compressive, else at the outer edge while that one's does, else
    /// with both edges free (its centre found where the inner edge's coefficient vanishes too).
    fn state(&self, width: f64) -> Result<PathPoint> {
        let at_hole = self.band(self.hole, self.hole + width, false)?;
        if at_hole.other_coefficient >= 0.0 {
            return Ok(at_hole.point);
        }
        let at_rim = self.band(1.0 - width, 1.0, true)?;
        if at_rim.other_coefficient >= 0.0 {
            return Ok(at_rim.point);
        }
        let half = 0.5 * width;
        let (lo, hi) = (self.hole + half, 1.0 - half);
        let margin = 1e-9 * (hi - lo).max(1e-300);
        let (lo, hi) = (lo + margin, hi - margin);
        let (guess, slope) = match self.centre_hint.get() {
            Some((centre, slope)) if (lo..=hi).contains(&centre) => (centre, Some(slope)),
            _ => (0.5 * (lo + hi), None),
        };
        let (root, band) = band_at_root(
            |centre| self.band(centre - half, centre + half, false),
            (lo, hi),
            guess,
            slope.filter(|s| s.is_finite() && *s != 0.0),
            |e| {
                not_converged(format!(
                    "no contact {width} wide with both edges free on the face [{}, 1]: {e:?}",
                    self.hole
                ))
            },
        )?;
        self.centre_hint.set(Some((root.x, root.slope)));
        Ok(band.point)
    }

    /// The recessed face's equilibrium whose contact's inner edge is `c1`: held at the rim
    /// while the rim's stress stays compressive, else with the outer edge free too (found where
    /// the outer edge's coefficient vanishes with the inner edge freed: freeing the inner edge
    /// keeps the recess's gap positive, so its zone is found without ambiguity).
    pub(super) fn state_from_inner_edge(&self, c1: f64) -> Result<PathPoint> {
        let at_rim = self.band(c1, 1.0, true)?;
        if at_rim.other_coefficient >= 0.0 {
            return clear_of_floor(c1, at_rim);
        }
        // The outer edge nearest the rim where its coefficient vanishes (the states met from
        // the rim-held ones; a root far from the rim is a contact deep in the recess).
        let band_to = |c2: f64| self.band(c1, c2, true);
        let no_state = || Error::OutOfRange {
            method: METHOD.into(),
            reason: format!(
                "no contact from r/a = {c1} holds the rim or lets go of it with both edges free \
                 (the rim's stress is tensile at every outer edge)"
            ),
        };
        let mut step = (1e-3 * self.law.zone_length()).min(0.25 * (1.0 - c1));
        let mut near = 1.0;
        let narrowest = c1 + NARROWEST_CONTACT * (1.0 - c1);
        let far = loop {
            // The last step stops at the narrowest contact rather than stepping past a root.
            let far = (1.0 - step).max(narrowest);
            if band_to(far)?.other_coefficient >= 0.0 {
                break far;
            }
            if far == narrowest {
                return Err(no_state());
            }
            (near, step) = (far, 2.0 * step);
        };
        let (_, band) = band_at_root(
            band_to,
            (far, near.min(1.0 - 1e-12)),
            0.5 * (far + near),
            None,
            |e| {
                not_converged(format!(
                    "the outer edge of the contact from r/a = {c1} with both edges free: {e:?}"
                ))
            },
        )?;
        clear_of_floor(c1, band)
    }

    /// The states with no contact left, the whole face in tension (none where the gap's spread
    /// over the face exceeds `δc`).
    pub(super) fn whole_face(&self) -> Vec<PathPoint> {
        whole_face_in_tension(self.law, self.hole, self.h, self.profile)
            .map(Vec::from)
            .unwrap_or_default()
    }
}

/// The root in `bracket` (from `guess`, with the coefficient's `slope` there if known) of the
/// other edge's coefficient of `band_at(x)`, and the band there: the last one solved when the
/// search ended on it (it does unless it stopped at rounding), else solved again; `failed`
/// names a search that found no root.
fn band_at_root(
    band_at: impl Fn(f64) -> Result<BandEquilibrium>,
    bracket: (f64, f64),
    guess: f64,
    slope: Option<f64>,
    failed: impl FnOnce(RootError) -> Error,
) -> Result<(Root, BandEquilibrium)> {
    let mut last: Option<(f64, BandEquilibrium)> = None;
    let root = find_root_with_slope(
        |x| {
            let band = band_at(x).map_err(|e| e.to_string())?;
            let coefficient = band.other_coefficient;
            last = Some((x, band));
            Ok(coefficient)
        },
        bracket,
        guess,
        slope,
        (POSITION_TOLERANCE, None),
        200,
    )
    .map_err(failed)?;
    let band = match last {
        Some((x, band)) if x == root.x => band,
        _ => band_at(root.x)?,
    };
    Ok((root, band))
}

/// The state `band` of the contact from `c1`, or an [`Error::OutOfRange`] where its surface meets
/// the recess's floor (contact there is a second region, not modelled).
fn clear_of_floor(c1: f64, band: BandEquilibrium) -> Result<PathPoint> {
    match band.floor_touch {
        None => Ok(band.point),
        Some(r) => Err(Error::OutOfRange {
            method: METHOD.into(),
            reason: format!(
                "the surface meets the recess's floor at r/a = {r:.3} (contact from r/a = \
                 {c1:.4}): a second contact region inside the recess is not modelled"
            ),
        }),
    }
}

/// The first of [`FLOOR_PROBES`] radii in the recess `r < c1` where the gap is negative (the
/// surface meets the punch's floor), if any.
fn floor_touch(c1: f64, gap: &dyn Fn(f64) -> Option<f64>) -> Option<f64> {
    (0..FLOOR_PROBES)
        .map(|k| c1 * k as f64 / FLOOR_PROBES as f64)
        .find(|&r| gap(r).is_some_and(|g| g < -FLOOR_OVERLAP))
}

/// One contact `[c1, c2]` of a face on its collocation system, the depth freeing one edge.
struct Band<'b, 'a> {
    face: &'b AnnularFace<'a>,
    c1: f64,
    c2: f64,
    /// Whether the depth frees the outer edge (else the inner).
    free_outer: bool,
    system: &'b RingSystem,
    /// What the band's zones do not change, solved once.
    parts: &'b BandParts,
    rule: &'b TanhSinhRule,
}

impl Band<'_, '_> {
    /// The fields with the loaded region `[z1, z2]` and the depth freeing the chosen edge.
    fn solve(&self, z1: f64, z2: f64) -> Result<(Fields<'_>, f64)> {
        let (c1, c2) = (self.c1, self.c2);
        let configuration = Configuration {
            inner: c1,
            outer: c2,
            zone_inner: z1,
            zone_outer: z2,
        };
        let fields = Fields::solve_on_band(configuration, self.system, self.parts)
            .ok_or_else(|| not_converged(format!("singular collocation matrix on [{c1}, {c2}]")))?;
        let depth = fields.depth_freeing(self.free_outer, self.face.h, self.face.law.tension());
        Ok((fields, depth))
    }

    /// The gap at `r` (0 on the contact, where it closes continuously) with the loaded region
    /// `[z1, z2]`.
    fn gap_at(&self, z1: f64, z2: f64, r: f64) -> Result<f64> {
        let (c1, c2) = (self.c1, self.c2);
        if (c1..=c2).contains(&r) {
            return Ok(0.0);
        }
        let (face, sigma0) = (self.face, self.face.law.tension());
        let (fields, depth) = self.solve(z1, z2)?;
        let equilibrium = fields.at_depth(depth, face.h, sigma0);
        fields
            .gap(&equilibrium, r, face.h, sigma0, face.profile, self.rule)
            .ok_or_else(|| not_converged(format!("no gap at r = {r} off [{c1}, {c2}]")))
    }

    /// The root in `[lo, hi]` of `gap(z) = δc`, a zone's end.
    fn zone_end(&self, lo: f64, hi: f64, gap: &dyn Fn(f64) -> Result<f64>) -> Result<f64> {
        let range = self.face.law.range();
        find_root(
            |z| gap(z).map(|g| g - range).map_err(|e| e.to_string()),
            lo,
            hi,
            0.5 * (lo + hi),
            POSITION_TOLERANCE,
            200,
        )
        .map(|root| root.x)
        .map_err(|e| {
            not_converged(format!(
                "a cohesive zone's end beside [{}, {}]: {e:?}",
                self.c1, self.c2
            ))
        })
    }

    /// On a recess, a zone's end nearest its contact edge, stepping from `edge` toward the face's
    /// edge `towards` until the gap passes `δc` (`towards` where it never does): a zone reaching
    /// further can also hold itself up, the surface lifted into the recess, but it is not met
    /// by pulling.
    fn nearest_zone_end(
        &self,
        edge: f64,
        towards: f64,
        gap: &dyn Fn(f64) -> Result<f64>,
    ) -> Result<f64> {
        let span = (towards - edge).abs();
        let mut step = (0.05 * self.face.law.zone_length()).min(0.5 * span);
        let mut near = edge;
        loop {
            let far = if step >= span {
                towards
            } else {
                edge + (towards - edge).signum() * step
            };
            if gap(far)? >= self.face.law.range() {
                let (lo, hi) = if far < near { (far, near) } else { (near, far) };
                return self.zone_end(lo, hi, gap);
            }
            if far == towards {
                return Ok(towards);
            }
            (near, step) = (far, 2.0 * step);
        }
    }

    /// The inner zone's end with the outer at `z2`.
    fn inner_zone_end(&self, z2: f64) -> Result<f64> {
        let (hole, c1) = (self.face.hole, self.c1);
        let gap = |z: f64| self.gap_at(z, z2, z);
        if self.face.h > 0.0 {
            self.nearest_zone_end(c1, 0.0, &gap)
        } else if c1 <= hole || self.gap_at(hole, z2, hole)? <= self.face.law.range() {
            Ok(hole)
        } else {
            self.zone_end(hole, c1, &gap)
        }
    }

    /// The outer zone's end with the inner at `z1`.
    fn outer_zone_end(&self, z1: f64) -> Result<f64> {
        let c2 = self.c2;
        let gap = |z: f64| self.gap_at(z1, z, z);
        if c2 >= 1.0 {
            Ok(1.0)
        } else if self.face.h > 0.0 {
            self.nearest_zone_end(c2, 1.0, &gap)
        } else if self.gap_at(z1, 1.0, 1.0)? <= self.face.law.range() {
            Ok(1.0)
        } else {
            self.zone_end(c2, 1.0, &gap)
        }
    }

    /// The zones' ends, each solved with the other held, in passes until both settle.
    fn settled_zones(&self) -> Result<(f64, f64)> {
        let (mut z1, mut z2) = (self.face.hole, 1.0);
        // The inner end is a function of the outer one: solved once per outer end met.
        let mut last_inner: Option<(f64, f64)> = None;
        let mut inner_zone_end = |z2: f64| -> Result<f64> {
            match last_inner {
                Some((outer, inner)) if outer == z2 => Ok(inner),
                _ => {
                    let inner = self.inner_zone_end(z2)?;
                    last_inner = Some((z2, inner));
                    Ok(inner)
                }
            }
        };
        if self.face.h > 0.0 {
            z1 = inner_zone_end(z2)?;
        }
        for _ in 0..ZONE_PASSES {
            let inner = inner_zone_end(z2)?;
            let outer = self.outer_zone_end(inner)?;
            let settled =
                (inner - z1).abs() <= SETTLED_ZONES && (outer - z2).abs() <= SETTLED_ZONES;
            (z1, z2) = (inner, outer);
            if settled {
                return Ok((z1, z2));
            }
        }
        Err(not_converged(format!(
            "the cohesive zones beside [{}, {}] did not settle in {ZONE_PASSES} passes",
            self.c1, self.c2
        )))
    }

    /// The equilibrium with the zones `[z1, c1]`, `[c2, z2]`: its point, where its surface meets
    /// a recess's floor, and the coefficient of the edge the depth did not free.
    fn equilibrium(&self, z1: f64, z2: f64) -> Result<BandEquilibrium> {
        let face = self.face;
        let (sigma0, range) = (face.law.tension(), face.law.range());
        let (fields, depth) = self.solve(z1, z2)?;
        let equilibrium = fields.at_depth(depth, face.h, sigma0);
        let gap = |r: f64| fields.gap(&equilibrium, r, face.h, sigma0, face.profile, self.rule);
        let floor_touch = face
            .probe_floor
            .then(|| floor_touch(self.c1, &gap))
            .flatten();
        let edge_gap = |r: f64| gap(r).map(|g| g / range).unwrap_or(0.0);
        let gaps = [
            if self.c1 > face.hole {
                edge_gap(face.hole)
            } else {
                0.0
            },
            if self.c2 < 1.0 { edge_gap(1.0) } else { 0.0 },
        ];
        Ok(BandEquilibrium {
            point: PathPoint::new(fields.configuration(), depth, equilibrium.force, gaps),
            floor_touch,
            other_coefficient: fields.coefficient(&equilibrium, !self.free_outer),
        })
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

    fn beyond_contact(&self, _: &PathPoint, ceased: bool) -> Beyond {
        Beyond::exact(self.whole_face(), ceased)
    }
}
