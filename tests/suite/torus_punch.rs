//! The toroidal punch `g = (r - a)²/(2ρ)`, both contact edges free, against references the ring
//! BEM's torus path does not use: the plane-strain Hertz solution of a cylinder (the narrow
//! limit), the flat annulus's stiffness (the incremental stiffness of any contact whose edges
//! are free), the band solver with both edges prescribed, and the surface beyond both edges.

use std::f64::consts::PI;
use std::process::Command;

use ringcontact::methods::RingBem;
use ringcontact::methods::{self, Method};
use ringcontact::punch::PunchKind;
use ringcontact::scene::{Scene, SceneSpec};

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1e-300)
}

/// A torus scene: ring radius `a`, tube radius `rho`, modulus `es`, and the load.
fn torus_scene(a: f64, rho: f64, es: f64, load: &str) -> Scene {
    SceneSpec::from_toml(
        &format!(
            "[punch]\nshape = \"torus\"\nrim_radius = {a}\ntube_radius = {rho}\n\
             [material]\neffective_modulus = {es}\n[load]\n{load}\n[accuracy]\ntolerance = 1e-10\n"
        ),
        "test",
    )
    .and_then(SceneSpec::validate)
    .unwrap()
}

/// As `w/a -> 0` the ring is a plane-strain cylinder of radius `ρ` pressed over the length
/// `2π m` (`m` the band's mid radius), whose Hertz solution carries `P = π E* w²/(4ρ)` per unit
/// length for the half-width `w` (Johnson, *Contact Mechanics*, eq. 4.43). Solved through the
/// public API with dimensions (`a = 2`, `ρ = 0.3`, `E* = 5`) under force control, the solver's
/// own edges give `w` and `m`; the difference falls at relative order `(w/a)²` up to a
/// logarithm (the ring's curvature).
#[test]
fn a_narrow_torus_approaches_the_plane_strain_hertz_cylinder() {
    let (a, rho, es) = (2.0, 0.3, 5.0);
    let mut previous: Option<f64> = None;
    for w_over_a in [0.08, 0.04, 0.02, 0.01] {
        let w = w_over_a * a;
        let force = 2.0 * PI * a * PI * es * w * w / (4.0 * rho);
        let scene = torus_scene(a, rho, es, &format!("force = {force}"));
        let s = methods::solve(&scene, Method::RingBem).unwrap();
        let (b, c) = (s.inner_radius, s.outer_radius);
        let (half_width, mid) = (0.5 * (c - b), 0.5 * (b + c));
        let hertz = 2.0 * PI * mid * PI * es * half_width * half_width / (4.0 * rho);
        let difference = relative(s.force, hertz);
        println!(
            "w/a {w_over_a}: b {b:.8}, c {c:.8}, d {:.6e}, F {:.8e}, Hertz {hertz:.8e}, \
             difference {difference:.2e}, estimate {:.1e}",
            s.depth,
            s.force,
            s.error_estimate.unwrap()
        );
        assert!(b < a && c > a, "the band straddles the ring radius");
        assert!(difference < 1e-2, "w/a {w_over_a}: {difference:e}");
        if let Some(p) = previous {
            let order = (p / difference).log2();
            println!("  observed order {order:.2}");
            assert!(
                (1.5..=2.2).contains(&order),
                "w/a {w_over_a}: observed order {order:.2}, expected about 2 (w² with a logarithm)"
            );
        }
        previous = Some(difference);
    }
}

/// A contact whose edges are free has the incremental stiffness of a flat punch on the same
/// contact (the edges' motion does no work at first order: the pressure vanishes there). For
/// the torus's band `[b, c]` that is the flat annulus of ratio `b/c` scaled by `c`:
/// `dF/dd = 2 E* c γ(b/c)`, with `γ` from the flat-annulus path (checked against Collins's and
/// Shibuya's tables and the narrow-ring asymptote in `ring_bem_references`). `dF/dd` here is a
/// central difference of the torus's own `F(d)`, `O(δ²)` with `δ = 1e-4 d`.
#[test]
fn the_incremental_stiffness_is_that_of_the_flat_band() {
    let solver = RingBem::new();
    let tol = 1e-11;
    for depth in [0.01, 0.5, 3.0, 12.0] {
        let state = solver
            .concave_at_depth(&PunchKind::TORUS, depth, tol)
            .unwrap();
        let step = 1e-4 * depth;
        let force = |d: f64| {
            2.0 * solver
                .concave_at_depth(&PunchKind::TORUS, d, tol)
                .unwrap()
                .gamma2
                .unwrap()
        };
        let stiffness = (force(depth + step) - force(depth - step)) / (2.0 * step);
        let (b, c) = (state.eps, state.outer_edge);
        let flat = 2.0 * c * solver.flat(b / c, tol).unwrap().gamma.unwrap();
        let difference = relative(stiffness, flat);
        println!(
            "d/h {depth}: band [{b:.8}, {c:.8}], dF/dd {stiffness:.10}, flat band {flat:.10}, \
             difference {difference:.1e}"
        );
        assert!(difference < 1e-6, "d/h {depth}: {difference:e}");
    }
}

