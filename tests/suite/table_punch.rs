//! The table punch (`--punch table --profile FILE`): a concave punch whose profile is a CSV table
//! of `(r/a, g/h)` points, interpolated by monotone cubics (PCHIP).
//!
//! Independent checks: tables sampled from the sphere's profile `1 - (r/a)²` at 6 to 41 points,
//! solved by the ring BEM (through the flat band's fields, `crates/ringcontact/src/bem/ring_contact/piecewise_gap.rs`)
//! and by the FEM at `--tol 1e-7`, tend to the sphere's converged ring-BEM state (1e-12) as the
//! table is refined, and agree with each other within the FEM's estimate. Two facts bound the
//! difference from the sphere: the contact problem is monotone in the gap, so a gap within `δ` of
//! the sphere's changes `γ2 = F/(2 E* h a)` at a given depth by at most `δ` (the force's slope in
//! the depth is at most `2 E* a`), and `δ` falls at least as the square of the spacing (the
//! interpolant's order next to the axis, `crates/ringcontact/src/punch/table.rs`). A state the ring BEM's single
//! annulus cannot model is refused with the reason, and bad tables are errors naming the line.

use crate::common;
use common::assert_study_converges;

use std::path::{Path, PathBuf};
use std::process::Command;

use ringcontact::methods::RingBem;
use ringcontact::punch::{PunchKind, PunchName};

/// A table of the sphere's profile at `points` equally spaced radii, written to a fresh file.
fn sphere_table(dir: &Path, points: usize) -> PathBuf {
    profile_table(dir, &format!("sphere-{points}.csv"), points, |r| {
        1.0 - r * r
    })
}

