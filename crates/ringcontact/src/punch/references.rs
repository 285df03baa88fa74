//! What a reference is: a closed form, series, asymptote or fit of one dimensionless function of
//! a punch, with the range of `eps = b/a` where it holds and its error bound there. Each
//! built-in profile declares its own ([`super::Profile::references`]).

use serde::Serialize;

/// A dimensionless function the references approximate: `γ` (`F = 2 E* d a γ`, function 0),
/// `γ1 = d/h` (1) or `γ2 = F/(2 E* h a)` (2) of one punch family.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Quantity {
    key: &'static str,
    label: &'static str,
    function: u8,
}

impl Quantity {
    /// A function with its JSON key (`<punch>_gamma1`), its label (`gamma1 (<punch>)`) and its
    /// number.
    pub const fn new(key: &'static str, label: &'static str, function: u8) -> Quantity {
        Quantity {
            key,
            label,
            function,
        }
    }

    /// The key in JSON (`verify references --json`).
    pub fn key(self) -> &'static str {
        self.key
    }

    /// The name people read: the function and the punch.
    pub fn label(self) -> &'static str {
        self.label
    }

    /// Which function: 0 for `γ`, 1 for `γ1 = d/h`, 2 for `γ2 = F/(2 E* h a)`.
    pub fn function(self) -> usize {
        usize::from(self.function)
    }
}

impl Serialize for Quantity {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.key)
    }
}

/// A quantity read back from JSON: one that some built-in punch declares.
impl<'de> serde::Deserialize<'de> for Quantity {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let key = String::deserialize(deserializer)?;
        super::PunchKind::every_built_in()
            .iter()
            .flat_map(|kind| kind.references())
            .map(|r| r.quantity)
            .find(|q| q.key == key)
            .ok_or_else(|| serde::de::Error::custom(format!("unknown quantity '{key}'")))
    }
}

/// A reference value with its declared accuracy.
#[derive(Clone, Copy, Debug, Serialize, serde::Deserialize)]
pub struct ReferenceValue {
    pub value: f64,
    /// Bound on the absolute error, if the source provides one.
    pub error_bound: Option<f64>,
}

impl ReferenceValue {
    /// An exact value (error bound 0).
    pub fn exact(value: f64) -> ReferenceValue {
        ReferenceValue {
            value,
            error_bound: Some(0.0),
        }
    }

    /// A value without an error bound (a fit).
    pub fn unbounded(value: f64) -> ReferenceValue {
        ReferenceValue {
            value,
            error_bound: None,
        }
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
    /// The value at `eps` (inside `eps_range`).
    pub eval: fn(f64) -> ReferenceValue,
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
