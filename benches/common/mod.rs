//! What the benches share.

use ringcontact::punch::{PunchKind, PunchName};

/// The table punch of the committed example `verify/profiles/sphere-21.csv`: the sphere's
/// profile sampled at 21 points (the report's table).
pub fn sampled_sphere() -> PunchKind {
    PunchName::Table
        .with_parameters(
            None,
            Some(std::path::Path::new(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/verify/profiles/sphere-21.csv"
            ))),
        )
        .expect("the committed profile")
}
