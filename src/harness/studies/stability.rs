//! `verify stability`: drive every method toward its limits and classify what comes back.
//!
//! Each probe solves one scene through the common interface and compares the answer with an
//! independent reference (Boussinesq, Collins, the narrow-ring asymptote, MDR full contact, the
//! converged ring BEM). Outcomes:
//! * `error` - the method declined with an error (the rule: what it can detect, it reports);
//! * `ok` - a number within the method's own error estimate (plus the reference's bound);
//! * `no estimate` - a number the method does not certify (single mesh or grid): its actual error
//!   is listed so the reader sees how far such numbers go wrong;
//! * `WRONG` - a number outside its own estimate: a wrong number without an error. The harness
//!   fails when it finds one.

use serde::Serialize;

use ringcontact::error::Result;
use ringcontact::methods::RingBem;
use ringcontact::methods::{self, Method, MethodOptions};
use ringcontact::punch::PunchKind;
use ringcontact::reference::asymptotic::{collins_series, narrow_ring};

use super::UnitLoad;
use crate::harness::cases;
use ringcontact::scene::{Scene, SceneSpec};

use crate::harness::report::table::{Cell, Column, Format, Table};

/// One probe and what happened.
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct Probe {
    pub method: String,
    pub probe: String,
    pub outcome: String,
    pub value: Option<f64>,
    pub reference: Option<f64>,
    pub relative_error: Option<f64>,
    pub error_estimate: Option<f64>,
    pub message: Option<String>,
}

/// Value and bound of the independent reference of a scene, if there is one.
type Reference = Option<(f64, f64)>;

fn flat_reference(ring: &RingBem, eps: f64) -> Reference {
    if eps <= 0.05 {
        let r = collins_series(eps);
        return Some((r.value, r.error_bound.unwrap_or(0.0) + 1e-13));
    }
    if eps >= 0.9999 {
        let r = narrow_ring(eps);
        return Some((r.value, r.error_bound.unwrap_or(0.0)));
    }
    ring.flat(eps, 1e-12)
        .ok()
        .and_then(|s| s.gamma.map(|g| (g, 1e-12 * g)))
}

/// Past its closure the contact is the disk and `dγ2/d(d/h) = 1`: `γ2 = γ2_c + (γ1 - d_c)`
/// from the closure `(d_c, γ2_c)` the profile declares, exact.
fn beyond_closure(kind: &PunchKind, depth: f64) -> Reference {
    let (closure_depth, closure_force) = kind.closure()?;
    (depth >= closure_depth).then_some((closure_force + (depth - closure_depth), 0.0))
}

fn concave_reference(ring: &RingBem, kind: PunchKind, depth: f64) -> Reference {
    if let Some(reference) = beyond_closure(&kind, depth) {
        return Some(reference);
    }
    ring.concave_at_depth(&kind, depth, 1e-11)
        .ok()
        .and_then(|s| s.gamma2.map(|g| (g, 1e-11 * g)))
}

fn probe(
    method: Method,
    options: &MethodOptions,
    name: String,
    scene: Result<Scene>,
    reference: Reference,
) -> Probe {
    let mut p = Probe {
        method: method.name().to_string(),
        probe: name,
        outcome: String::new(),
        value: None,
        reference: reference.map(|r| r.0),
        relative_error: None,
        error_estimate: None,
        message: None,
    };
    let solution = scene.and_then(|s| methods::solve_with(&s, method, options));
    match solution {
        Err(e) => {
            p.outcome = "error".into();
            p.message = Some(e.to_string());
        }
        Ok(s) => {
            let value = s.gamma.or(s.gamma2).unwrap_or(f64::NAN);
            p.value = Some(value);
            p.error_estimate = s.error_estimate;
            if let Some((r, bound)) = reference {
                let err = (value - r).abs() / r.abs();
                p.relative_error = Some(err);
                p.outcome = match s.error_estimate {
                    None => "no estimate".into(),
                    Some(e) if err <= e + bound / r.abs() + 1e-13 => "ok".into(),
                    Some(_) => "WRONG".into(),
                };
            } else {
                p.outcome = if s.error_estimate.is_some() {
                    "ok (no reference)".into()
                } else {
                    "no estimate".into()
                };
            }
        }
    }
    p
}

