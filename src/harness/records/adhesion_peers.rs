//! Tamaas as the peer of the pull-off simulation: its grid BEM with its
//! exponential adhesion functional on our punches and law (`scripts/peers/run_adhesion.py`,
//! stored in `verify/peers/adhesion/`), against this build's simulation at the same range.
//!
//! The law is the same (tension `(Δw/ρ) e^{-g/ρ}`, non-penetration), so the two pull-off forces
//! at one range must agree within the grid's resolution and images (the stored `uncertainty`)
//! plus our own mesh's share (the change from the study mesh to the level below it).

use serde::{Deserialize, Serialize};

use crate::harness::report::table::{verdict, Column, Format, Table};
use ringcontact::cohesive::study::{self, Case, LiveSimulation};
use ringcontact::error::{Error, Result};
use ringcontact::punch::PunchKind;

/// One of Tamaas's runs of a case (one cell and grid).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct TamaasRun {
    /// Side of the periodic cell, units of `a`.
    pub side: f64,
    pub cells: usize,
    pub pulloff_over_f0: f64,
    /// `(d/d0, F/F0)` with the isolated half-space's approach, compression positive.
    pub curve: Vec<[f64; 2]>,
    pub wall_s: f64,
}

/// A stored Tamaas pull-off.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct TamaasPulloff {
    pub package_version: String,
    #[serde(flatten)]
    pub punch: PunchKind,
    pub d0_over_h: Option<f64>,
    pub range_over_d0: f64,
    /// The finest grid's pull-off with the image correction, tensile positive, over `F0`.
    pub pulloff_over_f0: f64,
    /// The image correction's and the resolution change's sizes, summed.
    pub uncertainty: f64,
    pub runs: Vec<TamaasRun>,
    pub date: String,
    pub reproduce: String,
}

/// Tamaas's pull-off against ours on one case.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct AdhesionPeerComparison {
    pub file: String,
    #[serde(flatten)]
    pub punch: PunchKind,
    pub d0_over_h: Option<f64>,
    pub range_over_d0: f64,
    pub tabor: f64,
    pub tamaas_over_f0: f64,
    pub tamaas_uncertainty: f64,
    pub ours_over_f0: f64,
    /// Our pull-off on the level below the study mesh minus on the study mesh.
    pub our_mesh_change: f64,
    pub difference: f64,
    pub agrees: bool,
    /// Our simulation's curve on the study mesh, and Tamaas's in its largest cell.
    pub our_curve: Vec<(f64, f64, bool)>,
    pub tamaas_curve: Vec<[f64; 2]>,
    pub tamaas_version: String,
    pub our_wall_s: f64,
}

/// The stored Tamaas pull-offs (none without the directory).
pub fn load() -> Result<Vec<(String, TamaasPulloff)>> {
    let dir = crate::harness::settings::project_root().join("verify/peers/adhesion");
    if !dir.is_dir() {
        return Ok(Vec::new());
    }
    crate::harness::records::stored::load_json_dir(&dir, "Tamaas pull-off result")
}

fn case_of(stored: &TamaasPulloff) -> Case {
    Case {
        punch: stored.punch.clone(),
        eps: 0.0,
        d0_over_h: stored.d0_over_h.unwrap_or(0.0),
        linear_solver: crate::harness::settings::linear_solver(),
        data: crate::harness::settings::data_paths(),
    }
}