/// The three controls land on one state: the inner edge prescribed, then its depth, then its
/// force, give the same band to well within the tolerance; and the band solver with both edges
/// prescribed there finds both stress intensities zero (to 1e-8 of the band's natural scale
/// `F/(2π m sqrt(c - b))`, a code path of its own: edges given, no search).
#[test]
fn depth_force_and_edge_controls_agree_and_both_edges_are_free() {
    let solver = RingBem::new();
    let tol = 1e-10;
    for eps in [0.98, 0.7, 0.3, 0.05] {
        let at_ratio = solver
            .concave_at_ratio(&PunchKind::TORUS, eps, tol)
            .unwrap();
        let (d, f) = (at_ratio.gamma1.unwrap(), at_ratio.gamma2.unwrap());
        let at_depth = solver.concave_at_depth(&PunchKind::TORUS, d, tol).unwrap();
        let at_force = solver.concave_at_force(&PunchKind::TORUS, f, tol).unwrap();
        for (control, s) in [("depth", &at_depth), ("force", &at_force)] {
            assert!(
                (s.eps - eps).abs() < 1e-8 && (s.outer_edge - at_ratio.outer_edge).abs() < 1e-8,
                "eps {eps} by {control}: band [{}, {}] vs [{eps}, {}]",
                s.eps,
                s.outer_edge,
                at_ratio.outer_edge
            );
        }
        assert!(relative(at_depth.gamma2.unwrap(), f) < 1e-8);
        assert!(relative(at_force.gamma1.unwrap(), d) < 1e-8);

        let c = at_ratio.outer_edge;
        let band = solver
            .prescribed_band(|r| (1.0 - r) * (1.0 - r), eps, c, d, tol)
            .unwrap();
        let scale = band.force / (PI * (eps + c) * (c - eps).sqrt());
        println!(
            "eps {eps}: c {c:.10}, K_in {:.1e}, K_out {:.1e} (scale {scale:.2e})",
            band.inner_stress_intensity, band.outer_stress_intensity
        );
        assert!(relative(band.force, 2.0 * f) < 1e-9);
        assert!(band.inner_stress_intensity.abs() < 1e-8 * scale);
        assert!(band.outer_stress_intensity.abs() < 1e-8 * scale);
    }
}

/// The estimate bounds the error: states at loose tolerances against the same states at a
/// tight one (`1e-11`, the method converged, its own estimate there below it; `1e-10` and `1e-8`
/// for the deep states, `b = 1e-2 a` and `3e-4 a`, above their free edges' rounding floors, where
/// the error bound is the sum of both estimates), narrow to
/// wide bands (`b/a` from 0.98 to 3e-4), under depth and force control. The error is that of
/// the inner and outer edges (absolute, units of `a`) and of `γ1`, `γ2` (relative), the
/// quantities the estimate covers.
#[test]
fn the_estimate_bounds_the_error_of_depth_and_force_controlled_states() {
    let solver = RingBem::new();
    let state = |depth: bool, target: f64, tol: f64| {
        if depth {
            solver.concave_at_depth(&PunchKind::TORUS, target, tol)
        } else {
            solver.concave_at_force(&PunchKind::TORUS, target, tol)
        }
        .unwrap()
    };
    let states = [
        (true, 1e-3, 1e-11),
        (true, 2.0, 1e-11),
        // b/a = 1e-2, c/a = 5.8: the free edges' rounding floor is 3e-11.
        (true, 50.0, 1e-10),
        // b/a = 3e-4, c/a = 8.9: the floor is 1.5e-9.
        (true, 130.0, 1e-8),
        (false, 1e-2, 1e-11),
        // b/a = 1e-2, c/a = 5.7: the floor is 2.7e-11.
        (false, 200.0, 1e-10),
    ];
    for (depth, target, reference_tol) in states {
        let reference = state(depth, target, reference_tol);
        assert!(reference.error_estimate <= reference_tol);
        for tol in [1e-4, 1e-6, 1e-9]
            .into_iter()
            .filter(|&t| t > reference_tol)
        {
            let s = state(depth, target, tol);
            let error = (s.eps - reference.eps)
                .abs()
                .max((s.outer_edge - reference.outer_edge).abs())
                .max(relative(s.gamma1.unwrap(), reference.gamma1.unwrap()))
                .max(relative(s.gamma2.unwrap(), reference.gamma2.unwrap()));
            let bound = s.error_estimate
                + if reference_tol > 1e-11 {
                    reference.error_estimate
                } else {
                    0.0
                };
            println!(
                "depth control {depth}, target {target}, tol {tol:.0e}: error {error:.2e}, \
                 estimate {:.2e} (N = {}), bound {bound:.2e}",
                s.error_estimate, s.unknowns
            );
            assert!(s.error_estimate <= tol);
            assert!(
                error <= bound,
                "error {error:.2e} above the bound {bound:.2e}"
            );
        }
    }
}

