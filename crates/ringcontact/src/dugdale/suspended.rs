//! A recessed face's states with no contact left: the surface held by its cohesive zone alone.
//!
//! The zone `[z1, a]` carries the tension `σ0` and nothing else loads the surface, so a state is
//! closed form ([`super::uniform_load`]): the gap `g(r) = h ĝ(r) - σ0 U(r) - d`, `U` the
//! deflection of a unit pressure on `[z1, a]`, the depth set by the zone's end, `g(z1) = δc`,
//! the force `-π σ0 (a² - z1²)`. A state holds where `0 < g <= δc` on the zone and `g >= δc`
//! inside its end. Pulled on from where the contact's states end (the least gap reaching 0), the
//! zone shrinks toward the rim and the force to zero.

use std::f64::consts::PI;

use crate::error::{Error, Result};

use super::configuration::{least_between, Configuration};
use super::law::DugdaleLaw;
use super::path::{Beyond, PathPoint, BEYOND_CONTACT};
use super::uniform_load::annulus_deflection;
use super::METHOD;

/// States sampled from a whole-face zone to the last.
const SAMPLES: usize = 60;

/// `ln(a / (a - z1))` of the last zone sampled, `z1 = a - 10⁻¹⁰ a`: a punch held in grips
/// comes away where the depth is least, which can be at a zone a millionth of `a` long (the
/// zone's own deflection, logarithmic in its length, outgrowing the recess's slope).
const LAST: f64 = 23.025_850_929_940_457;

/// Relative rounding of a gap compared with `δc` at the zone's end, where it equals `δc`.
const GAP_ROUNDING: f64 = 1e-9;

/// Width in `ln(a / (a - z1))` below which the zone's end where the contact vanishes is found.
const JUNCTION_WIDTH: f64 = 1e-13;

/// Where the least gap on a zone is located (units of `a`): its value is then exact to far
/// below the gap's rounding check.
const LEAST_GAP_WIDTH: f64 = 1e-9;

/// Where the largest gap on a zone, or the least inside its end, is located (units of `a`):
/// they are compared with `δc` only.
const CHECK_WIDTH: f64 = 1e-6;

/// What the zone `[z1, a]` alone makes of the surface.
enum Suspension {
    /// A state: the zone holds the surface clear of the punch.
    Held(PathPoint),
    /// The surface reaches the punch at `at` (the least gap `<= 0`): a contact, not a state of
    /// the zone alone.
    Touching { at: f64 },
    /// No state, for the reason given.
    Other(String),
}

/// The recessed face `r <= a` of gap `h ĝ(r)` with no contact left.
pub(crate) struct SuspendedStates<'a> {
    law: DugdaleLaw,
    h: f64,
    profile: &'a dyn Fn(f64) -> f64,
}

/// `z1 = a - a e^{-u}`, the zone's end at the suspended states' parameter `u`.
fn zone_end(u: f64) -> f64 {
    -(-u).exp_m1()
}

impl<'a> SuspendedStates<'a> {
    /// The states of the face of depth `h/a` and shape `profile` (`ĝ`) under `law`.
    pub fn new(law: DugdaleLaw, h: f64, profile: &'a dyn Fn(f64) -> f64) -> Self {
        Self { law, h, profile }
    }

    /// The gap at `r` with the zone `[z1, a]`, its end's gap `δc`.
    fn gap(&self, z1: f64, r: f64) -> f64 {
        let offset = |r: f64| {
            self.h * (self.profile)(r) - self.law.tension() * annulus_deflection(z1, 1.0, r)
        };
        offset(r) - offset(z1) + self.law.range()
    }

    /// Where the gap is least on the zone `[z1, a]`, and that gap.
    fn least_gap(&self, z1: f64) -> (f64, f64) {
        let gap = |r: f64| self.gap(z1, r);
        let at = least_between(&gap, z1, 1.0, LEAST_GAP_WIDTH);
        (at, gap(at))
    }

