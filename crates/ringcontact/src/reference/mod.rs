//! Analytic references: closed forms, series, asymptotes and the paper's fitted formulas.
//!
//! Every reference declares the range of `eps = b/a` (or of `d/h`) where it may be used and an
//! error bound there, so that the harness never compares a solver with a reference outside its
//! range. The paper's fits carry no bound: how good they are is a result of this project
//! (the harness grades them), not an input.

pub use crate::punch::mdr;
pub use crate::punch::power_law;
pub use crate::punch::{Quantity, Reference, ReferenceKind, ReferenceValue};

use crate::punch::PunchKind;

/// The series and the asymptote of `γ(b/a)` under their older path.
pub mod dugdale_flat;

pub mod asymptotic {
    pub use crate::punch::{collins_series, narrow_ring};
}

/// All references, most trusted first within each quantity.
pub fn catalogue() -> Vec<Reference> {
    let mut all: Vec<Reference> = Vec::new();
    for r in PunchKind::every_built_in()
        .iter()
        .flat_map(|k| k.references())
    {
        if !all
            .iter()
            .any(|o| o.name == r.name && o.quantity == r.quantity)
        {
            all.push(r);
        }
    }
    all.sort_by_key(|r| r.kind);
    all
}

/// The fitted approximation of `kind`'s function `function` (0: `γ`, 1: `γ1`, 2: `γ2`), where
/// its profile declares one.
pub fn fit_of(kind: &PunchKind, function: usize) -> Option<Reference> {
    kind.references()
        .into_iter()
        .find(|r| r.kind == ReferenceKind::Fit && r.quantity.function() == function)
}

/// Every quantity the built-in punches declare references for, in the order they declare them
/// (the command line's order of the punches).
pub fn quantities() -> Vec<Quantity> {
    let mut all: Vec<Quantity> = Vec::new();
    for r in PunchKind::every_built_in()
        .iter()
        .flat_map(|k| k.references())
    {
        if !all.contains(&r.quantity) {
            all.push(r.quantity);
        }
    }
    all
}

/// The quantity of `kind`'s function `function`, where its profile declares references for it.
pub fn quantity_of(kind: &PunchKind, function: usize) -> Option<Quantity> {
    kind.references()
        .into_iter()
        .map(|r| r.quantity)
        .find(|q| q.function() == function)
}

/// The built-in punch whose paper fit approximates `quantity`.
pub fn fitted_punch(quantity: Quantity) -> Option<PunchKind> {
    PunchKind::every_built_in().into_iter().find(|k| {
        k.references()
            .iter()
            .any(|r| r.kind == ReferenceKind::Fit && r.quantity == quantity)
    })
}

/// References for `quantity` valid at `eps`, most trusted first.
pub fn valid_references(quantity: Quantity, eps: f64) -> Vec<Reference> {
    catalogue()
        .into_iter()
        .filter(|r| r.quantity == quantity && r.is_valid_at(eps))
        .collect()
}
