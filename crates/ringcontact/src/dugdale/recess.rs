//! A recessed face `r <= a` of gap `h ĝ(r)` ([`crate::punch::Contact::RimAndFreeInner`]) under
//! the Dugdale law: the annular contact `[c1, c2]` of [`super::annulus`] with the inner edge
//! always free and a cohesive zone running from it into the recess.
//!
//! **Loading history** (`verify jkr`'s annular route). The path runs from `c1 = 10⁻³ a` to a
//! ring [`NARROWEST_CONTACT`] wide, or to where the ring vanishes, and on past the contact, the
//! surface held by its zone alone ([`SuspendedStates`]). Touching at the rim, the contact jumps in; pressing grows it
//! inward while the held quantity rises, up to its first maximum (pressed past it, the hole
//! snaps shut: at finite range a hole shallower than `δc` is held in tension throughout, close
//! to full contact, a regime the annular route does not enter). Pulled from there, the
//! pull-off is the lowest held value that follows.

use super::annulus::AnnularFace;
use super::path::{Beyond, Family, PathPoint, BEYOND_CONTACT};
use super::suspended::{continues, SuspendedStates};
use crate::error::Result;

/// Inner edge `c1/a` of the widest contact sampled (the hole about to close).
const WIDEST_HOLE: f64 = 1e-3;

/// Width of the narrowest contact sampled, in units of `a`.
const NARROWEST_CONTACT: f64 = 1e-4;

/// The recessed face's states at one node count, parameterised by `t = logit(c1)`, `c1` the
/// contact's inner edge (its outer edge at the rim or, once the rim lets go, found from `c1`);
/// past the contact, the states with no contact left ([`SuspendedStates`]).
pub(crate) struct RecessedFace<'a> {
    face: AnnularFace<'a>,
    suspended: SuspendedStates<'a>,
}

impl<'a> RecessedFace<'a> {
    /// The states of `face` (built by [`AnnularFace::recessed`]) and, past its contact, of
    /// `suspended` (the same face).
    pub fn new(face: AnnularFace<'a>, suspended: SuspendedStates<'a>) -> Self {
        Self { face, suspended }
    }
}

/// `ln(x / (1 - x))`.
fn logit(x: f64) -> f64 {
    (x / (1.0 - x)).ln()
}

impl Family for RecessedFace<'_> {
    fn parameter_range(&self) -> (f64, f64) {
        (logit(WIDEST_HOLE), logit(1.0 - NARROWEST_CONTACT))
    }

    fn at(&self, t: f64) -> Result<PathPoint> {
        if t >= BEYOND_CONTACT {
            return self.suspended.at(t);
        }
        self.face.state_from_inner_edge(1.0 / (1.0 + (-t).exp()))
    }

    fn pressed_from_rim(&self) -> bool {
        true
    }

    /// The whole face in tension, where its gap's spread is within `δc` (and, where the
    /// contact's states ceased, it touches the punch within their last contact), then the zone
    /// alone shrinking to the rim; else the zone alone from where the contact vanishes.
    fn beyond_contact(&self, last: &PathPoint, ceased: bool) -> Beyond {
        let whole_face = self.face.whole_face();
        let joins = |first: &PathPoint| !ceased || continues(last, first.configuration.inner);
        if !whole_face.first().is_some_and(joins) {
            return self.suspended.beyond(last, false);
        }
        let shrinking = self.suspended.beyond(last, true);
        if shrinking.states.is_empty() {
            return Beyond::exact(whole_face, false);
        }
        // The whole face's last state is the shrinking zone's first.
        let mut states = vec![(f64::INFINITY, whole_face[0])];
        states.extend(shrinking.states);
        Beyond {
            states,
            cut_short: shrinking.cut_short,
        }
    }

    fn beyond_step(&self) -> f64 {
        self.suspended.step()
    }
}
