//! Punch shapes and their gap functions.
//!
//! The gap `g(r)` is the distance from the punch face up to the plane of the sharp rim, for
//! `0 <= r <= a` (see `docs/conventions.md`). Non-penetration reads `w(r) >= d - g(r)`.
//!
//! | shape | gap `g(r)` | contact |
//! |---|---|---|
//! | flat circular | `0` | `[0, a]` |
//! | flat annular | hole for `r < b`, `0` on `[b, a]` | `[b, a]`, fixed |
//! | conical concave | `h (1 - r/a)` | `[b(d), a]` |
//! | spherical (parabolic) concave | `h (1 - r²/a²)` | `[b(d), a]` |
//! | power-law concave, exponent `n > 0` | `h (1 - (r/a)^n)` | `[b(d), a]` |
//! | torus (parabolic section), tube radius `ρ` | `(r - a)²/(2ρ) = h (1 - r/a)²`, `h = a²/(2ρ)` | `[b(d), c(d)]` |
//! | table (a measured profile) | `h ĝ(r/a)`, `ĝ` interpolated from `(r/a, g/h)` points | `[b(d), a]` |
//!
//! Every concave punch has a sharp rim at `r = a` (fixed edge, pressure singular) and a free
//! inner edge `b` found by the solution (pressure zero there without adhesion). The power law
//! holds the cone (`n = 1`) and the sphere (`n = 2`) as special cases; `cone` and `sphere` keep
//! their own names and evaluate the same gap. The torus has no rim: both edges of its contact
//! are free, and its gap is defined on both sides of the ring radius `a`. Written as
//! `h (1 - r/a)²` it is one dimensionless shape for every tube radius (the tube radius only sets
//! the depth scale `h`), so it shares the concave punches' `γ1 = d/h` and `γ2 = F/(2 E* h a)`.
//! The table punch is a concave punch whose profile is read from a file ([`table`]).
//!
//! Each shape is one [`Profile`] implementation in its own file; a [`PunchKind`] is a shared
//! handle to one, and this file is the registry that builds the built-in shapes from their
//! names and parameters. A user's own profile is a type implementing [`Profile`], handed to
//! the solvers as [`PunchKind::new`].

mod cone;
mod flat;
mod flat_annulus;
pub mod mdr;
mod power;
pub mod power_law;
mod profile;
mod references;
mod sphere;
pub mod table;
mod torus;

use std::hash::{Hash, Hasher};
use std::path::Path;
use std::sync::Arc;

pub use cone::Cone;
pub use flat::Flat;
pub use flat_annulus::{collins_series, narrow_ring, FlatAnnulus};
pub use power::{Exponent, Power};
pub use profile::{Contact, PiecewiseProfile, Profile, Summary};
pub use references::{Quantity, Reference, ReferenceKind, ReferenceValue};
pub use sphere::Sphere;
pub use table::TableProfile;
pub use torus::Torus;

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

/// The paper's fit a concave profile of rim slope `s = -a g'(a)/h` starts its inverse search
/// from, and the value `target` becomes for it: for `s >= 1.5` the parabolic gap's fit at
/// `2 target / s` (`γ ≈ (s/2) γ_sphere`, exact as the contact narrows toward the rim), else the
/// linear gap's, unscaled. The parabolic gap's fit unscaled started a steep-walled profile inside
/// its hole, where `γ1` is not monotone.
pub fn starting_fit(rim_slope: f64, target: f64) -> (f64, fn(usize, f64) -> f64) {
    if rim_slope < 1.5 {
        (target, cone::paper_fit)
    } else {
        (2.0 * target / rim_slope, sphere::paper_fit)
    }
}

/// The names of the built-in punch shapes, as written on the command line (`--punch`), in scene
/// files (`punch.shape`) and in JSON (`"punch"`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PunchName {
    Flat,
    FlatAnnulus,
    Cone,
    Sphere,
    Power,
    Torus,
    Table,
}

impl crate::choice::Choice for PunchName {
    const ALL: &'static [PunchName] = &PunchName::ALL;

    fn name(self) -> &'static str {
        self.as_str()
    }

    fn description(self) -> &'static str {
        self.summary().description
    }
}

impl PunchName {
    /// Every built-in shape, in the order the command line lists them.
    pub const ALL: [PunchName; 7] = [
        PunchName::Flat,
        PunchName::FlatAnnulus,
        PunchName::Cone,
        PunchName::Sphere,
        PunchName::Power,
        PunchName::Torus,
        PunchName::Table,
    ];