    /// What the zone `[z1, a]` makes of the surface.
    fn suspension(&self, z1: f64) -> Suspension {
        let range = self.law.range();
        let gap = |r: f64| self.gap(z1, r);
        let (at, least) = self.least_gap(z1);
        if least <= 0.0 {
            return Suspension::Touching { at };
        }
        let most = gap(least_between(&|r| -gap(r), z1, 1.0, CHECK_WIDTH));
        if most > range * (1.0 + GAP_ROUNDING) {
            return Suspension::Other(format!(
                "the gap passes δc inside the zone [{z1:.6}, 1] a: a zone ending short of the \
                 rim is not modelled"
            ));
        }
        if z1 > 0.0 && gap(least_between(&gap, 0.0, z1, CHECK_WIDTH)) < range * (1.0 - GAP_ROUNDING)
        {
            return Suspension::Other(format!(
                "the gap inside the zone's end r/a = {z1:.6} is below δc: the zone would reach \
                 further in"
            ));
        }
        let depth = self.h * (self.profile)(z1)
            - self.law.tension() * annulus_deflection(z1, 1.0, z1)
            - range;
        let configuration = Configuration {
            inner: at,
            outer: at,
            zone_inner: z1,
            zone_outer: 1.0,
        };
        let force = -PI * self.law.tension() * (1.0 - z1 * z1);
        let edge_gaps = [gap(0.0) / range, gap(1.0) / range];
        Suspension::Held(PathPoint::new(configuration, depth, force, edge_gaps))
    }

    /// The state at the parameter `t = BEYOND_CONTACT + ln(a / (a - z1))`; an
    /// [`Error::OutOfRange`] where the zone alone holds no state.
    pub fn at(&self, t: f64) -> Result<PathPoint> {
        let z1 = zone_end(t - BEYOND_CONTACT);
        match self.suspension(z1) {
            Suspension::Held(point) => Ok(point),
            Suspension::Touching { at, .. } => Err(Error::OutOfRange {
                method: METHOD.into(),
                reason: format!(
                    "with the zone from r/a = {z1:.6} alone the surface reaches the punch at \
                     r/a = {at:.6}"
                ),
            }),
            Suspension::Other(reason) => Err(Error::OutOfRange {
                method: METHOD.into(),
                reason,
            }),
        }
    }

    /// Spacing of the sampled states in their parameter `ln(a / (a - z1))`.
    pub fn step(&self) -> f64 {
        LAST / (SAMPLES - 1) as f64
    }

    /// The states met as the punch is pulled on from `last`, the contact's last state: from
    /// where the contact vanishes (the least gap reaching 0 within `last`'s contact) toward the
    /// rim; with `from_whole_face`, from the whole face in tension instead (its last state, when
    /// it has its largest gap at the centre). None where they do not join.
    pub fn beyond(&self, last: &PathPoint, from_whole_face: bool) -> Beyond {
        let step = self.step();
        let grid: Vec<(f64, Suspension)> = (0..SAMPLES)
            .map(|k| {
                let u = step * k as f64;
                (u, self.suspension(zone_end(u)))
            })
            .collect();
        let junction = if from_whole_face {
            matches!(grid[0].1, Suspension::Held(_)).then_some(0)
        } else {
            grid.windows(2)
                .position(|pair| {
                    matches!(
                        (&pair[0].1, &pair[1].1),
                        (Suspension::Touching { .. }, Suspension::Held(_))
                    )
                })
                .map(|k| k + 1)
        };
        let Some(first) = junction else {
            return Beyond::none();
        };
        let mut states = Vec::new();
        if first > 0 {
            match self.junction(grid[first - 1].0, grid[first].0, last) {
                Some(state) => states.push(state),
                None => return Beyond::none(),
            }
        }
        let mut cut_short = None;
        for (u, suspension) in grid.into_iter().skip(first) {
            match suspension {
                Suspension::Held(point) => states.push((BEYOND_CONTACT + u, point)),
                Suspension::Touching { at, .. } => {
                    cut_short = Some(format!(
                        "the zone-only states end at r/a = {:.6}: the surface reaches the punch \
                         again at r/a = {at:.6}",
                        zone_end(u)
                    ));
                    break;
                }
                Suspension::Other(reason) => {
                    cut_short = Some(format!("the zone-only states end ({reason})"));
                    break;
                }
            }
        }
        if cut_short.is_none() {
            states.push((f64::INFINITY, self.separated()));
        }
        Beyond { states, cut_short }
    }