/// A probe whose only right answer is an error (an overflowing load, a mesh that does not model
/// the scene): any number is `WRONG`.
fn must_decline(
    method: Method,
    options: &MethodOptions,
    name: &str,
    scene: Result<Scene>,
) -> Probe {
    let solution = scene.and_then(|s| methods::solve_with(&s, method, options));
    Probe {
        method: method.name().to_string(),
        probe: name.to_string(),
        outcome: if solution.is_err() { "error" } else { "WRONG" }.into(),
        value: solution
            .as_ref()
            .ok()
            .map(|s| s.gamma.or(s.gamma2).unwrap_or(f64::NAN)),
        reference: None,
        relative_error: None,
        error_estimate: solution.as_ref().ok().and_then(|s| s.error_estimate),
        message: solution.err().map(|e| e.to_string()),
    }
}

/// The committed `small-domain-R5.msh` with the physical tags of its arc (3) and axis (4)
/// swapped, written to a temporary file.
fn swapped_tag_mesh() -> Option<std::path::PathBuf> {
    let text = std::fs::read_to_string(
        crate::harness::settings::mesh_directory().join("small-domain-R5.msh"),
    )
    .ok()?;
    let swapped: Vec<String> = text
        .lines()
        .map(|line| {
            let mut words: Vec<&str> = line.split_whitespace().collect();
            // Curve entities: tag, 6 bounds, 1 physical tag, the tag, ...
            if words.len() >= 9 && words[7] == "1" && (words[8] == "3" || words[8] == "4") {
                words[8] = if words[8] == "3" { "4" } else { "3" };
                words.join(" ")
            } else {
                line.to_string()
            }
        })
        .collect();
    let path = std::env::temp_dir().join(format!(
        "ringcontact-stability-swapped-{}.msh",
        std::process::id()
    ));
    std::fs::write(&path, swapped.join("\n")).ok()?;
    Some(path)
}

/// The disk (`eps = 0`) or the fixed annulus of `b/a = eps` on the unit scene.
fn flat_scene(eps: f64) -> Result<Scene> {
    super::unit_scene(cases::flat_punch(eps), eps, UnitLoad::Flat, None)
}

/// A punch's name as words, hyphens as spaces.
fn words(kind: &PunchKind) -> String {
    kind.name().replace('-', " ")
}

/// A concave punch at depth `d/h` on the unit scene.
fn concave_scene(kind: PunchKind, depth: f64, tolerance: Option<f64>) -> Result<Scene> {
    super::unit_scene(kind, 0.0, UnitLoad::Depth(depth), tolerance)
}

/// Number of probes [`run`] makes (for progress display).
pub const PROBES: usize = 43;

/// Run all probes, calling `progress` as each one ends.
pub fn run(mut progress: impl FnMut(&Probe)) -> Vec<Probe> {
    let ring = RingBem::new();
    let mut probes = Vec::new();
    let mut push = |p: Probe| {
        progress(&p);
        probes.push(p);
    };
    ring_bem_probes(&ring, &mut push);
    fem_probes(&ring, &mut push);
    grid_bem_probes(&ring, &mut push);
    push(iteration_cap_probe());
    declined_probes(&mut push);
    reference_probes(&ring, &mut push);
    probes
}

/// Ring BEM: eps -> 0 and -> 1, the open hole's blow-up, the closing hole at the edge of full
/// contact, a tolerance below its rounding floor.
fn ring_bem_probes(ring: &RingBem, push: &mut impl FnMut(Probe)) {
    let none = MethodOptions::default();
    let punches = cases::stability_punches();
    let annulus = words(&punches.annulus);
    for eps in [0.0, 1e-5, 1e-4, 1e-3, 0.5, 0.999, 0.9999, 0.99999] {
        let p = probe(
            Method::RingBem,
            &none,
            format!("{annulus} b/a = {eps}"),
            flat_scene(eps),
            flat_reference(ring, eps),
        );
        push(p);
    }
    let (open, open_depths) = &punches.open_hole;
    for &depth in open_depths.iter() {
        let reference = None; // the ring BEM is its own yardstick here; MDR limits are in the tests
        let p = probe(
            Method::RingBem,
            &none,
            format!("{open} d/h = {depth}"),
            concave_scene(open.clone(), depth, None),
            reference,
        );
        push(p);
    }
    let (closing, closing_depths) = &punches.closing_hole;
    for &depth in closing_depths.iter() {
        let p = probe(
            Method::RingBem,
            &none,
            format!("{closing} d/h = {depth}"),
            concave_scene(closing.clone(), depth, None),
            beyond_closure(closing, depth),
        );
        push(p);
    }
    let p = probe(
        Method::RingBem,
        &none,
        format!("{annulus} b/a = 0.5, tolerance 1e-15"),
        SceneSpec::default()
            .shape(punches.annulus.clone())
            .inner_ratio(0.5)
            .tolerance(1e-15)
            .validate(),
        flat_reference(ring, 0.5),
    );
    push(p);
}