    /// Name used on the command line and in JSON.
    pub fn as_str(self) -> &'static str {
        match self {
            PunchName::Flat => "flat",
            PunchName::FlatAnnulus => "flat-annulus",
            PunchName::Cone => "cone",
            PunchName::Sphere => "sphere",
            PunchName::Power => "power",
            PunchName::Torus => "torus",
            PunchName::Table => "table",
        }
    }

    /// How this built-in shape's contact is bounded ([`Profile::contact`]), before its
    /// parameters are known.
    pub fn contact(self) -> Contact {
        match self {
            PunchName::Flat => Flat.contact(),
            PunchName::FlatAnnulus => FlatAnnulus.contact(),
            PunchName::Torus => Torus.contact(),
            PunchName::Cone | PunchName::Sphere | PunchName::Power | PunchName::Table => {
                Contact::RimAndFreeInner
            }
        }
    }

    /// The built-in names whose contact is `contact`, joined by `separator` (`cone, sphere`);
    /// every built-in name for `None`.
    pub fn names(contact: Option<Contact>, separator: &str) -> String {
        PunchName::ALL
            .iter()
            .filter(|name| contact.is_none_or(|c| name.contact() == c))
            .map(|name| name.as_str())
            .collect::<Vec<_>>()
            .join(separator)
    }

    /// What `verify references` says of this shape: its flags, gap, edges and closed forms.
    pub fn summary(self) -> Summary {
        match self {
            PunchName::Flat => flat::SUMMARY,
            PunchName::FlatAnnulus => flat_annulus::SUMMARY,
            PunchName::Cone => cone::SUMMARY,
            PunchName::Sphere => sphere::SUMMARY,
            PunchName::Power => power::SUMMARY,
            PunchName::Torus => torus::SUMMARY,
            PunchName::Table => table::SUMMARY,
        }
    }

    /// The built-in shape of this name (`flat-annulus`), if one has it.
    pub fn parse(name: &str) -> Option<PunchName> {
        PunchName::ALL.into_iter().find(|n| n.as_str() == name)
    }

    /// The punch of this name; `exponent` is the power law's `n` and is refused for every other
    /// shape; the table punch needs [`with_parameters`](Self::with_parameters).
    pub fn with_exponent(self, exponent: Option<f64>) -> Result<PunchKind> {
        self.with_parameters(exponent, None)
    }

    /// The punch of this name with its parameters: `exponent` the power law's `n`, `profile`
    /// the table punch's file; each refused for every other shape.
    pub fn with_parameters(
        self,
        exponent: Option<f64>,
        profile: Option<&Path>,
    ) -> Result<PunchKind> {
        match (self, profile) {
            (PunchName::Table, Some(path)) if exponent.is_none() => {
                return Ok(PunchKind::new(TableProfile::load(path)?));
            }
            (PunchName::Table, None) => {
                return Err(Error::InvalidScene {
                    field: "profile".into(),
                    rule: "the table punch needs its profile, a CSV file of (r/a, g/h) points \
                           (--profile FILE, or punch.profile in a scene file)"
                        .into(),
                })
            }
            (PunchName::Table, Some(_)) => {}
            (_, Some(_)) => {
                return Err(Error::InvalidScene {
                    field: "profile".into(),
                    rule: format!("applies only to shape = table, not {}", self.as_str()),
                })
            }
            (_, None) => {}
        }
        match (self, exponent) {
            (PunchName::Power, Some(n)) => Ok(PunchKind::power(Exponent::new(n)?)),
            (PunchName::Power, None) => Err(Error::InvalidScene {
                field: "exponent".into(),
                rule: "the power-law punch needs its exponent n > 0 (--exponent N, or \
                          punch.exponent in a scene file); n = 1 is the cone, n = 2 the sphere"
                    .into(),
            }),
            (_, Some(_)) => Err(Error::InvalidScene {
                field: "exponent".into(),
                rule: format!(
                    "applies only to shape = power, not {} (the cone is n = 1 and the sphere \
                     n = 2 by definition)",
                    self.as_str()
                ),
            }),
            (PunchName::Flat, None) => Ok(PunchKind::FLAT),
            (PunchName::FlatAnnulus, None) => Ok(PunchKind::FLAT_ANNULUS),
            (PunchName::Cone, None) => Ok(PunchKind::CONE),
            (PunchName::Sphere, None) => Ok(PunchKind::SPHERE),
            (PunchName::Torus, None) => Ok(PunchKind::TORUS),
            (PunchName::Table, None) => {
                unreachable!("the table returned above")
            }
        }
    }
}

