//! The JKR solution of any punch at one state, chosen by how its contact is bounded: a fixed
//! annulus at its `b/a`, a punch with a rim and a free inner edge or a free band at its work of
//! adhesion `d0/h`.

use serde::Serialize;

use super::{band_jkr, concave, fixed_annulus, BandJkr, ConcaveJkr, FixedAnnulusJkr};
use crate::error::{Error, Result};
use crate::methods::RingBem;
use crate::punch::{Contact, PunchKind};

/// One punch's JKR solution (serialised as the solution it holds).
#[derive(Clone, Debug, Serialize)]
#[serde(untagged)]
pub enum Jkr {
    /// A fixed annulus: the critical states at either edge.
    FixedAnnulus(FixedAnnulusJkr),
    /// A rim and a free inner edge: pull-off under fixed load, fixed grips, from full contact.
    Concave(Box<ConcaveJkr>),
    /// Two free edges: pull-off under fixed load and fixed grips.
    Band(BandJkr),
}

/// The JKR solution of `kind`: at `b/a = eps` for a fixed annulus, at the work of adhesion
/// `d0/h = d0h` (`d0 = sqrt(2π a Δw / E*)`) for a free inner edge or a free band; an error
/// naming the value that is missing or belongs to the other family.
pub fn jkr(solver: &RingBem, kind: &PunchKind, eps: Option<f64>, d0h: Option<f64>) -> Result<Jkr> {
    refuse_other_family(kind, eps, d0h)?;
    let name = kind.name();
    match kind.contact() {
        Contact::Disk => Err(Error::invalid(
            "punch",
            format!(
                "the {name} punch is Kendall's: F_c = -F0, d_c = -d0 (give the {} punch with \
                 its b/a)",
                crate::punch::PunchName::names(Some(Contact::FixedAnnulus), ", ")
            ),
        )),
        Contact::FixedAnnulus => {
            let eps = eps.ok_or_else(|| {
                Error::invalid("eps", format!("is needed: the {name}'s b/a (0 < b/a < 1)"))
            })?;
            fixed_annulus(solver, eps).map(Jkr::FixedAnnulus)
        }
        Contact::RimAndFreeInner | Contact::FreeBand => {
            let s = d0h.ok_or_else(|| {
                Error::invalid(
                    "d0h",
                    format!(
                        "is needed: the {name}'s work of adhesion as d0/h, d0 = sqrt(2 pi a dw / \
                         E*)"
                    ),
                )
            })?;
            if kind.contact() == Contact::FreeBand {
                band_jkr(solver, kind, s).map(Jkr::Band)
            } else {
                concave(solver, kind.clone(), s).map(|r| Jkr::Concave(Box::new(r)))
            }
        }
    }
}

/// An error naming `eps` given for a punch whose contact ratio is found, or `d0h` given for a
/// fixed annulus (whose results are in units of `d0` and `F0` already).
pub fn refuse_other_family(kind: &PunchKind, eps: Option<f64>, d0h: Option<f64>) -> Result<()> {
    let name = kind.name();
    match kind.contact() {
        Contact::FixedAnnulus if d0h.is_some() => Err(Error::invalid(
            "d0h",
            format!(
                "is a concave punch's work of adhesion in units of h; the {name}'s results are \
                 in units of d0 and F0 already"
            ),
        )),
        Contact::RimAndFreeInner | Contact::FreeBand if eps.is_some() => Err(Error::invalid(
            "eps",
            format!(
                "fixes the hole of a fixed annulus; the {name}'s contact ratio is found, not \
                 given (give d0h)"
            ),
        )),
        _ => Ok(()),
    }
}
