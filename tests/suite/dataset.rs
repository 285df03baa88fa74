//! `verify dataset`: the committed small copy (verify/dataset/) is what the command makes, within
//! the error bounds it states; every column is described in datapackage.json; and the values
//! agree with independent references at the ends of their range.

use crate::common;

use std::collections::BTreeMap;
use std::path::Path;

use common::{scratch, verify};

/// The CSV at `path` as columns by name (text cells kept as NaN: only numbers are compared).
fn columns(path: &Path) -> (Vec<String>, BTreeMap<String, Vec<f64>>) {
    let mut reader = csv::Reader::from_path(path).unwrap();
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    let mut out: BTreeMap<String, Vec<f64>> =
        header.iter().map(|h| (h.clone(), Vec::new())).collect();
    for record in reader.records() {
        let record = record.unwrap();
        for (h, cell) in header.iter().zip(record.iter()) {
            out.get_mut(h)
                .unwrap()
                .push(cell.parse().unwrap_or(f64::NAN));
        }
    }
    (header, out)
}

/// The bound that goes with column `key` of a row: its `_error` column, or the relative
/// `error_estimate` times the value.
fn bound(table: &BTreeMap<String, Vec<f64>>, key: &str, row: usize, value: f64) -> f64 {
    if let Some(b) = table.get(&format!("{key}_error")) {
        return b[row];
    }
    match table.get("error_estimate") {
        Some(e) if key.starts_with("gamma") => e[row] * value.abs(),
        _ => 0.0,
    }
}

#[test]
fn the_committed_copy_is_what_the_command_makes_within_its_bounds() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let stored = root.join("verify/dataset");
    let fresh = scratch("dataset_small");
    let out = verify(&["dataset", "--small", "--out", fresh.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let package: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(stored.join("datapackage.json")).unwrap())
            .unwrap();
    let resources = package["resources"].as_array().unwrap();
    assert!(resources.len() >= 11);
    for resource in resources {
        let path = resource["path"].as_str().unwrap();
        let (header, old) = columns(&stored.join(path));
        let (fresh_header, new) = columns(&fresh.join(path));
        assert_eq!(header, fresh_header, "{path}");
        // Every column is described: name, type, and a unit for numbers.
        let fields = resource["schema"]["fields"].as_array().unwrap();
        let names: Vec<&str> = fields.iter().map(|f| f["name"].as_str().unwrap()).collect();
        assert_eq!(
            names,
            header.iter().map(String::as_str).collect::<Vec<_>>(),
            "{path}"
        );
        for f in fields {
            assert!(!f["description"].as_str().unwrap().is_empty());
            if f["type"] == "number" {
                assert!(f["unit"].is_string(), "{path}: {f}");
            }
        }
        for key in &header {
            for (row, (a, b)) in old[key].iter().zip(&new[key]).enumerate() {
                if a.is_nan() && b.is_nan() {
                    continue;
                }
                if key.ends_with("error") || key.ends_with("estimate") || key.contains("max") {
                    // Bounds and fit errors: the same to a part in 1e6.
                    assert!(
                        (a - b).abs() <= 1e-6 * a.abs().max(1e-300),
                        "{path} {key} row {row}: {a} {b}"
                    );
                    continue;
                }
                let allowed =
                    bound(&old, key, row, *a) + bound(&new, key, row, *b) + 1e-12 * a.abs();
                assert!(
                    (a - b).abs() <= allowed,
                    "{path} {key} row {row}: {a} stored, {b} now"
                );
            }
        }
        // The JSON copy holds the same rows.
        let json: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(stored.join(resource["json_copy"].as_str().unwrap())).unwrap(),
        )
        .unwrap();
        assert_eq!(
            json["rows"].as_array().unwrap().len(),
            old[&header[0]].len(),
            "{path}"
        );
    }
    assert!(package["provenance"]["commit"].is_string());
    assert!(package["provenance"]["command"]
        .as_str()
        .unwrap()
        .contains("dataset --small"));
}