impl std::fmt::Display for PunchName {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// A punch shape with its dimensionless parameters: a shared handle to its [`Profile`], which
/// it dereferences to. Compared and hashed by the profile's [`label`](Profile::label). Written
/// in JSON as the keys `punch` (its name), for the power law `exponent`, for the table
/// `profile_file` and `profile_sha256`; structs holding one flatten it.
#[derive(Clone)]
pub struct PunchKind(Shared);

#[derive(Clone)]
enum Shared {
    Builtin(&'static dyn Profile),
    Owned(Arc<dyn Profile>),
}

impl PunchKind {
    /// Flat circular punch (Boussinesq).
    pub const FLAT: PunchKind = PunchKind(Shared::Builtin(&Flat));
    /// Flat annular punch (its inner radius is the [`Punch`]'s).
    pub const FLAT_ANNULUS: PunchKind = PunchKind(Shared::Builtin(&FlatAnnulus));
    /// Conical concave punch, gap `h (1 - r/a)`.
    pub const CONE: PunchKind = PunchKind(Shared::Builtin(&Cone));
    /// Spherical concave punch, gap `h (1 - r²/a²)`.
    pub const SPHERE: PunchKind = PunchKind(Shared::Builtin(&Sphere));
    /// Torus, gap `h (1 - r/a)²`.
    pub const TORUS: PunchKind = PunchKind(Shared::Builtin(&Torus));

    /// The punch of any profile, a built-in one or a user's own.
    pub fn new(profile: impl Profile + 'static) -> PunchKind {
        PunchKind(Shared::Owned(Arc::new(profile)))
    }

    /// The power-law concave punch of exponent `n`.
    pub fn power(n: Exponent) -> PunchKind {
        PunchKind::new(Power(n))
    }

    /// The profile this punch is.
    pub fn profile(&self) -> &(dyn Profile + 'static) {
        match &self.0 {
            Shared::Builtin(p) => *p,
            Shared::Owned(p) => p.as_ref(),
        }
    }

    /// The built-in shape's name ([`PunchName`]), if the punch is built in.
    pub fn shape_name(&self) -> Option<PunchName> {
        self.profile().builtin()
    }

    /// The power law's exponent `n` as a parameter (`None` for the other shapes, even the cone
    /// and sphere).
    pub fn exponent(&self) -> Option<f64> {
        self.exponent_parameter()
    }

    /// Dimensionless gap `g(r)/h` at `rho = r/a` ([`Profile::gap`]).
    pub fn gap_shape(&self, rho: f64) -> f64 {
        self.gap(rho)
    }

    /// Whether the inner contact radius is found by the solver, with the depth scale `h` and
    /// the functions `γ1 = d/h`, `γ2 = F/(2 E* h a)`: the concave punches and the torus.
    pub fn is_concave(&self) -> bool {
        matches!(self.contact(), Contact::RimAndFreeInner | Contact::FreeBand)
    }

    /// Whether the contact's outer edge is a sharp rim at `r = a` (every punch but a free band).
    pub fn has_rim(&self) -> bool {
        self.contact() != Contact::FreeBand
    }

    /// Whether the contact is a fixed annulus whose inner radius is a parameter.
    pub fn has_fixed_hole(&self) -> bool {
        self.contact() == Contact::FixedAnnulus
    }

    /// Whether both contact edges are free (a band around the ring radius).
    pub fn is_free_band(&self) -> bool {
        self.contact() == Contact::FreeBand
    }

    /// The built-in punches whose contact is `contact` and that take no parameter (every
    /// shape but the power law and the table), in the command line's order.
    pub fn built_in(contact: Contact) -> Vec<PunchKind> {
        PunchName::ALL
            .into_iter()
            .filter(|name| name.contact() == contact)
            .filter_map(|name| name.with_parameters(None, None).ok())
            .collect()
    }

    /// Every built-in punch that takes no parameter, in the command line's order.
    pub fn every_built_in() -> Vec<PunchKind> {
        PunchName::ALL
            .into_iter()
            .filter_map(|name| name.with_parameters(None, None).ok())
            .collect()
    }

    /// The built-in punch of a [`label`](Profile::label) (`cone`, `power-n2.5`), if it names
    /// one; a table's label names its file's content, which only that file gives back.
    pub fn from_label(label: &str) -> Option<PunchKind> {
        if let Some(n) = label.strip_prefix("power-n") {
            return Exponent::new(n.parse().ok()?).ok().map(PunchKind::power);
        }
        PunchName::parse(label)?.with_exponent(None).ok()
    }