/// FEM: default ladder, tolerances it cannot reach, coarse single meshes, P1.
fn fem_probes(ring: &RingBem, push: &mut impl FnMut(Probe)) {
    let none = MethodOptions::default();
    for (eps, tol) in [(0.0, 1e-3), (0.5, 1e-4), (0.9, 1e-5)] {
        let scene = flat_scene(eps).map(|s| Scene {
            tolerance: Some(tol),
            ..s
        });
        let p = probe(
            Method::Fem,
            &none,
            format!("flat b/a = {eps}, tolerance {tol:.0e}"),
            scene,
            flat_reference(ring, eps),
        );
        push(p);
    }
    let punches = cases::stability_punches();
    let disk = &punches.disk;
    for (kind, depth) in punches.fem_states {
        let p = probe(
            Method::Fem,
            &none,
            format!("{kind} d/h = {depth}"),
            concave_scene(kind.clone(), depth, None),
            concave_reference(ring, kind, depth),
        );
        push(p);
    }
    let coarse = MethodOptions {
        mesh: Some(crate::harness::settings::mesh_directory().join("disk-L0.msh")),
        degree: Some(ringcontact::methods::Degree::Linear),
        ..crate::harness::settings::method_options()
    };
    let p = probe(
        Method::Fem,
        &coarse,
        format!("{disk}, coarsest mesh L0, P1 (single mesh)"),
        flat_scene(0.0),
        flat_reference(ring, 0.0),
    );
    push(p);
    let small = MethodOptions {
        mesh: Some(crate::harness::settings::mesh_directory().join("small-domain-R5.msh")),
        ..crate::harness::settings::method_options()
    };
    let p = probe(
        Method::Fem,
        &small,
        format!("{disk}, small domain R = 5a (single mesh)"),
        flat_scene(0.0),
        flat_reference(ring, 0.0),
    );
    push(p);
}

/// Grid BEM: rings narrower than the cells, coarse grids, near full contact.
fn grid_bem_probes(ring: &RingBem, push: &mut impl FnMut(Probe)) {
    let punches = cases::stability_punches();
    let annulus = words(&punches.annulus);
    for (eps, n) in [(0.9, 64), (0.97, 64), (0.99, 64), (0.99, 512)] {
        let options = MethodOptions {
            grid: Some(n),
            ..crate::harness::settings::method_options()
        };
        let p = probe(
            Method::GridBem,
            &options,
            format!("{annulus} b/a = {eps}, {n}²"),
            flat_scene(eps),
            flat_reference(ring, eps),
        );
        push(p);
    }
    for (kind, depth, n) in punches.grid_states {
        let options = MethodOptions {
            grid: Some(n),
            ..crate::harness::settings::method_options()
        };
        let p = probe(
            Method::GridBem,
            &options,
            format!("{kind} d/h = {depth}, {n}²"),
            concave_scene(kind.clone(), depth, None),
            concave_reference(ring, kind, depth),
        );
        push(p);
    }
}

/// Iteration caps: Polonsky-Keer stopped after 3 iterations must be an error, not a number.
fn iteration_cap_probe() -> Probe {
    let (closing, _) = cases::stability_punches().closing_hole;
    let capped = ringcontact::methods::GridBem {
        cells: 64,
        with_estimate: false,
        max_iterations: Some(3),
        ..Default::default()
    };
    let outcome = concave_scene(closing.clone(), 1.5, None).and_then(|s| capped.state(&s));
    Probe {
        method: "grid-bem".into(),
        probe: format!("{closing} d/h = 1.5, 64², iteration cap 3"),
        outcome: if outcome.is_err() {
            "error".into()
        } else {
            "WRONG".into()
        },
        value: outcome.as_ref().ok().map(|c| c.force),
        reference: None,
        relative_error: None,
        error_estimate: None,
        message: outcome.err().map(|e| e.to_string()),
    }
}