/// The torus's gap is a function of `h (1 - r/a)²` alone, so states at the same `d/h` on tori
/// of different tube radii are similar: `b/a`, `c/a`, `d/h` and `F/(2 E* h a)` agree, while the
/// physical depth and force scale with `h = a²/(2ρ)`.
#[test]
fn tube_radius_scales_the_state() {
    let base = methods::solve(&torus_scene(1.0, 0.5, 1.0, "depth = 0.4"), Method::RingBem).unwrap();
    let (a, rho, es) = (3.0, 0.2, 7.0);
    let h = a * a / (2.0 * rho);
    let scaled = methods::solve(
        &torus_scene(a, rho, es, &format!("depth = {}", 0.4 * h)),
        Method::RingBem,
    )
    .unwrap();
    assert!((scaled.eps - base.eps).abs() < 1e-9);
    assert!(relative(scaled.outer_radius / a, base.outer_radius) < 1e-9);
    assert!(relative(scaled.force, 2.0 * es * h * a * base.gamma2.unwrap()) < 1e-9);
    assert_eq!(scaled.tube_radius, Some(rho));
    assert!(
        scaled.stress_intensity_rim.is_none(),
        "the torus has no rim"
    );
}

/// The paper's square-grid BEM finds both edges by its own complementarity iteration, on a
/// square it sizes itself: against the ring BEM (1e-10) its force converges as the grid is
/// refined (measured at `d = h/2`: 3.7e-4, 7.9e-5, 2.0e-5 at 64, 128, 256 cells, about second
/// order) and its edges, read off the contact cells, lie within two cells of the ring BEM's
/// (the square's half-size is below `c + 1`, so a cell is below `2 (c + 1)/N`).
#[test]
fn the_grid_bem_finds_both_edges() {
    let scene = torus_scene(1.0, 0.5, 1.0, "depth = 0.5");
    let ring = methods::solve(&scene, Method::RingBem).unwrap();
    let mut previous: Option<f64> = None;
    for n in [64, 128, 256] {
        let options = methods::MethodOptions {
            grid: Some(n),
            ..Default::default()
        };
        let grid = methods::solve_with(&scene, Method::GridBem, &options).unwrap();
        let error = relative(grid.force, ring.force);
        let cell = 2.0 * (ring.outer_radius + 1.0) / n as f64;
        println!(
            "{n}²: F {:.8} (ring {:.8}), difference {error:.1e}, band [{:.5}, {:.5}] vs \
             [{:.5}, {:.5}]",
            grid.force,
            ring.force,
            grid.inner_radius,
            grid.outer_radius,
            ring.inner_radius,
            ring.outer_radius
        );
        assert!((grid.inner_radius - ring.inner_radius).abs() < 2.0 * cell);
        assert!((grid.outer_radius - ring.outer_radius).abs() < 2.0 * cell);
        if let Some(p) = previous {
            assert!(error < 0.5 * p, "{n}²: {error:e} after {p:e}");
        }
        previous = Some(error);
    }
    assert!(previous.unwrap() < 1e-4);
}

fn verify(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_verify"))
        .args(args)
        .output()
        .unwrap()
}