    /// The limit of a zone shrinking to the rim: no load, the rim's gap `δc`, so `d = -δc` and
    /// `F = 0` (the punch off the surface).
    fn separated(&self) -> PathPoint {
        let range = self.law.range();
        let configuration = Configuration {
            inner: 1.0,
            outer: 1.0,
            zone_inner: 1.0,
            zone_outer: 1.0,
        };
        let centre_gap = self.h * (self.profile)(0.0) + range;
        PathPoint::new(configuration, -range, 0.0, [centre_gap / range, 1.0])
    }

    /// The state where the contact vanishes, between `touching` (the surface reaching the
    /// punch) and `held` (clear of it), if it continues `last`: its touching point lies within
    /// `last`'s contact, widened by its width.
    fn junction(&self, touching: f64, held: f64, last: &PathPoint) -> Option<(f64, PathPoint)> {
        let (mut lo, mut hi) = (touching, held);
        let mut touch_point = None;
        while hi - lo > JUNCTION_WIDTH {
            let middle = 0.5 * (lo + hi);
            let (at, least) = self.least_gap(zone_end(middle));
            if least <= 0.0 {
                touch_point = Some(at);
                lo = middle;
            } else {
                hi = middle;
            }
        }
        let Suspension::Held(point) = self.suspension(zone_end(hi)) else {
            return None;
        };
        let touch = touch_point.unwrap_or(point.configuration.inner);
        continues(last, touch).then_some((BEYOND_CONTACT + hi, point))
    }
}

/// Whether a state touching the punch at `touch` alone (its contact vanishing there) continues
/// the contact's state `last`: `touch` lies within `last`'s contact widened by its width.
pub(crate) fn continues(last: &PathPoint, touch: f64) -> bool {
    let contact = last.configuration;
    let width = contact.outer - contact.inner;
    (contact.inner - width..=contact.outer + width).contains(&touch)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bem::ring_contact::RingBemSolver;
    use crate::dugdale::annulus::AnnularFace;

    /// Where the contact's states on a paraboloidal recess (`ĝ = 1 - r²`, `h = d0`, `λ = 2`)
    /// end, the ring BEM's narrowest contact and the closed-form state of the zone alone meet:
    /// two independent constructions of the same state (one solves the contact's pressure by
    /// collocation, the other has no contact) agree in force and depth as the contact vanishes.
    #[test]
    fn the_zone_alone_continues_the_vanishing_contact() {
        let law = DugdaleLaw::new(2.0).unwrap();
        let profile = |r: f64| 1.0 - r * r;
        let solver = RingBemSolver::new();
        let face = AnnularFace::recessed(&solver, 64, law, 1.0, &profile, false);
        let holds = |c1: f64| face.state_from_inner_edge(c1).ok();
        // The contact's states hold at c1 = 0.99 and have ended by 1 - 1e-4.
        let (mut lo, mut hi) = (0.99, 1.0 - 1e-4);
        assert!(holds(lo).is_some() && holds(hi).is_none());
        for _ in 0..30 {
            let middle = 0.5 * (lo + hi);
            if holds(middle).is_some() {
                lo = middle;
            } else {
                hi = middle;
            }
        }
        let last = holds(lo).unwrap();
        let width = last.configuration.outer - last.configuration.inner;
        let beyond = SuspendedStates::new(law, 1.0, &profile).beyond(&last, false);
        let (_, junction) = beyond.states.first().expect("a state of the zone alone");
        let (force, depth) = (junction.force - last.force, junction.depth - last.depth);
        println!("contact width {width:.2e}: force {force:.2e}, depth {depth:.2e} apart");
        // The narrowest contact sampled is a thousandth of the distance to the rim.
        assert!(width < 1e-5, "{last:?}");
        assert!(
            force.abs() < 1e-7 && depth.abs() < 1e-7,
            "{last:?} {junction:?}"
        );
    }
}
