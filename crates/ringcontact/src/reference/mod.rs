//! Analytic references: closed forms, series, asymptotes and the paper's fitted formulas.
//!
//! Every reference declares the range of `eps = b/a` (or of `d/h`) where it may be used and an
//! error bound there, so that the harness never compares a solver with a reference outside its
//! range. The paper's fits carry no bound: how good they are is a result of this project
//! (the harness grades them), not an input.

pub mod asymptotic;
pub use crate::punch::mdr;
pub mod paper_fits;
pub use crate::punch::power_law;

use serde::Serialize;

use crate::punch::PunchKind;

/// A dimensionless function the references approximate.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// `γ(eps)` of the flat annulus, `F = 2 E* d a γ`.
    FlatGamma,
    /// `γ1(eps)` of the conical concave punch, `d = h γ1`.
    ConeGamma1,
    /// `γ2(eps)` of the conical concave punch, `F = 2 E* h a γ2`.
    ConeGamma2,
    /// `γ1(eps)` of the spherical concave punch.
    SphereGamma1,
    /// `γ2(eps)` of the spherical concave punch.
    SphereGamma2,
}

impl Quantity {
    /// The name people read: the function and the punch (`gamma (flat annulus)`).
    pub fn label(self) -> &'static str {
        match self {
            Quantity::FlatGamma => "gamma (flat annulus)",
            Quantity::ConeGamma1 => "gamma1 (cone)",
            Quantity::ConeGamma2 => "gamma2 (cone)",
            Quantity::SphereGamma1 => "gamma1 (sphere)",
            Quantity::SphereGamma2 => "gamma2 (sphere)",
        }
    }

    /// The punch whose function this is.
    pub fn punch(self) -> PunchKind {
        match self {
            Quantity::FlatGamma => PunchKind::FLAT_ANNULUS,
            Quantity::ConeGamma1 | Quantity::ConeGamma2 => PunchKind::CONE,
            Quantity::SphereGamma1 | Quantity::SphereGamma2 => PunchKind::SPHERE,
        }
    }

    /// Which function: 0 for `γ` (`F = 2 E* d a γ`), 1 for `γ1 = d/h`, 2 for `γ2 = F/(2 E* h a)`.
    pub fn function(self) -> usize {
        match self {
            Quantity::FlatGamma => 0,
            Quantity::ConeGamma1 | Quantity::SphereGamma1 => 1,
            Quantity::ConeGamma2 | Quantity::SphereGamma2 => 2,
        }
    }
}

/// A reference value with its declared accuracy.
#[derive(Clone, Copy, Debug, Serialize, serde::Deserialize)]
pub struct ReferenceValue {
    pub value: f64,
    /// Bound on the absolute error, if the source provides one.
    pub error_bound: Option<f64>,
}

/// An analytic reference for one quantity.
#[derive(Clone, Copy, Debug)]
pub struct Reference {
    /// Short name used in tables and JSON (`collins-series`, ...).
    pub name: &'static str,
    /// Where it comes from.
    pub source: &'static str,
    /// Which function it approximates.
    pub quantity: Quantity,
    /// Closed interval of `eps` where it may be used.
    pub eps_range: (f64, f64),
    /// Kind of reference, in order of trust: exact, series, asymptote, fit.
    pub kind: ReferenceKind,
    eval: fn(f64) -> ReferenceValue,
}

/// A reference as `verify references --json` lists it: its name, quantity, kind, range of `eps`
/// as `[low, high]` and source (keys in alphabetical order).
impl Serialize for Reference {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let mut fields = serializer.serialize_struct("Reference", 5)?;
        fields.serialize_field("eps_range", &[self.eps_range.0, self.eps_range.1])?;
        fields.serialize_field("kind", &self.kind)?;
        fields.serialize_field("name", self.name)?;
        fields.serialize_field("quantity", &self.quantity)?;
        fields.serialize_field("source", self.source)?;
        fields.end()
    }
}

/// How much a reference can be trusted.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ReferenceKind {
    /// A closed-form exact result.
    Exact,
    /// A convergent or asymptotic series with a truncation bound.
    Series,
    /// A leading-order asymptote with an estimated error.
    Asymptote,
    /// A fitted approximation without an error bound.
    Fit,
}

impl ReferenceKind {
    /// Lower-case name for tables.
    pub fn label(self) -> &'static str {
        match self {
            ReferenceKind::Exact => "exact",
            ReferenceKind::Series => "series",
            ReferenceKind::Asymptote => "asymptote",
            ReferenceKind::Fit => "fit",
        }
    }
}

impl Reference {
    /// Whether `eps` lies in the declared range.
    pub fn is_valid_at(&self, eps: f64) -> bool {
        eps >= self.eps_range.0 && eps <= self.eps_range.1
    }

    /// Value at `eps`, or `None` outside the declared range.
    pub fn evaluate(&self, eps: f64) -> Option<ReferenceValue> {
        self.is_valid_at(eps).then(|| (self.eval)(eps))
    }
}

/// All references, most trusted first within each quantity.
pub fn catalogue() -> Vec<Reference> {
    let mut all = asymptotic::references();
    all.extend(paper_fits::references());
    all.sort_by_key(|r| r.kind);
    all
}

/// The fitted approximation of `kind`'s function `function` (0: `γ`, 1: `γ1`, 2: `γ2`), where
/// the catalogue has one (the paper fitted the flat annulus, the cone and the sphere).
pub fn fit_of(kind: &PunchKind, function: usize) -> Option<Reference> {
    catalogue().into_iter().find(|r| {
        r.kind == ReferenceKind::Fit
            && r.quantity.function() == function
            && r.quantity.punch() == *kind
    })
}

/// References for `quantity` valid at `eps`, most trusted first.
pub fn valid_references(quantity: Quantity, eps: f64) -> Vec<Reference> {
    catalogue()
        .into_iter()
        .filter(|r| r.quantity == quantity && r.is_valid_at(eps))
        .collect()
}

/// Spherical concave punch in full contact (`d >= 3h`), method of dimensionality reduction:
/// `F = 2 E* a (d - h/3)`, i.e. `γ2 = γ1 - 1/3` for `γ1 = d/h >= 3` (docs/conventions.md fact 4).
/// Returns `None` for `d/h < 3`, where the contact is an annulus.
pub fn sphere_full_contact_gamma2(depth_over_hole: f64) -> Option<f64> {
    (depth_over_hole >= 3.0).then(|| depth_over_hole - 1.0 / 3.0)
}