/// Loads whose results overflow, and meshes that do not model the scene: only an error is
/// right.
fn declined_probes(push: &mut impl FnMut(Probe)) {
    let none = MethodOptions::default();
    let punches = cases::stability_punches();
    let (disk, open) = (&punches.disk, &punches.open_hole.0);
    let overflowing = [disk, open, &punches.closing_hole.0].map(|kind| (kind.clone(), 1e308));
    for (kind, depth) in overflowing {
        let scene = SceneSpec::default()
            .shape(kind.clone())
            .depth(depth)
            .validate();
        let p = must_decline(Method::RingBem, &none, &format!("{kind} d = 1e308"), scene);
        push(p);
    }
    let mesh_options = |path: std::path::PathBuf| MethodOptions {
        mesh: Some(path),
        ..crate::harness::settings::method_options()
    };
    let swapped = swapped_tag_mesh();
    let p = must_decline(
        Method::Fem,
        &mesh_options(swapped.clone().unwrap_or_default()),
        &format!("{disk} on a mesh with far and axis tags swapped"),
        flat_scene(0.0),
    );
    push(p);
    if let Some(path) = swapped {
        let _ = std::fs::remove_file(path);
    }
    let annulus = crate::harness::settings::mesh_directory().join("annulus-0.5-L0.msh");
    let p = must_decline(
        Method::Fem,
        &mesh_options(annulus.clone()),
        &format!("{open} on an annulus mesh (contact line from r = b)"),
        concave_scene(open.clone(), 2.0, None),
    );
    push(p);
    let p = must_decline(
        Method::Fem,
        &mesh_options(annulus),
        &format!("{disk} punch on an annulus mesh"),
        flat_scene(0.0),
    );
    push(p);
}

/// References outside their ranges.
fn reference_probes(ring: &RingBem, push: &mut impl FnMut(Probe)) {
    let none = MethodOptions::default();
    let annulus = words(&cases::stability_punches().annulus);
    for eps in [0.5, 0.95] {
        let p = probe(
            Method::Reference,
            &none,
            format!("{annulus} b/a = {eps}"),
            flat_scene(eps),
            flat_reference(ring, eps),
        );
        push(p);
    }
}

/// Number of wrong numbers without an error.
pub(crate) fn wrong_numbers(probes: &[Probe]) -> usize {
    probes.iter().filter(|p| p.outcome == "WRONG").count()
}

/// One row per probe: outcome, error against the reference, own estimate, the message.
pub fn table(probes: &[Probe]) -> Table {
    let mut t = Table::new(
        "Stability: every method toward its limits (error = declined, ok = within its own \
         estimate, no estimate = uncertified number, WRONG = wrong number without error)",
        vec![
            Column::text("method", "method"),
            Column::text("probe", "probe"),
            Column::text("outcome", "outcome"),
            Column::number("relative_error", "rel. error", Format::Scientific(1)),
            Column::number("error_estimate", "estimate", Format::Scientific(0)),
            Column::text("message", "note"),
        ],
    );
    for p in probes {
        t.push(vec![
            p.method.clone().into(),
            p.probe.clone().into(),
            if p.outcome == "WRONG" {
                Cell::Flag(p.outcome.clone())
            } else {
                Cell::Text(p.outcome.clone())
            },
            p.relative_error.into(),
            p.error_estimate.into(),
            p.message
                .as_deref()
                .map(|m| m.chars().take(90).collect::<String>())
                .unwrap_or_default()
                .into(),
        ]);
    }
    t
}

/// Table for the terminal: [`table`], then a summary per method.
pub fn render(probes: &[Probe]) -> String {
    use std::fmt::Write;
    let mut out = table(probes).to_terminal();
    let _ = writeln!(
        out,
        "\nPer method: where it met its tolerance, and how it declined outside:"
    );
    for method in ["ring-bem", "fem", "grid-bem", "reference"] {
        let of = |outcome: &str| -> Vec<&str> {
            probes
                .iter()
                .filter(|p| p.method == method && p.outcome.starts_with(outcome))
                .map(|p| p.probe.as_str())
                .collect()
        };
        let _ = writeln!(
            out,
            "  {method}: ok on {}; declined on {}; uncertified numbers on {}",
            list(&of("ok")),
            list(&of("error")),
            list(&of("no estimate"))
        );
    }
    let wrong = wrong_numbers(probes);
    let _ = writeln!(
        out,
        "\n{} probes; {} declined with an error; {} wrong numbers without an error.",
        probes.len(),
        probes.iter().filter(|p| p.outcome == "error").count(),
        wrong
    );
    out
}

fn list(items: &[&str]) -> String {
    if items.is_empty() {
        "none".into()
    } else {
        items.join(", ")
    }
}
