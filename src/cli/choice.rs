//! The library's named options ([`Choice`]: punch shapes, methods, far-field treatments) as clap
//! values: the possible values with their one-line descriptions, parsed into the library's type.

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use ringcontact::choice::Choice;

/// clap's parser of a `T` from its name; `--help` lists every name with its description.
pub fn parser<T: Choice + Clone>() -> impl TypedValueParser<Value = T> {
    let values = T::ALL
        .iter()
        .map(|option| PossibleValue::new(option.name()).help(option.description()));
    PossibleValuesParser::new(values).try_map(|name: String| {
        T::named(&name).ok_or_else(|| format!("{name:?} is not one of {}", T::names_joined(", ")))
    })
}
