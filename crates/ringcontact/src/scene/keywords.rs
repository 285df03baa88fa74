//! A scene given as one flat set of keywords (`shape`, `depth`, `effective_modulus`, ...), as the
//! Python package's `solve(**keywords)` passes it: every key of the scene file, without its
//! sections (no key name repeats across sections), plus `punch` (a name for `shape`, as on the
//! command line) and `eps` (b/a: the fixed annulus's hole, or a concave punch's prescribed contact,
//! as `--eps`).

use super::{PunchName, SceneSpec};
use crate::error::{Error, Result};
use crate::punch::Contact;

/// Each flat keyword and the section of the scene file it belongs to.
const SECTIONS: [(&str, &str); 14] = [
    ("shape", "punch"),
    ("exponent", "punch"),
    ("rim_radius", "punch"),
    ("inner_radius", "punch"),
    ("hole_depth", "punch"),
    ("tube_radius", "punch"),
    ("profile", "punch"),
    ("effective_modulus", "material"),
    ("youngs_modulus", "material"),
    ("poisson_ratio", "material"),
    ("depth", "load"),
    ("force", "load"),
    ("contact_ratio", "load"),
    ("tolerance", "accuracy"),
];

/// The keywords a flat scene takes, in the order the docs list them.
pub fn keyword_names() -> Vec<&'static str> {
    let mut names = vec!["punch"];
    names.extend(SECTIONS.iter().map(|(k, _)| *k));
    names.push("eps");
    names
}

/// [`SceneSpec::from_keywords`].
pub(super) fn from_keywords(
    object: serde_json::Map<String, serde_json::Value>,
    origin: &str,
    base: Option<&std::path::Path>,
) -> Result<SceneSpec> {
    let mut nested = serde_json::Map::new();
    let mut eps = None;
    for (key, value) in object {
        if value.is_null() {
            continue;
        }
        let (key, section) = match key.as_str() {
            "eps" => {
                eps = Some(value);
                continue;
            }
            "punch" | "shape" => {
                if let Some(name) = value.as_str().filter(|n| PunchName::parse(n).is_none()) {
                    return Err(Error::invalid(
                        &key,
                        format!(
                            "is not a punch: {name:?} (one of {})",
                            PunchName::names(None, ", ")
                        ),
                    ));
                }
                ("shape".to_string(), "punch")
            }
            _ => match SECTIONS.iter().find(|(k, _)| *k == key) {
                Some((_, section)) => (key, *section),
                None => {
                    return Err(Error::invalid(
                        &key,
                        format!(
                            "is not a scene keyword (a scene takes {})",
                            keyword_names().join(", ")
                        ),
                    ))
                }
            },
        };
        let entry = nested
            .entry(section)
            .or_insert_with(|| serde_json::Value::Object(Default::default()));
        if let Some(fields) = entry.as_object_mut() {
            if fields.insert(key.clone(), value).is_some() {
                return Err(Error::invalid(
                    "punch",
                    "and `shape` both name the shape: give one",
                ));
            }
        }
    }
    let eps = match eps {
        None => None,
        Some(value) => Some(
            value
                .as_f64()
                .ok_or_else(|| Error::invalid("eps", format!("must be a number (got {value})")))?,
        ),
    };
    let loads = nested
        .get("load")
        .and_then(|l| l.as_object())
        .map_or(0, |l| l.len());
    let has_inner_radius = nested
        .get("punch")
        .and_then(|p| p.get("inner_radius"))
        .is_some();
    let spec = SceneSpec::from_json_value(serde_json::Value::Object(nested), origin, base)
        .map_err(|e| match e {
            // Keywords are no file: their error names the keywords.
            Error::SceneFile { message, .. } => {
                Error::invalid("keywords", format!("do not make a scene: {message}"))
            }
            other => other,
        })?;
    let Some(eps) = eps else {
        return Ok(spec);
    };
    if loads > 0 && spec.shape_name().map(PunchName::contact) != Some(Contact::FixedAnnulus) {
        return Err(Error::invalid(
            "eps",
            "prescribes the contact of a concave punch; do not combine it with `depth`, \
                 `force` or `contact_ratio`",
        ));
    }
    if has_inner_radius {
        return Err(Error::invalid(
            "eps",
            "and `inner_radius` both give the fixed annulus's hole: give one",
        ));
    }
    spec.eps(eps)
}

/// The error of a scene given by keywords (`given`: the keywords the caller passed), naming
/// the keyword given (`eps`, `force`, `inner_radius`) rather than the scene file's `section.key`.
pub fn in_keywords(error: Error, given: &[String]) -> Error {
    let Error::InvalidScene { field, rule } = error else {
        return error;
    };
    let gave = |keyword: &str| given.iter().any(|g| g == keyword);
    let key = field.rsplit('.').next().unwrap_or(&field).to_string();
    let loads: Vec<&str> = ["depth", "force", "contact_ratio"]
        .into_iter()
        .filter(|k| gave(k))
        .collect();
    let (field, rule) = match key.as_str() {
        "contact_ratio" | "inner_radius" if gave("eps") => ("eps".to_string(), rule),
        "shape" if !gave("shape") => ("punch".to_string(), rule),
        // The scene file's `load` section is the load keywords given.
        "load" if loads.len() > 1 => (
            loads.join("` and `"),
            format!(
                "are {} loads: give exactly one of depth, force, contact_ratio",
                if loads.len() == 2 { "both" } else { "all" }
            ),
        ),
        _ => (key, rule),
    };
    Error::InvalidScene { field, rule }
}

/// [`SceneSpec::eps`].
pub(super) fn with_eps(spec: SceneSpec, eps: f64) -> Result<SceneSpec> {
    match spec.shape_name().map(PunchName::contact) {
        Some(Contact::Disk) => Err(Error::invalid(
            "eps",
            format!(
                "does not apply to the flat circular punch; use the {} punch with eps = b/a",
                PunchName::names(Some(Contact::FixedAnnulus), ", ")
            ),
        )),
        Some(Contact::FixedAnnulus) | None => Ok(spec.inner_ratio(eps)),
        Some(_) => Ok(spec.contact_ratio(eps)),
    }
}

/// Every value of the sectioned scene `nested` has its key's type (a name or path for `shape`
/// and `profile`, a number otherwise): an error naming `section.key` and the value, where
/// serde's own message would name only the type.
pub(super) fn check_types(nested: &serde_json::Value) -> Result<()> {
    let Some(sections) = nested.as_object() else {
        return Ok(());
    };
    for (section, fields) in sections {
        let Some(fields) = fields.as_object() else {
            return Err(Error::invalid(
                section,
                format!(
                    "is a section of keys such as {section}.{} (got {fields})",
                    {
                        SECTIONS
                            .iter()
                            .find(|(_, s)| s == section)
                            .map_or("...", |(k, _)| k)
                    }
                ),
            ));
        };
        for (key, value) in fields {
            let text = matches!(key.as_str(), "shape" | "profile");
            let fits = if text {
                value.is_string()
            } else {
                value.is_number()
            };
            if !fits && !value.is_null() {
                return Err(Error::invalid(
                    &format!("{section}.{key}"),
                    format!(
                        "must be {} (got {value})",
                        if text { "a name" } else { "a number" }
                    ),
                ));
            }
        }
    }
    Ok(())
}