    /// The exponent `n` of the power law `h (1 - (r/a)^n)` the gap is: 1 for the cone, 2 for
    /// the sphere, `n` for the power law; `None` otherwise.
    pub fn concave_exponent(&self) -> Option<f64> {
        self.power_law_exponent()
    }

    /// Whether the concave profile is flat at the axis ([`Profile::smooth_at_axis`]).
    pub fn profile_smooth_at_axis(&self) -> bool {
        self.smooth_at_axis()
    }
}

impl std::ops::Deref for PunchKind {
    type Target = dyn Profile;
    fn deref(&self) -> &Self::Target {
        self.profile()
    }
}

impl std::fmt::Debug for PunchKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.label())
    }
}

impl std::fmt::Display for PunchKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.describe())
    }
}

impl PartialEq for PunchKind {
    fn eq(&self, other: &Self) -> bool {
        self.name() == other.name() && self.label() == other.label()
    }
}

impl Eq for PunchKind {}

impl Hash for PunchKind {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.label().hash(state);
    }
}

impl Serialize for PunchKind {
    fn serialize<S: serde::Serializer>(
        &self,
        serializer: S,
    ) -> std::result::Result<S::Ok, S::Error> {
        self.record().serialize(serializer)
    }
}

impl<'de> Deserialize<'de> for PunchKind {
    fn deserialize<D: serde::Deserializer<'de>>(
        deserializer: D,
    ) -> std::result::Result<Self, D::Error> {
        let record = PunchRecord::deserialize(deserializer)?;
        PunchKind::try_from(record).map_err(serde::de::Error::custom)
    }
}

/// How a [`PunchKind`] is written in JSON: its name and parameters.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct PunchRecord {
    /// The shape's name.
    pub punch: String,
    /// The power law's `n`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub exponent: Option<f64>,
    /// The table's file, as named.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profile_file: Option<String>,
    /// The SHA-256 of the table's file, hex.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profile_sha256: Option<String>,
}

impl PunchRecord {
    /// The record of a shape without parameters.
    pub fn named(name: &str) -> Self {
        PunchRecord {
            punch: name.to_string(),
            exponent: None,
            profile_file: None,
            profile_sha256: None,
        }
    }
}

impl TryFrom<PunchRecord> for PunchKind {
    type Error = Error;
    fn try_from(record: PunchRecord) -> Result<Self> {
        let name = PunchName::parse(&record.punch).ok_or_else(|| {
            Error::invalid(
                "punch",
                format!(
                    "`{}` is not a built-in punch (flat, flat-annulus, cone, sphere, power, \
                     torus, table); a profile of your own is given from Rust",
                    record.punch
                ),
            )
        })?;
        let kind = name.with_parameters(
            record.exponent,
            record.profile_file.as_deref().map(Path::new),
        )?;
        let now = kind.record();
        if let (Some(file), Some(sha), Some(recorded)) = (
            &now.profile_file,
            &now.profile_sha256,
            &record.profile_sha256,
        ) {
            if sha != recorded {
                return Err(Error::invalid(
                    "profile_sha256",
                    format!(
                        "the profile `{}` has changed since the record was written (SHA-256 {} \
                         now, {recorded} recorded)",
                        file, sha
                    ),
                ));
            }
        }
        Ok(kind)
    }
}

/// Punch geometry in physical units (any consistent length unit).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Punch {
    pub kind: PunchKind,
    /// Outer contact radius `a` = the sharp rim.
    pub rim_radius: f64,
    /// Inner radius `b` of the flat annulus (`0 <= b < a`; `b = 0` is the flat circular punch).
    pub inner_radius: f64,
    /// Depth `h` of the concave hole at `r = 0` (concave punches only; 0 otherwise). For the
    /// torus the gap at the axis, `h = a²/(2ρ)`.
    pub hole_depth: f64,
}

impl Punch {
    /// Gap `g(r)` in length units, `0 <= r <= a`.
    pub fn gap(&self, r: f64) -> f64 {
        self.hole_depth * self.kind.gap_shape(r / self.rim_radius)
    }

    /// `b/a` of a flat annulus (0 for the other shapes).
    pub fn inner_ratio(&self) -> f64 {
        self.inner_radius / self.rim_radius
    }

    /// The torus's tube radius `ρ = a²/(2h)` (`None` for the other shapes).
    pub fn tube_radius(&self) -> Option<f64> {
        self.kind
            .is_free_band()
            .then(|| self.rim_radius * self.rim_radius / (2.0 * self.hole_depth))
    }
}
