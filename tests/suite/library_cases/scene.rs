use ringcontact::punch::PunchKind;
use ringcontact::scene::{Load, SceneSpec};

fn rule_of(text: &str) -> String {
    SceneSpec::from_toml(text, "test")
        .and_then(SceneSpec::validate)
        .unwrap_err()
        .to_string()
}

#[test]
fn defaults_give_dimensionless_scene() {
    let s = SceneSpec::default()
        .shape(PunchKind::CONE)
        .depth(2.0)
        .validate()
        .unwrap();
    assert_eq!(s.punch.rim_radius, 1.0);
    assert_eq!(s.punch.hole_depth, 1.0);
    assert_eq!(s.material.effective_modulus, 1.0);
    assert_eq!(s.load, Load::Depth(2.0));
}

#[test]
fn each_rule_is_named() {
    assert!(rule_of("[punch]\nshape='flat-annulus'\ninner_radius=1.0").contains("b < a"));
    assert!(
        rule_of("[punch]\nshape='cone'\nhole_depth=-1\n[load]\ndepth=1")
            .contains("punch.hole_depth")
    );
    assert!(
        rule_of("[punch]\nshape='cone'\nhole_depth=0\n[load]\ndepth=1").contains("must be > 0")
    );
    assert!(
        rule_of("[punch]\nshape='flat'\n[material]\neffective_modulus=-2")
            .contains("material.effective_modulus")
    );
    assert!(
        rule_of("[punch]\nshape='flat'\n[material]\nyoungs_modulus=1\npoisson_ratio=0.5")
            .contains("(-1, 0.5)")
    );
    assert!(rule_of("[punch]\nshape='flat'\n[load]\ndepth=nan").contains("finite"));
    assert!(rule_of("[punch]\nshape='flat'\n[load]\ndepth=inf").contains("finite"));
    assert!(rule_of("[punch]\nshape='flat'\ncolour='red'").contains("unknown field `colour`"));
    assert!(rule_of("[punch]\nshape='hexagon'").contains("unknown variant"));
    assert!(rule_of("[punch]\nshape='sphere'").contains("needs one of depth"));
}

#[test]
fn youngs_modulus_and_poisson_give_effective_modulus() {
    let s = SceneSpec::from_toml(
        "[punch]\nshape='flat'\n[material]\nyoungs_modulus=3.0\npoisson_ratio=0.5e0\n",
        "t",
    );
    assert!(s.unwrap().validate().is_err());
    let s = SceneSpec::from_toml(
        "[punch]\nshape='flat'\n[material]\nyoungs_modulus=3.0\npoisson_ratio=0.0\n",
        "t",
    )
    .unwrap()
    .validate()
    .unwrap();
    assert_eq!(s.material.effective_modulus, 3.0);
}
