//! Meshes that read cleanly but do not model the scene: tags swapped between groups, a domain
//! that misses part of the half-space, overlapping triangles, the wrong contact line for the
//! punch. Each must be an error naming the problem, never a confident number.
//! Built from the committed `small-domain-R5.msh` (a quarter disk of radius 5a, P1).

use std::path::PathBuf;

use ringcontact::discretisation::far_field::FarField;
use ringcontact::fem::solver::{self, FemLoad, FemOptions};
use ringcontact::mesh::triangulation::Degree;
use ringcontact::punch::PunchKind;

fn original() -> String {
    std::fs::read_to_string(solver::mesh_directory().join("small-domain-R5.msh")).unwrap()
}

/// Solve the flat punch (or `kind`) on `text`, written to a temporary file.
fn solve_text(text: &str, kind: PunchKind, name: &str) -> Result<f64, String> {
    let path: PathBuf = std::env::temp_dir().join(format!(
        "ringcontact-roles-{}-{name}.msh",
        std::process::id()
    ));
    std::fs::write(&path, text).unwrap();
    let options = FemOptions {
        linear_solver: Default::default(),
        trace: false,
        data: Default::default(),
        progress: Default::default(),
        degree: Degree::Quadratic,
        tolerance: 0.9,
        mesh: Some(path.clone()),
        poisson_ratio: 0.0,
        far_field: FarField::Boussinesq,
    };
    let load = if kind.is_concave() {
        FemLoad::ConcaveDepth(2.0)
    } else {
        FemLoad::Flat
    };
    let outcome = solver::solve(kind, 0.0, load, &options)
        .map(|s| s.gamma.or(s.gamma2).unwrap_or(f64::NAN))
        .map_err(|e| e.to_string());
    let _ = std::fs::remove_file(&path);
    outcome
}

/// Replace token `index` of line `line` (1-based) of `text`.
fn with_token(text: &str, line: usize, index: usize, value: &str) -> String {
    text.lines()
        .enumerate()
        .map(|(i, l)| {
            if i + 1 == line {
                let mut words: Vec<&str> = l.split_whitespace().collect();
                words[index] = value;
                words.join(" ")
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn line_of(text: &str, starts_with: &str) -> usize {
    text.lines()
        .position(|l| l.starts_with(starts_with))
        .map(|i| i + 1)
        .unwrap_or_else(|| panic!("no line starting with {starts_with:?}"))
}

#[test]
fn the_original_is_accepted() {
    let gamma = solve_text(&original(), PunchKind::FLAT, "original").unwrap();
    assert!((gamma - 1.0).abs() < 0.01, "{gamma}");
}

#[test]
fn swapped_far_and_axis_tags_are_an_error() {
    // Curve entities 4 (the arc, physical 3) and 5 (the axis, physical 4): swap their tags.
    let text = original();
    let arc = line_of(&text, "4 4.44");
    let axis = line_of(&text, "5 0 -5 0 0 0 0 1 4");
    let swapped = with_token(&with_token(&text, arc, 8, "4"), axis, 8, "3");
    let message = solve_text(&swapped, PunchKind::FLAT, "swapped").unwrap_err();
    println!("{message}");
    assert!(message.contains("swapped"), "{message}");
}

#[test]
fn a_domain_that_does_not_reach_the_axis_is_an_error() {
    // Shift every node 0.25 a outward in r: the axis group no longer lies on r = 0.
    let text = original();
    let start = line_of(&text, "$Nodes");
    let end = line_of(&text, "$EndNodes");
    let shifted: Vec<String> = text
        .lines()
        .enumerate()
        .map(|(i, l)| {
            let words: Vec<&str> = l.split_whitespace().collect();
            if i + 1 > start && i + 1 < end && words.len() == 3 && l.contains('.')
                || (i + 1 > start && i + 1 < end && words.len() == 3 && words[2] == "0")
            {
                let r: f64 = words[0].parse().unwrap_or(0.0);
                format!("{} {} {}", r + 0.25, words[1], words[2])
            } else {
                l.to_string()
            }
        })
        .collect();
    let message = solve_text(&shifted.join("\n"), PunchKind::FLAT, "shifted").unwrap_err();
    println!("{message}");
    assert!(
        message.contains("axis") || message.contains("contact line"),
        "{message}"
    );
}

#[test]
fn overlapping_triangles_are_an_error() {
    // Duplicate the first triangle of the solid's block under a new element tag.
    let text = original();
    let lines: Vec<&str> = text.lines().collect();
    let section = line_of(&text, "$Elements");
    let block = (section..lines.len())
        .find(|&i| {
            let w: Vec<&str> = lines[i].split_whitespace().collect();
            w.len() == 4 && w[0] == "2"
        })
        .unwrap();
    let header: Vec<&str> = lines[section].split_whitespace().collect();
    let (count, max_tag): (usize, usize) = (header[1].parse().unwrap(), header[3].parse().unwrap());
    let block_words: Vec<&str> = lines[block].split_whitespace().collect();
    let in_block: usize = block_words[3].parse().unwrap();
    let first: Vec<&str> = lines[block + 1].split_whitespace().collect();
    let mut out: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    out[section] = format!("{} {} {} {}", header[0], count + 1, header[2], max_tag + 1);
    out[block] = format!(
        "{} {} {} {}",
        block_words[0],
        block_words[1],
        block_words[2],
        in_block + 1
    );
    out.insert(
        block + 2,
        format!("{} {} {} {}", max_tag + 1, first[1], first[2], first[3]),
    );
    let message = solve_text(&out.join("\n"), PunchKind::FLAT, "overlap").unwrap_err();
    println!("{message}");
    assert!(message.contains("overlap"), "{message}");
}

#[test]
fn a_concave_punch_on_an_annulus_mesh_is_an_error() {
    let annulus = solver::mesh_directory().join("annulus-0.5-L0.msh");
    let text = std::fs::read_to_string(annulus).unwrap();
    let message = solve_text(&text, PunchKind::CONE, "annulus").unwrap_err();
    assert!(message.contains("contact line spans"), "{message}");
}