/// The command line takes `--tube-radius`; the JSON carries `punch`, `tube_radius` and both
/// edges; the methods and commands that do not model two free edges say so by name; bad tube
/// radii and misplaced keys are errors naming them.
#[test]
fn command_line_json_and_refusals() {
    let out = verify(&[
        "solve",
        "--punch",
        "torus",
        "--tube-radius",
        "0.25",
        "--force",
        "0.1",
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["punch"], "torus");
    assert_eq!(json["tube_radius"], 0.25);
    let (b, c) = (
        json["inner_radius"].as_f64().unwrap(),
        json["outer_radius"].as_f64().unwrap(),
    );
    assert!(0.5 < b && b < 1.0 && 1.0 < c && c < 1.5, "band [{b}, {c}]");
    assert!(json.get("stress_intensity_rim").is_none());

    for (args, expected) in [
        (
            vec!["solve", "--punch", "torus", "--depth", "1"],
            "tube_radius",
        ),
        (
            vec![
                "solve",
                "--punch",
                "torus",
                "--tube-radius",
                "-1",
                "--depth",
                "1",
            ],
            "must be > 0",
        ),
        (
            vec![
                "solve",
                "--punch",
                "torus",
                "--tube-radius",
                "nan",
                "--depth",
                "1",
            ],
            "tube_radius",
        ),
        (
            vec![
                "solve",
                "--punch",
                "cone",
                "--tube-radius",
                "1",
                "--depth",
                "1",
            ],
            "only to shape = torus",
        ),
        (
            vec![
                "solve",
                "--punch",
                "torus",
                "--tube-radius",
                "1",
                "--eps",
                "0.5",
                "--method",
                "fem",
            ],
            "takes a depth or a force",
        ),
        (
            vec![
                "solve",
                "--punch",
                "torus",
                "--tube-radius",
                "0.5",
                "--force",
                "1e-4",
                "--method",
                "grid-bem",
                "--grid",
                "64",
            ],
            "cells wide",
        ),
        (
            vec![
                "solve",
                "--punch",
                "torus",
                "--tube-radius",
                "1",
                "--depth",
                "1",
                "--method",
                "reference",
            ],
            "no closed form",
        ),
        (
            vec!["pulloff", "--punch", "torus", "--d0h", "5"],
            "d0/h <= 1",
        ),
        (
            vec![
                "pulloff", "--punch", "torus", "--d0h", "1", "--mesh", "x.msh",
            ],
            "--mesh does not apply",
        ),
        (
            vec![
                "pulloff", "--punch", "torus", "--d0h", "1", "--ranges", "0.01",
            ],
            "use ranges rho/d0 >=",
        ),
        (
            vec![
                "solve",
                "--punch",
                "cone",
                "--depth",
                "1",
                "--method",
                "grid-bem",
                "--grid-extent",
                "1.5",
            ],
            "--grid-extent sets the square of a free band's grid",
        ),
        (
            vec![
                "solve",
                "--punch",
                "torus",
                "--tube-radius",
                "0.5",
                "--depth",
                "0.5",
                "--grid-extent",
                "1.5",
            ],
            "--grid-extent sets the square of a free band's grid",
        ),
        (
            vec![
                "solve",
                "--punch",
                "torus",
                "--tube-radius",
                "0.5",
                "--depth",
                "0.5",
                "--method",
                "grid-bem",
                "--grid",
                "64",
                "--grid-extent",
                "0.9",
            ],
            "must lie in (1, 10]",
        ),
        (
            vec![
                "solve",
                "--punch",
                "torus",
                "--tube-radius",
                "0.5",
                "--depth",
                "0.5",
                "--method",
                "grid-bem",
                "--grid",
                "64",
                "--grid-extent",
                "1.2",
            ],
            "the square must extend past the band",
        ),
    ] {
        let out = verify(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} succeeded");
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
    }
    let help = verify(&["solve", "--help"]);
    let help = String::from_utf8_lossy(&help.stdout);
    assert!(help.contains("torus") && help.contains("--tube-radius"));

    let rule = |text: &str| {
        SceneSpec::from_toml(text, "test")
            .and_then(SceneSpec::validate)
            .unwrap_err()
            .to_string()
    };
    assert!(
        rule("[punch]\nshape='torus'\nhole_depth=1\ntube_radius=1\n[load]\ndepth=1")
            .contains("punch.hole_depth")
    );
    assert!(rule("[punch]\nshape='torus'\ntube_radius=0\n[load]\ndepth=1").contains("> 0"));
    assert!(rule("[punch]\nshape='torus'\ntube_radius=1\n").contains("load"));
}
