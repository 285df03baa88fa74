//! The harness around the solvers: stability sweep, automatic method choice, VTK output and the
//! report directory of the default run.

use std::process::Command;

use ringcontact::methods::{self, Method, MethodOptions};
use ringcontact::punch::PunchKind;
use ringcontact::scene::SceneSpec;
use ringcontact_verify::harness::studies::stability;

#[test]
fn no_method_returns_a_wrong_number_without_an_error() {
    let probes = stability::run(|_| {});
    assert_eq!(
        probes.len(),
        stability::PROBES,
        "update PROBES (the progress bar length)"
    );
    let wrong: Vec<_> = probes.iter().filter(|p| p.outcome == "WRONG").collect();
    assert!(
        wrong.is_empty(),
        "wrong numbers without an error: {wrong:?}"
    );
    // Each method is driven past its limits at least once and declines there.
    for method in ["ring-bem", "fem", "grid-bem"] {
        assert!(
            probes
                .iter()
                .any(|p| p.method == method && p.outcome == "error"),
            "{method} never declined"
        );
    }
}

/// `--method auto` on a validated scene.
fn auto(spec: SceneSpec) -> ringcontact::solution::Solution {
    let scene = spec.validate().unwrap();
    methods::solve_with(&scene, Method::Auto, &MethodOptions::default()).unwrap()
}

#[test]
fn auto_picks_the_cheapest_method_that_meets_the_tolerance() {
    let s = auto(
        SceneSpec::default()
            .shape(PunchKind::CONE)
            .depth(2.0)
            .tolerance(1e-6),
    );
    assert_eq!(s.method, "ring-bem");
    assert!(s.selection.unwrap().contains("cheapest"));
    // A ring 1e-5 a wide at 1e-6: the ring BEM's range ends at 1e-4 a and the FEM's rim
    // elements would have to be below 1e-10 a; the narrow-ring asymptote (bound 4e-10) answers.
    let s = auto(
        SceneSpec::default()
            .shape(PunchKind::FLAT_ANNULUS)
            .inner_ratio(0.99999)
            .tolerance(1e-6),
    );
    assert_eq!(s.method, "reference:narrow-ring");
    assert!(s.error_estimate.unwrap() <= 1e-9);
}

/// Where the ring BEM declines (the cone's contact nearly closed), `--method auto` chooses the
/// FEM. Its full contact is bounded by the first node off the axis, which the committed meshes
/// do not bring within 1e-3 a: gmsh makes the mesh that does.
#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn auto_picks_the_fem_where_the_ring_bem_declines() {
    let s = auto(
        SceneSpec::default()
            .shape(PunchKind::CONE)
            .depth(60.0)
            .tolerance(1e-3),
    );
    assert_eq!(s.method, "fem");
    assert!(s.error_estimate.unwrap() <= 1e-3);
}

#[test]
fn fem_fields_are_written_as_vtk() {
    let dir = std::env::temp_dir().join(format!("ringcontact-vtu-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("flat.vtu");
    let scene = SceneSpec::default()
        .shape(PunchKind::FLAT)
        .validate()
        .unwrap();
    let options = MethodOptions {
        vtu: Some(path.clone()),
        ..MethodOptions::default()
    };
    let s = methods::solve_with(&scene, Method::Fem, &options).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(
        text.starts_with("<?xml")
            && text.contains("UnstructuredGrid")
            && text.contains("Name=\"displacement\"")
    );
    assert!(text.contains(&format!(
        "NumberOfPoints=\"{}\"",
        s.fem.as_ref().unwrap().dofs / 2
    )));
    let e = methods::solve_with(&scene, Method::RingBem, &options).unwrap_err();
    assert!(e.to_string().contains("--vtu"));
}

#[test]
fn the_default_run_writes_a_report_directory() {
    let dir = std::env::temp_dir().join(format!("ringcontact-report-{}", std::process::id()));
    let out = Command::new(env!("CARGO_BIN_EXE_verify"))
        .args(["compare", "--report", dir.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("report.md"));
    for file in [
        "report.md",
        "report.json",
        "speed-accuracy-0.svg",
        "speed-accuracy-1.svg",
        "gamma-flat-annulus.svg",
        "pressure-sphere.svg",
        "pulloff-sphere.svg",
        "convergence-fem.svg",
    ] {
        assert!(dir.join(file).exists(), "missing {file}");
    }
    // Every chart the report shows is written, the table punch's among them (its label is its
    // profile's hash: `verify/profiles/sphere-21.csv`).
    let markdown = std::fs::read_to_string(dir.join("report.md")).unwrap();
    for chart in markdown.split("![](").skip(1) {
        let name = &chart[..chart.find(')').unwrap()];
        assert!(
            dir.join(name).exists(),
            "the report shows {name}, not written"
        );
    }
    // The units the report's tables use are defined in it.
    for (unit, definition) in [("F0", "F0 = sqrt("), ("d0", "d0 = sqrt(")] {
        assert!(
            !markdown.contains(unit) || markdown.contains(definition),
            "the report uses {unit} and does not define it"
        );
    }
    for prefix in ["gammas-table-", "pulloff-table-"] {
        assert!(
            markdown.contains(&format!("![]({prefix}")),
            "no {prefix}* chart in the report"
        );
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).unwrap()).unwrap();
    // The table's checks against the sphere it samples are counted, and pass.
    let table_checks: Vec<&serde_json::Value> = json["comparison"]["identities"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|c| c["name"].as_str().unwrap().starts_with("table ("))
        .collect();
    assert_eq!(table_checks.len(), 3, "{table_checks:?}");
    assert!(
        table_checks.iter().all(|c| c["passed"] == true),
        "{table_checks:?}"
    );
    let points = json["extras"]["speed_accuracy"][0]["points"]
        .as_array()
        .unwrap();
    assert!(points.iter().any(|p| p["on_pareto_front"] == true));
}
