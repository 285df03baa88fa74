use ringcontact::error::Result;
use ringcontact::scene::{in_keywords, SceneSpec};

fn keywords(text: &str) -> Result<SceneSpec> {
    let serde_json::Value::Object(object) = serde_json::from_str(text).unwrap() else {
        panic!("not an object: {text}")
    };
    SceneSpec::from_keywords(object, "test", None)
}

/// The flat keywords give the scene the sectioned file gives.
#[test]
fn flat_keywords_equal_the_sectioned_file() {
    let flat = keywords(
        r#"{"punch": "cone", "hole_depth": 0.1, "youngs_modulus": 3, "poisson_ratio": 0.45,
            "depth": 0.2, "tolerance": 1e-6}"#,
    )
    .unwrap()
    .validate()
    .unwrap();
    let file = SceneSpec::from_toml(
        "[punch]\nshape = \"cone\"\nhole_depth = 0.1\n[material]\nyoungs_modulus = 3.0\n\
         poisson_ratio = 0.45\n[load]\ndepth = 0.2\n[accuracy]\ntolerance = 1e-6\n",
        "test",
    )
    .unwrap()
    .validate()
    .unwrap();
    assert_eq!(flat, file);
}

/// `eps` is the hole of the fixed annulus and the prescribed contact of a concave punch.
#[test]
fn eps_means_what_the_command_line_flag_means() {
    let annulus = keywords(r#"{"punch": "flat-annulus", "eps": 0.25, "rim_radius": 2}"#)
        .unwrap()
        .validate()
        .unwrap();
    assert_eq!(annulus.punch.inner_radius, 0.5);
    let cone = keywords(r#"{"punch": "cone", "eps": 0.4}"#)
        .unwrap()
        .validate()
        .unwrap();
    assert_eq!(cone.load, ringcontact::scene::Load::ContactRatio(0.4));
}

/// Unknown keys, a shape named twice, `eps` beside a load: errors naming the key.
/// Validation errors of a keyword scene name the keywords the caller gave, not the scene
/// file's sections or the command line's flags.
#[test]
fn validation_errors_name_the_keywords_given() {
    let cases = [
        (
            r#"{"punch": "cone", "eps": 1.5}"#,
            "`eps` must satisfy 0 < b/a < 1",
        ),
        (r#"{"punch": "sphere", "force": -1}"#, "`force` must be > 0"),
        (
            r#"{"punch": "flat-annulus"}"#,
            "`inner_radius` is required for shape = flat-annulus (or give eps = b/a)",
        ),
        (r#"{"punch": "cone"}"#, "(or eps = b/a)"),
    ];
    for (text, expected) in cases {
        let object: serde_json::Map<String, serde_json::Value> =
            serde_json::from_str(text).unwrap();
        let given: Vec<String> = object.keys().cloned().collect();
        let error = SceneSpec::from_keywords(object, "test", None)
            .and_then(SceneSpec::validate)
            .map_err(|e| in_keywords(e, &given))
            .unwrap_err()
            .to_string();
        assert!(error.contains(expected), "{text}: {error}");
        assert!(
            !error.contains("load.") && !error.contains("--"),
            "{text}: {error}"
        );
    }
}

#[test]
fn bad_keywords_are_named() {
    for (keywords_text, expected) in [
        (
            r#"{"punch": "cone", "dept": 1}"#,
            "`dept` is not a scene keyword",
        ),
        (
            r#"{"punch": "cone", "shape": "sphere"}"#,
            "`punch` and `shape`",
        ),
        (
            r#"{"punch": "cone", "eps": 0.5, "depth": 1}"#,
            "do not combine",
        ),
        (r#"{"punch": "flat", "eps": 0.5}"#, "flat circular"),
        (
            r#"{"punch": "cone", "depth": "deep"}"#,
            "`load.depth` must be a number (got \"deep\")",
        ),
    ] {
        let e = keywords(keywords_text).err().expect("an error");
        assert!(e.to_string().contains(expected), "{keywords_text}: {e}");
    }
}
