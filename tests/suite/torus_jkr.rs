//! The JKR adhesion of the torus (a Griffith condition at both edges of its band) against the
//! plane-strain JKR cylinder in the narrow limit, and its critical states against the band
//! solver with both edges prescribed.

use std::f64::consts::PI;
use std::process::Command;

use ringcontact::adhesion;
use ringcontact::methods::RingBem;
use ringcontact::punch::PunchKind;

/// The plane-strain JKR cylinder (Barquins 1988): per unit length, the Hertz load of half-width
/// `w` less the flat strip's adhesive load, `P = π E* w²/(4ρ) - sqrt(2π E* Δw w)` (the strip's
/// edge intensity is `K = -P_a/sqrt(π w)`, and `K²/(2E*) = Δw`). Its minimum is at
/// `w_c³ = 2 ρ² Δw/(π E*)`, `P_c = -(3/4) π E* w_c²/ρ`. Over the ring's length `2π a` in the
/// torus's units (`a = E* = h = 1`, so `ρ = 1/2`; `d0 = sqrt(2π Δw)`, so `Δw = s²/(2π)` for
/// `s = d0/h`; `F0 = 2 d0`): `F_c/F0 = 2π P_c/(2s)`.
fn plane_strain_cylinder_pulloff(s: f64) -> f64 {
    let (rho, dw) = (0.5, s * s / (2.0 * PI));
    let w = (2.0 * rho * rho * dw / PI).cbrt();
    let p = PI * w * w / (4.0 * rho) - (2.0 * PI * dw * w).sqrt();
    2.0 * PI * p / (2.0 * s)
}

/// As `d0/h -> 0` the pull-off band narrows (`w_c ∝ (d0/h)^(2/3)`) and the torus's fixed-load
/// pull-off approaches the plane-strain cylinder's: measured relative differences 1.4e-6,
/// 2.5e-5, 4.2e-4 at `d0/h = 1e-4, 1e-3, 1e-2`, falling about 17 times per decade (`w_c²`
/// falls 21.5 times; the ring's correction carries a logarithm). The library's
/// `plane_strain_pulloff` is checked against the closed form written here.
#[test]
fn the_narrow_torus_pulls_off_like_the_plane_strain_jkr_cylinder() {
    let solver = RingBem::new();
    let mut previous: Option<f64> = None;
    for s in [1e-2, 1e-3, 1e-4] {
        let r = adhesion::band_jkr(&solver, &PunchKind::TORUS, s).unwrap();
        let critical = r.fixed_load.clone().expect("a fixed-load pull-off");
        let reference = plane_strain_cylinder_pulloff(s);
        assert!((r.plane_strain_fixed_load.unwrap() - reference).abs() < 1e-14 * reference.abs());
        let difference = ((critical.force - reference) / reference).abs();
        println!(
            "d0/h {s:e}: F_c/F0 {:.10} (bound {:.1e}), plane strain {reference:.10}, \
             difference {difference:.2e}, band [{:.6}, {:.6}]",
            critical.force, critical.error_bound, critical.eps, critical.outer
        );
        assert!(critical.force < 0.0 && critical.error_bound < 1e-9);
        assert!(difference < 1e-3, "d0/h {s}: {difference:e}");
        if let Some(p) = previous {
            let ratio = p / difference;
            println!("  falls {ratio:.1} times per decade");
            assert!(
                (8.0..=30.0).contains(&ratio),
                "d0/h {s}: the difference fell {ratio:.1} times per decade (w_c² with a \
                 logarithm: about 15-21)"
            );
        }
        previous = Some(difference);
    }
}

/// At both critical states the band solver, given the band and the depth, finds the intensity
/// of equilibrium `K = -sqrt(2 E* Δw) = -(d0/h)/sqrt(π)` at both edges (to 1e-7 of it) and the
/// force the analysis reports; and the fixed-grips pull-off is at a smaller tension than the
/// fixed-load one (its branch runs on past the minimum of the force).
#[test]
fn the_critical_states_have_both_edges_in_equilibrium() {
    let solver = RingBem::new();
    for s in [0.01, 0.3, 1.0] {
        let r = adhesion::band_jkr(&solver, &PunchKind::TORUS, s).unwrap();
        let k = -s / PI.sqrt();
        for critical in [
            r.fixed_load.clone().unwrap(),
            r.fixed_grips.clone().unwrap(),
        ] {
            let band = solver
                .prescribed_band(
                    |x| (1.0 - x) * (1.0 - x),
                    critical.eps,
                    critical.outer,
                    critical.depth,
                    1e-11,
                )
                .unwrap();
            println!(
                "d0/h {s}: band [{:.6}, {:.6}], K_in {:.10}, K_out {:.10}, K_c {k:.10}",
                critical.eps,
                critical.outer,
                band.inner_stress_intensity,
                band.outer_stress_intensity
            );
            assert!((band.inner_stress_intensity - k).abs() < 1e-7 * k.abs());
            assert!((band.outer_stress_intensity - k).abs() < 1e-7 * k.abs());
            assert!((band.force / (2.0 * s) - critical.force).abs() < 1e-8);
        }
        let (load, grips) = (r.fixed_load.unwrap(), r.fixed_grips.unwrap());
        assert!(
            grips.force > load.force,
            "d0/h {s}: fixed grips pull off at less tension ({} vs {})",
            grips.force,
            load.force
        );
    }
}

/// `verify jkr --punch torus --d0h S` prints both pull-offs; the JSON carries them; what the
/// analysis does not cover is refused by name.
#[test]
fn command_line() {
    let run = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_verify"))
            .args(args)
            .output()
            .unwrap()
    };
    let out = run(&["jkr", "--punch", "torus", "--d0h", "0.01", "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["punch"], "torus");
    assert!(json["fixed_load"]["force"].as_f64().unwrap() < 0.0);
    assert!(json["fixed_grips"]["outer"].as_f64().unwrap() > 1.0);
    for (args, expected) in [
        (vec!["jkr", "--punch", "torus"], "--d0h"),
        (vec!["jkr", "--punch", "torus", "--d0h", "-1"], "positive"),
        (
            vec!["jkr", "--punch", "torus", "--d0h", "1", "--sweep"],
            "--sweep",
        ),
        (
            vec!["jkr", "--punch", "torus", "--d0h", "1", "--eps", "0.5"],
            "--eps",
        ),
    ] {
        let out = run(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} succeeded");
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
    }
}