/// A table of the profile `g(r/a)` at `points` equally spaced radii, written to `dir/name`.
fn profile_table(dir: &Path, name: &str, points: usize, g: impl Fn(f64) -> f64) -> PathBuf {
    let mut text = String::from("r/a,g/h\n");
    for k in 0..points {
        let r = k as f64 / (points - 1) as f64;
        text.push_str(&format!("{r},{}\n", g(r)));
    }
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ringcontact-table-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn verify(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_verify"))
        .args(args)
        .output()
        .unwrap()
}

/// Largest difference between the table's interpolant and the sphere's profile.
fn profile_error(kind: PunchKind) -> f64 {
    (0..=20000)
        .map(|k| k as f64 / 20000.0)
        .map(|rho| (kind.gap_shape(rho) - (1.0 - rho * rho)).abs())
        .fold(0.0, f64::max)
}

#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn sampled_sphere_tends_to_the_sphere_as_the_table_is_refined() {
    let dir = scratch("convergence");
    let sphere = RingBem::new()
        .concave_at_depth(&PunchKind::SPHERE, 1.0, 1e-12)
        .unwrap();
    let reference = sphere.gamma2.unwrap();
    let mut errors = Vec::new();
    for points in [6, 11, 21, 41] {
        let path = sphere_table(&dir, points);
        let kind = PunchName::Table.with_parameters(None, Some(&path)).unwrap();
        let out = verify(&[
            "solve",
            "--punch",
            "table",
            "--profile",
            path.to_str().unwrap(),
            "--depth",
            "1",
            "--method",
            "fem",
            "--tol",
            "1e-7",
            "--json",
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(json["punch"], "table");
        assert_eq!(json["profile_file"], path.to_str().unwrap());
        assert_eq!(json["profile_sha256"].as_str().map(str::len), Some(64));
        let gamma2 = json["gamma2"].as_f64().unwrap();
        let estimate = json["error_estimate"].as_f64().unwrap();
        // The ring BEM on the same table: within the FEM's estimate (two independent methods
        // on the same piecewise-cubic gap).
        let ring = RingBem::new().concave_at_depth(&kind, 1.0, 1e-10).unwrap();
        let ring_gamma2 = ring.gamma2.unwrap();
        assert!(
            (ring_gamma2 - gamma2).abs() <= estimate * gamma2 + 1e-10 * ring_gamma2,
            "{points} points: ring BEM {ring_gamma2} against FEM {gamma2} (estimate {estimate:.1e})"
        );
        let error = (gamma2 - reference).abs();
        let bound = profile_error(kind) + estimate * reference;
        eprintln!("{points} points: γ2 off by {error:.2e}, bound {bound:.2e}, FEM estimate {estimate:.1e}");
        assert!(estimate <= 1e-7, "{json}");
        assert!(error <= bound, "{points} points: {error:e} > {bound:e}");
        errors.push(error);
    }
    for pair in errors.windows(2) {
        // Halving the spacing: at least the interpolant's second order (measured: 13 to 20).
        assert!(pair[0] / pair[1] > 4.0, "{errors:?}");
    }
}

/// The ring BEM alone (no gmsh): the sampled sphere's `γ2` at `d = h` tends to the sphere's at
/// the interpolant's order, inside the monotonicity bound, each solve within its own estimate of
/// 1e-10 (the kinks of the table do not slow the ring BEM's convergence).
#[test]
fn the_ring_bem_tends_to_the_sphere_as_the_table_is_refined() {
    let dir = scratch("ring-convergence");
    let solver = RingBem::new();
    let reference = solver
        .concave_at_depth(&PunchKind::SPHERE, 1.0, 1e-12)
        .unwrap()
        .gamma2
        .unwrap();
    let mut errors = Vec::new();
    for points in [6, 11, 21, 41, 81] {
        let path = sphere_table(&dir, points);
        let kind = PunchName::Table.with_parameters(None, Some(&path)).unwrap();
        let state = solver.concave_at_depth(&kind, 1.0, 1e-10).unwrap();
        assert!(state.error_estimate <= 1e-10, "{points} points: {state:?}");
        let error = (state.gamma2.unwrap() - reference).abs();
        let bound = profile_error(kind) + 1e-10 * reference;
        eprintln!("{points} points: γ2 off by {error:.2e}, bound {bound:.2e}");
        assert!(error <= bound, "{points} points: {error:e} > {bound:e}");
        errors.push(error);
    }
    for pair in errors.windows(2) {
        assert!(pair[0] / pair[1] > 4.0, "{errors:?}");
    }
}

/// A table sampled from a steep-walled profile, `1 - (r/a)^20` at 81 points, under depth
/// control: solved (its search starts from the sphere of the table's rim slope; from the
/// sphere's own fit it wandered inside the hole and stopped after 60 solves), and within the
/// monotonicity bound of the power law's state: `γ2` at a given depth moves by at most the
/// largest difference of the gaps.
#[test]
fn a_steep_walled_table_is_solved_near_its_power_law() {
    let dir = scratch("steep");
    let path = profile_table(&dir, "power-20.csv", 81, |r| 1.0 - r.powi(20));
    let table = PunchName::Table.with_parameters(None, Some(&path)).unwrap();
    let power = PunchName::Power.with_exponent(Some(20.0)).unwrap();
    let gap_difference = (0..=20000)
        .map(|k| f64::from(k) / 20000.0)
        .map(|rho| (table.gap_shape(rho) - power.gap_shape(rho)).abs())
        .fold(0.0, f64::max);
    let solver = RingBem::new();
    for depth in [0.5, 0.9, 1.2] {
        let state = solver
            .concave_at_depth(&table, depth, 1e-9)
            .unwrap_or_else(|e| panic!("d/h = {depth}: {e}"));
        let reference = solver.concave_at_depth(&power, depth, 1e-10).unwrap();
        let (gamma2, reference) = (state.gamma2.unwrap(), reference.gamma2.unwrap());
        let bound = gap_difference + 1e-9 * reference;
        assert!(
            (gamma2 - reference).abs() <= bound,
            "d/h = {depth}: γ2 {gamma2} against the power law's {reference} (bound {bound:.1e})"
        );
    }
}

#[test]
fn auto_picks_the_ring_bem_for_a_table() {
    let out = verify(&[
        "solve",
        "--punch",
        "table",
        "--profile",
        "verify/profiles/sphere-21.csv",
        "--force",
        "1",
        "--method",
        "auto",
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["method"], "ring-bem", "{json}");
    assert!(json["error_estimate"].as_f64().unwrap() <= 1e-6, "{json}");
}

/// The sampled sphere's PCHIP is a little flatter than the sphere next to the axis, so just
/// below its closure (`d = 2.99 h`; it closes at 3.018 h) the punch touches the floor of its hole
/// (by 5.7e-5 h at `r = 0.021 a`): a disk and an annulus, which the ring BEM refuses with the
/// reason (as the power law's n > 2).
#[test]
fn the_ring_bem_names_a_table_state_it_cannot_model() {
    let out = verify(&[
        "solve",
        "--punch",
        "table",
        "--profile",
        "verify/profiles/sphere-21.csv",
        "--depth",
        "2.99",
        "--method",
        "ring-bem",
    ]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("floor of its hole") && stderr.contains("disk and an annulus"),
        "{stderr}"
    );
}

/// States beyond what the ring BEM's single annulus reaches are refused with the reason, not
/// after a search that wandered for 60 solves: a cosine dimple `(1 + cos(π r/a))/2` sampled at
/// 41 points (whose interpolant has a tiny slope at the axis, so its hole never closes) at
/// `d = 8 h`, where the ring would be narrower than the table's band functionals resolve
/// (`b < 1e-3 a`; at `1e-4 a` they gave `γ1 = -1322` and the search wandered); and the cube
/// `1 - (r/a)^3` sampled at 41 points under `F/(2 E* h a) = 2`, short of its full contact, whose
/// contact is a disk and an annulus (named as for the power law `n = 3`, whose full contact
/// also opens on a ring).
#[test]
fn states_beyond_the_single_annulus_are_refused_with_the_reason() {
    let dir = scratch("beyond");
    let cosine = profile_table(&dir, "cosine.csv", 41, |r| {
        0.5 * (1.0 + (std::f64::consts::PI * r).cos())
    });
    let cube = profile_table(&dir, "cube.csv", 41, |r| 1.0 - r.powi(3));
    for (path, flag, value, reason) in [
        (
            &cosine,
            "--depth",
            "8",
            "needs a contact ratio outside [0.001",
        ),
        (&cube, "--force", "4", "floor of its hole"),
    ] {
        let out = verify(&[
            "solve",
            "--punch",
            "table",
            "--profile",
            path.to_str().unwrap(),
            flag,
            value,
            "--method",
            "ring-bem",
        ]);
        assert!(!out.status.success());
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains(reason), "{flag} {value}: {stderr}");
    }
    // Short of them the same tables solve.
    let solver = RingBem::new();
    for (path, depth) in [(&cosine, 4.0), (&cube, 1.0)] {
        let kind = PunchName::Table.with_parameters(None, Some(path)).unwrap();
        let state = solver.concave_at_depth(&kind, depth, 1e-9).unwrap();
        assert!(state.error_estimate <= 1e-9, "{state:?}");
    }
}

#[test]
fn bad_tables_and_misplaced_flags_are_named() {
    let dir = scratch("bad");
    let unsorted = dir.join("unsorted.csv");
    std::fs::write(&unsorted, "r/a,g/h\n0,1\n0.6,0.5\n0.4,0.7\n1,0\n").unwrap();
    let unsorted = unsorted.to_str().unwrap();
    let cases: [(&[&str], &str); 5] = [
        (&["--punch", "table", "--profile", unsorted], "line 4"),
        (&["--punch", "table"], "needs its profile"),
        (
            &["--punch", "cone", "--profile", unsorted],
            "applies only to shape = table",
        ),
        (
            &["--punch", "table", "--profile", "no/such/file.csv"],
            "cannot read",
        ),
        (
            &["--punch", "table", "--profile", unsorted, "--exponent", "2"],
            "exponent",
        ),
    ];
    for (flags, expected) in cases {
        let mut args = vec!["solve"];
        args.extend_from_slice(flags);
        args.extend(["--depth", "1", "--method", "grid-bem", "--grid", "32"]);
        let out = verify(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            !out.status.success() && stderr.contains(expected),
            "{flags:?}: {stderr}"
        );
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}

#[test]
fn a_scene_file_reads_its_profile_beside_itself() {
    let dir = scratch("scene");
    sphere_table(&dir, 11);
    let scene = dir.join("tip.toml");
    std::fs::write(
        &scene,
        "[punch]\nshape = \"table\"\nprofile = \"sphere-11.csv\"\nhole_depth = 0.5\n\
         [load]\ndepth = 0.5\n",
    )
    .unwrap();
    let out = verify(&[
        "solve",
        "--scene",
        scene.to_str().unwrap(),
        "--method",
        "grid-bem",
        "--grid",
        "64",
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["punch"], "table");
    // d = h: the sphere's γ1 = 1 state, force 2 E* h a γ2 with γ2 = 0.756 (ring BEM), within
    // the 64² grid's discretisation error (a few per cent).
    let gamma2 = json["gamma2"].as_f64().unwrap();
    assert!((gamma2 - 0.7563).abs() < 0.05 * 0.7563, "{json}");
}

/// JKR of a table (`verify jkr --punch table`): the sampled sphere's fixed-load pull-off tends to
/// the sphere's as the table is refined, and a fresh solve of each critical state meets the
/// Griffith condition at its inner edge (the band of the table solved directly, not through the
/// branch formulas). At `d0/h = 1` the error falls at least as the interpolant's second order per
/// halving of the spacing; under weak adhesion (`d0/h` = 0.1 to 0.42) the pull-off ring is
/// narrow and sits at the rim, where it feels the profile's curvature, which a `C¹` interpolant
/// converges at first order only (measured: 2.1x per halving at `d0/h = 0.1`). There the
/// table's force against the contact ratio has extra local extrema (the interpolant's curvature
/// steps at its points): the pull-off is the lowest force after unloading starts, not the first
/// local minimum, which is a jump to a narrower ring at the same force (a compressive "pull-off"
/// of `+22 F0` at `d0/h = 0.1` before that was understood).
#[test]
fn the_jkr_pulloff_of_a_sampled_sphere_tends_to_the_spheres() {
    let dir = scratch("jkr");
    let solver = RingBem::new();
    let scales = [0.1, 0.178, 0.422, 1.0];
    let sphere = ringcontact::adhesion::ConcaveBranch::new(&solver, PunchKind::SPHERE).unwrap();
    let references: Vec<f64> = scales
        .iter()
        .map(|&s| sphere.jkr(s).unwrap().fixed_load.unwrap().force)
        .collect();
    let mut errors = vec![Vec::new(); scales.len()];
    for points in [11, 21, 41] {
        let path = sphere_table(&dir, points);
        let kind = PunchName::Table.with_parameters(None, Some(&path)).unwrap();
        let branch = ringcontact::adhesion::ConcaveBranch::new(&solver, kind).unwrap();
        for (k, &s) in scales.iter().enumerate() {
            let jkr = branch.jkr(s).unwrap();
            let ratio = jkr.direct_inner_energy_ratio.unwrap();
            assert!(
                (ratio - 1.0).abs() < 1e-8,
                "{points} points, d0/h = {s}: G/Δw = {ratio}"
            );
            let critical = jkr.fixed_load.unwrap();
            let error = (critical.force - references[k]).abs();
            eprintln!("{points} points, d0/h = {s}: pull-off off by {error:.2e}");
            assert!(
                error < 1e-3 * references[k].abs(),
                "{points} points, d0/h = {s}: F/F0 = {} against the sphere's {}",
                critical.force,
                references[k]
            );
            errors[k].push(error);
        }
    }
    for (k, &s) in scales.iter().enumerate() {
        let order = if s >= 1.0 { 4.0 } else { 1.5 };
        for pair in errors[k].windows(2) {
            assert!(pair[0] / pair[1] > order, "d0/h = {s}: {:?}", errors[k]);
        }
    }
}

/// `verify convergence --punch table --profile FILE`: the FEM's levels on the table converge
/// toward the ring BEM's state of the same table (the yardstick, an independent method), and
/// the finest level's error bar bounds its actual error; a profile on another punch is refused.
#[test]
fn a_convergence_study_of_a_table_is_bounded_by_its_bar() {
    let out = verify(&[
        "convergence",
        "--punch",
        "table",
        "--profile",
        "verify/profiles/sphere-21.csv",
        "--method",
        "fem",
        "--levels",
        "3",
        "--json",
        "--out",
        scratch("convergence").to_str().unwrap(),
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(json["profile_file"], "verify/profiles/sphere-21.csv");
    assert_study_converges(&json, "fem", 1e-4);
    let out = verify(&[
        "convergence",
        "--punch",
        "cone",
        "--profile",
        "verify/profiles/sphere-21.csv",
        "--method",
        "fem",
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("applies only to shape = table"));
}

/// The sphere's gap `1 - (r/a)²`, declared by a user as two pieces meeting at `r = a/2`: a
/// profile of their own that is only piecewise smooth (as far as the solver knows).
#[derive(Debug)]
struct SphereInPieces;

impl ringcontact::punch::Profile for SphereInPieces {
    fn name(&self) -> &str {
        "sphere-in-pieces"
    }
    fn contact(&self) -> ringcontact::punch::Contact {
        ringcontact::punch::Contact::RimAndFreeInner
    }
    fn gap(&self, rho: f64) -> f64 {
        1.0 - rho * rho
    }
    fn slope(&self, rho: f64) -> f64 {
        -2.0 * rho
    }
    fn piecewise(&self) -> Option<&dyn ringcontact::punch::PiecewiseProfile> {
        Some(self)
    }
}

impl ringcontact::punch::PiecewiseProfile for SphereInPieces {
    fn value(&self, rho: f64) -> f64 {
        1.0 - rho * rho
    }
    fn increment(&self, rho: f64, offset: f64) -> f64 {
        -(2.0 * rho + offset) * offset
    }
    fn slope(&self, rho: f64) -> f64 {
        -2.0 * rho
    }
    fn curvature(&self, _rho: f64) -> f64 {
        -2.0
    }
    fn break_points(&self) -> &[f64] {
        &[0.0, 0.5, 1.0]
    }
    fn content_key(&self) -> &str {
        "sphere-in-pieces"
    }
}

/// A user's own profile that declares itself piecewise takes the piecewise route (the band
/// through the flat band's fields, panel by panel between its break points) with no table and
/// no registry; on the sphere's gap it finds the state the analytic collocation of the built-in
/// sphere finds, within the two estimates (two routes through the ring BEM).
#[test]
fn a_users_own_piecewise_profile_takes_the_piecewise_route() {
    let solver = RingBem::new();
    let own = PunchKind::new(SphereInPieces);
    assert!(own.piecewise().is_some());
    for depth in [0.5, 1.5] {
        let pieces = solver.concave_at_depth(&own, depth, 1e-10).unwrap();
        let sphere = solver
            .concave_at_depth(&PunchKind::SPHERE, depth, 1e-12)
            .unwrap();
        let allowed = pieces.error_estimate + sphere.error_estimate + 1e-12;
        let (g2, g2_sphere) = (pieces.gamma2.unwrap(), sphere.gamma2.unwrap());
        println!(
            "d/h {depth}: gamma2 {g2:.14} pieces, {g2_sphere:.14} sphere; b/a {:.14} {:.14}; \
             estimates {:.1e} {:.1e}",
            pieces.eps, sphere.eps, pieces.error_estimate, sphere.error_estimate
        );
        assert!(
            (g2 / g2_sphere - 1.0).abs() <= allowed,
            "gamma2 {g2} {g2_sphere}"
        );
        assert!((pieces.eps - sphere.eps).abs() <= allowed, "eps");
    }
}