#[test]
fn the_functions_meet_independent_references_at_the_ends() {
    let stored = Path::new(env!("CARGO_MANIFEST_DIR")).join("verify/dataset");
    let pi = std::f64::consts::PI;
    // Flat annulus, small hole: Collins's series gamma = 1 - 4 eps^3/(3 pi^2) + O(eps^5).
    let (_, flat) = columns(&stored.join("functions-flat-annulus.csv"));
    let (eps, gamma) = (flat["eps"][0], flat["gamma"][0]);
    assert!(
        (gamma - (1.0 - 4.0 * eps.powi(3) / (3.0 * pi * pi))).abs() < 1e-12,
        "{gamma}"
    );
    // Sphere: the hole closes at d = 3h with F = 16/3 E* h a (gamma1 -> 3, gamma2 -> 8/3).
    let (_, sphere) = columns(&stored.join("functions-sphere.csv"));
    assert!(
        (sphere["gamma1"][0] - 3.0).abs() < 1e-6,
        "{}",
        sphere["gamma1"][0]
    );
    assert!(
        (sphere["gamma2"][0] - 8.0 / 3.0).abs() < 1e-6,
        "{}",
        sphere["gamma2"][0]
    );
    // Cone, small hole: d/h = (pi/2) ln(a/b) + 1 + o(1) (docs/conventions.md fact 5).
    let (_, cone) = columns(&stored.join("functions-cone.csv"));
    let asymptote = pi / 2.0 * (1.0 / cone["eps"][0]).ln() + 1.0;
    assert!(
        (cone["gamma1"][0] - asymptote).abs() < 1e-3 * asymptote,
        "{}",
        cone["gamma1"][0]
    );
    // Torus, narrow band: the plane-strain Hertz contact of a cylinder of radius rho, force
    // per unit length pi E* w^2 / (4 rho) for half-width w, around the ring's circumference
    // 2 pi a: F = pi^2 E* a w^2 / (2 rho), so gamma2 = F/(2 E* h a) = pi^2 w^2 / 2 in units of
    // a with h = a^2/(2 rho). At w = 1e-4 a the next term, O((w/a) ln(a/w)), is about 1e-3.
    let (_, torus) = columns(&stored.join("functions-torus.csv"));
    let last = torus["eps"].len() - 1;
    let half_width = 0.5 * (torus["outer_radius"][last] - torus["eps"][last]);
    let hertz = pi * pi * half_width * half_width / 2.0;
    assert!(
        (torus["gamma2"][last] - hertz).abs() < 1e-3 * hertz,
        "{} against {hertz}",
        torus["gamma2"][last]
    );
    // Power law n = 1.5 from full contact (the method of dimensionality reduction): the rim
    // detaches at d = -d0 - h (kappa - 1), F = 2 E* a (d - h (1 - kappa/(n + 1))), with
    // kappa = sqrt(pi) Gamma(n/2 + 1) / Gamma(n/2 + 1/2); Gamma(1.75) = 0.919062526848883,
    // Gamma(1.25) = 0.906402477055477 (Abramowitz and Stegun, table 6.1).
    let (_, power) = columns(&stored.join("jkr-power-n1.5.csv"));
    let kappa = pi.sqrt() * 0.919_062_526_848_883 / 0.906_402_477_055_477;
    for (row, &s) in power["d0_over_h"].iter().enumerate() {
        let depth = -s - (kappa - 1.0);
        let force = (depth - (1.0 - kappa / 2.5)) / s;
        assert!((power["full_contact_depth"][row] - depth).abs() < 1e-12 * depth.abs());
        assert!((power["full_contact_force"][row] - force).abs() < 1e-12 * force.abs());
    }
    // Torus, weak adhesion: the plane-strain JKR cylinder (Barquins 1988) of radius rho over
    // 2 pi a: w_c = (2 rho^2 dw / (pi E*))^(1/3), P_c = -(3/4) pi E* w_c^2 / rho per unit
    // length; with h = 1 (rho = a/2), dw = s^2/(2 pi) and F0 = 2 s: F/F0 = -3 pi^2 w_c^2/(2 s).
    // The torus tends to it as d0/h falls (the band narrows).
    let (_, torus_jkr) = columns(&stored.join("jkr-torus.csv"));
    let deviations: Vec<f64> = torus_jkr["d0_over_h"]
        .iter()
        .zip(&torus_jkr["fixed_load_force"])
        .map(|(&s, &force)| {
            let w = (s * s / (4.0 * pi * pi)).cbrt();
            let cylinder = -3.0 * pi * pi * w * w / (2.0 * s);
            ((force - cylinder) / cylinder).abs()
        })
        .collect();
    assert!(deviations[0] < 1e-4, "{deviations:?}");
    assert!(deviations.windows(2).all(|d| d[0] < d[1]), "{deviations:?}");
    // Every function falls as the contact ratio grows.
    for table in [&flat, &sphere, &cone, &torus] {
        for key in ["gamma", "gamma1", "gamma2"] {
            if let Some(v) = table.get(key) {
                assert!(v.windows(2).all(|w| w[1] < w[0]), "{key}");
            }
        }
    }
}
