//! The FEM on the torus, a contact with two free edges, against the ring BEM (converged to
//! 1e-10, an independent discretisation of the same problem): at 12 states under depth and force
//! control (`d/h` from 1e-3 to 10, `F/(2 E* h a)` from 1e-4 to 2) the FEM's answer at
//! `--tol 1e-6` is within its own estimate of the ring BEM's, the force-like outputs relative
//! and both edges `b/a`, `c/a` absolute, and the estimate is within the tolerance.

use crate::common;
use common::assert_study_converges;

use ringcontact::discretisation::far_field::FarField;
use ringcontact::fem::solver::{self, default_degree, FemLoad, FemOptions};
use ringcontact::methods::RingBem;
use ringcontact::punch::PunchKind;

fn options(tolerance: f64) -> FemOptions {
    FemOptions {
        linear_solver: Default::default(),
        trace: false,
        data: Default::default(),
        progress: Default::default(),
        degree: default_degree(&ringcontact::mesh::files::DataPaths::default(), tolerance),
        tolerance,
        mesh: None,
        poisson_ratio: 0.0,
        far_field: FarField::Boussinesq,
    }
}

/// The FEM's `(γ1, γ2, b, c)` errors against the ring BEM's, each within the FEM's estimate,
/// which is within `tolerance`.
fn check(loads: &[FemLoad], tolerance: f64) {
    let bem = RingBem::new();
    for &load in loads {
        let fem = solver::solve(PunchKind::TORUS, 0.0, load, &options(tolerance))
            .unwrap_or_else(|e| panic!("{load:?}: {e}"));
        let reference = match load {
            // 1e-10, 1e4 times finer than the FEM's tolerance: at 1e-12 the shallowest state
            // (F = 1e-4) is at the rounding of its depth (the relative estimate of the depth
            // scattered between 1e-12 and 4e-11 from N = 16 to 80).
            FemLoad::ConcaveDepth(d) => bem.concave_at_depth(&PunchKind::TORUS, d, 1e-10),
            FemLoad::ConcaveForce(f) => bem.concave_at_force(&PunchKind::TORUS, f, 1e-10),
            FemLoad::Flat => unreachable!("the torus is not flat"),
        }
        .unwrap();
        let relative = |x: f64, y: f64| (x - y).abs() / y.abs();
        let errors = [
            relative(fem.gamma1.unwrap(), reference.gamma1.unwrap()),
            relative(fem.gamma2.unwrap(), reference.gamma2.unwrap()),
            (fem.eps - reference.eps).abs(),
            (fem.outer_edge.unwrap() - reference.outer_edge).abs(),
        ];
        let estimate = fem.error_estimate.unwrap();
        eprintln!(
            "{load:?}: errors γ1 {:.1e} γ2 {:.1e} b {:.1e} c {:.1e}, estimate {estimate:.1e}, {} unknowns",
            errors[0], errors[1], errors[2], errors[3], fem.dofs
        );
        assert!(estimate <= tolerance, "{load:?}: estimate {estimate:e}");
        for (name, error) in ["γ1", "γ2", "b/a", "c/a"].iter().zip(errors) {
            assert!(
                error <= estimate,
                "{load:?}: {name} off by {error:e}, above the estimate {estimate:e}"
            );
        }
    }
}

#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn shallow_states_under_depth_control_are_within_the_estimate() {
    let depths = [1e-3, 1e-2, 0.1, 0.5];
    check(&depths.map(FemLoad::ConcaveDepth), 1e-6);
}

#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn deep_states_under_depth_control_are_within_the_estimate() {
    let depths = [1.0, 2.0, 5.0, 10.0];
    check(&depths.map(FemLoad::ConcaveDepth), 1e-6);
}

#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn states_under_force_control_are_within_the_estimate() {
    let forces = [1e-4, 1e-2, 0.5, 2.0];
    check(&forces.map(FemLoad::ConcaveForce), 1e-6);
}

#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn the_default_tolerance_is_met() {
    check(
        &[FemLoad::ConcaveDepth(0.3), FemLoad::ConcaveForce(0.3)],
        1e-3,
    );
}

#[test]
fn a_mesh_of_ones_own_is_refused_for_the_torus() {
    let mut options = options(1e-3);
    options.mesh = Some("meshes/disk-L0.msh".into());
    let error = solver::solve(PunchKind::TORUS, 0.0, FemLoad::ConcaveDepth(1.0), &options)
        .expect_err("a torus on a given mesh");
    assert!(error.to_string().contains("--mesh"), "{error}");
}

#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn the_command_line_gives_both_edges_of_the_fem() {
    let solve = |method: &str| -> serde_json::Value {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_verify"))
            .args([
                "solve",
                "--punch",
                "torus",
                "--tube-radius",
                "0.5",
                "--depth",
                "0.3",
            ])
            .args(["--method", method, "--json"])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let (fem, ring) = (solve("fem"), solve("ring-bem"));
    let estimate = fem["error_estimate"].as_f64().unwrap();
    assert!(estimate <= 1e-3, "{fem}");
    for key in ["inner_radius", "outer_radius", "gamma2"] {
        let (x, y) = (fem[key].as_f64().unwrap(), ring[key].as_f64().unwrap());
        assert!(
            (x - y).abs() <= estimate * y.abs().max(1.0),
            "{key}: {x} against {y}"
        );
    }
    assert!(fem["outer_radius"].as_f64().unwrap() > 1.0, "{fem}");
}

/// `verify convergence --punch torus`: the FEM's levels of the free-edges family (each refined
/// around both edges the level below located) and the grid BEM's grids on one square converge
/// toward the ring BEM's state (the yardstick, an independent method), and the finest level's
/// error bar bounds its actual error. Measured at `d/h = 1`: FEM 4.2e-3, 1.2e-3, 2.1e-4,
/// 3.4e-5 (bar 1.2e-4); grid BEM 2.6e-4, 6.2e-5, 1.9e-5 (bar 1.3e-4).
#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn convergence_studies_of_the_torus_are_bounded_by_their_bars() {
    let out_dir =
        std::env::temp_dir().join(format!("ringcontact-torus-conv-{}", std::process::id()));
    for (method, levels, finest) in [("fem", "4", 1e-4), ("grid-bem", "3", 1e-4)] {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_verify"))
            .args([
                "convergence",
                "--punch",
                "torus",
                "--method",
                method,
                "--depth",
                "1",
            ])
            .args(["--levels", levels, "--json", "--out"])
            .arg(&out_dir)
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "{method}: {text}{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let json: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(json["punch"], "torus");
        assert_study_converges(&json, method, finest);
    }
    // The ring BEM certifies its states by its node ladder, and plans hold one free edge.
    for args in [
        vec!["convergence", "--punch", "torus", "--method", "ring-bem"],
        vec![
            "plan",
            "--convergence",
            "--punch",
            "torus",
            "--method",
            "fem",
        ],
    ] {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_verify"))
            .args(&args)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            !out.status.success() && !err.contains("panicked"),
            "{args:?}: {err}"
        );
    }
    let _ = std::fs::remove_dir_all(&out_dir);
}