/// Our simulation of every stored case at its range, on the study mesh and the level below it
/// (each mesh condensed once; cases and meshes in parallel), against Tamaas's pull-off.
pub fn run() -> Result<Vec<AdhesionPeerComparison>> {
    let stored = load()?;
    let mut out = Vec::new();
    // Cases sharing a range share the simulations.
    let mut ranges: Vec<f64> = stored.iter().map(|s| s.1.range_over_d0).collect();
    ranges.sort_by(f64::total_cmp);
    ranges.dedup();
    let fine = study::study_mesh(
        &crate::harness::settings::data_paths(),
        0.0,
        study::STUDY_LEVEL,
    )?;
    let coarse = study::study_mesh(
        &crate::harness::settings::data_paths(),
        0.0,
        study::STUDY_LEVEL - 1,
    )?;
    for range in ranges {
        let here: Vec<&(String, TamaasPulloff)> = stored
            .iter()
            .filter(|s| s.1.range_over_d0 == range)
            .collect();
        if let Some((file, s)) = here.iter().find(|s| s.1.punch.has_fixed_hole()) {
            return Err(Error::Unsupported {
                method: "tamaas peer".into(),
                reason: format!("{file}: {} has no stored peer comparison", s.punch),
            });
        }
        let cases: Vec<Case> = here.iter().map(|s| case_of(&s.1)).collect();
        // The two meshes' simulations run side by side (each runs its cases in parallel too).
        let (ours, check) = rayon::join(
            || study::simulate_cases(&cases, range, &fine),
            || study::simulate_cases(&cases, range, &coarse),
        );
        let (ours, check) = (ours?, check?);
        for ((file, s), (mine, other)) in here.iter().zip(ours.into_iter().zip(check)) {
            out.push(compare(file, s, mine, &other));
        }
    }
    Ok(out)
}

fn compare(
    file: &str,
    stored: &TamaasPulloff,
    ours: LiveSimulation,
    check: &LiveSimulation,
) -> AdhesionPeerComparison {
    let mine = ours.entry.pulloff_over_f0;
    let mesh_change = check.entry.pulloff_over_f0 - mine;
    let difference = mine - stored.pulloff_over_f0;
    // The curve of the largest cell (the images' effect smallest; not corrected for them).
    let widest = stored
        .runs
        .iter()
        .max_by(|a, b| a.side.total_cmp(&b.side).then(a.cells.cmp(&b.cells)));
    AdhesionPeerComparison {
        file: file.to_string(),
        punch: stored.punch.clone(),
        d0_over_h: stored.d0_over_h,
        range_over_d0: stored.range_over_d0,
        tabor: ours.entry.tabor,
        tamaas_over_f0: stored.pulloff_over_f0,
        tamaas_uncertainty: stored.uncertainty,
        ours_over_f0: mine,
        our_mesh_change: mesh_change,
        difference,
        agrees: difference.abs() <= stored.uncertainty + mesh_change.abs(),
        our_curve: ours.curve,
        tamaas_curve: widest.map(|r| r.curve.clone()).unwrap_or_default(),
        tamaas_version: stored.package_version.clone(),
        our_wall_s: ours.wall_s,
    }
}

/// Comparisons that disagree.
pub fn failures(rows: &[AdhesionPeerComparison]) -> usize {
    rows.iter().filter(|r| !r.agrees).count()
}

/// The comparison as a table.
pub fn table(rows: &[AdhesionPeerComparison]) -> Table {
    let mut t = Table::new(
        "Pull-off: Tamaas's grid BEM with its exponential adhesion (stored) against this build's simulation, same law and range",
        vec![
            Column::text("case", "case"),
            Column::number("range_over_d0", "rho/d0", Format::Fixed(3)),
            Column::number("tabor", "Tabor", Format::Fixed(2)),
            Column::number("tamaas_over_f0", "Tamaas F/F0", Format::Fixed(4)),
            Column::number("tamaas_uncertainty", "+-", Format::Fixed(4)),
            Column::number("ours_over_f0", "ours F/F0", Format::Fixed(4)),
            Column::number("our_mesh_change", "our mesh change", Format::Scientific(1)),
            Column::number("difference", "difference", Format::Scientific(1)),
            Column::text("verdict", "verdict"),
            Column::number("our_wall_s", "our time", Format::Fixed(2)).with_unit("s"),
        ],
    );
    for r in rows {
        let case = match r.d0_over_h {
            Some(x) => format!("{} d0/h = {x}", r.punch),
            None => r.punch.to_string(),
        };
        t.push(vec![
            case.into(),
            r.range_over_d0.into(),
            r.tabor.into(),
            r.tamaas_over_f0.into(),
            r.tamaas_uncertainty.into(),
            r.ours_over_f0.into(),
            r.our_mesh_change.into(),
            r.difference.into(),
            verdict(r.agrees, "DISAGREES"),
            r.our_wall_s.into(),
        ]);
    }
    t
}
