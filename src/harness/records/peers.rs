//! Tamaas and ContactMechanics (stored results of `scripts/peers/run_peers.sh --out verify/peers`) against our
//! square-grid BEM on identical grids and profiles: the force at the same depth must agree within
//! 1e-6 relative (same discretisation: piecewise-constant pressure on square cells, Love kernel,
//! 2N zero padding).

use std::path::PathBuf;

use serde::{Deserialize, Serialize};

use crate::harness::report::table::{verdict, Column, Format, Table};
use ringcontact::error::Result;
use ringcontact::methods::{self, Method, MethodOptions};
use ringcontact::punch::PunchKind;
use ringcontact::solution::Solution;

/// Relative force agreement required on the same grid.
pub const PEER_AGREEMENT: f64 = 1e-6;

/// One stored peer result (`verify/peers/*.json`).
#[derive(Clone, Debug, Deserialize, Serialize)]
pub struct PeerResult {
    pub package: String,
    pub package_version: String,
    #[serde(flatten)]
    pub punch: PunchKind,
    pub eps: Option<f64>,
    pub grid: usize,
    /// A free band's square half-size `L/a` (the other punches' grid is `[-a, a]²`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grid_extent: Option<f64>,
    pub depth: f64,
    pub force: f64,
    pub wall_s: f64,
    pub date: String,
    pub reproduce: String,
}

/// One comparison.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct PeerComparison {
    pub file: String,
    pub stored: PeerResult,
    pub our_force: f64,
    pub our_iterations: usize,
    /// Wall time of our solve in this run, seconds (in the report's run it is solved beside
    /// other parts: a record, not a benchmark; the speed-against-accuracy study times the grid
    /// BEM alone).
    pub our_wall_s: f64,
    pub relative_difference: f64,
    pub passed: bool,
}

/// Directory of the stored peer results.
pub fn results_directory() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("verify")
        .join("peers")
}

/// Load every stored peer result, sorted by file name.
pub fn load_results() -> Result<Vec<(String, PeerResult)>> {
    crate::harness::records::stored::load_json_dir(&results_directory(), "peer result")
}

/// `(punch, b/a bits, grid, square half-size bits, depth bits)`: one state of the grid BEM.
type StateKey = (PunchKind, u64, usize, u64, u64);
/// `(force, iterations, wall seconds)` of a solved state.
type Solved = (f64, usize, f64);

/// Compare every stored result with our grid BEM on the same grid (each distinct state solved
/// once). `max_grid` skips larger grids (to keep quick runs quick).
pub fn run(max_grid: usize) -> Result<Vec<PeerComparison>> {
    let mut cache: Vec<(StateKey, Solved)> = Vec::new();
    let mut rows = Vec::new();
    for (file, stored) in load_results()? {
        if stored.grid > max_grid {
            continue;
        }
        let eps = stored.eps.unwrap_or(0.0);
        let key = (
            stored.punch.clone(),
            eps.to_bits(),
            stored.grid,
            stored.grid_extent.unwrap_or(1.0).to_bits(),
            stored.depth.to_bits(),
        );
        let (force, iterations, wall) = match cache.iter().find(|(k, _)| *k == key) {
            Some((_, v)) => *v,
            None => {
                let depth = if stored.punch.is_concave() {
                    stored.depth
                } else {
                    1.0
                };
                let solved = match (stored.punch.is_free_band(), stored.grid_extent) {
                    (true, Some(_)) | (false, None) => {
                        our_grid_bem(&stored.punch, eps, depth, stored.grid, stored.grid_extent)
                    }
                    (true, None) | (false, Some(_)) => {
                        Err(ringcontact::error::Error::Unsupported {
                            method: Method::GridBem.name().into(),
                            reason: "grid_extent (the square's half-size) is stored for a \
                                     free band, and only for it"
                                .into(),
                        })
                    }
                };
                let s = solved.map_err(|e| {
                    ringcontact::error::Error::file(
                        "compare the stored peer result",
                        &results_directory().join(&file),
                        e,
                    )
                })?;
                // Flat punches are linear in the depth.
                let force = if stored.punch.is_concave() {
                    s.force
                } else {
                    s.force * stored.depth
                };
                let v = (force, s.iterations, s.wall_s);
                cache.push((key, v));
                v
            }
        };
        let relative = (force - stored.force) / stored.force;
        rows.push(PeerComparison {
            file,
            stored,
            our_force: force,
            our_iterations: iterations,
            our_wall_s: wall,
            relative_difference: relative,
            passed: relative.abs() <= PEER_AGREEMENT,
        });
    }
    Ok(rows)
}

/// Our grid BEM as the peers run theirs: the requested grid alone (no error estimate), on the
/// unit scene (`a = E* = 1`; `h = 1`, a free band's tube radius `a/2`), at depth `d/h`
/// (`eps`: the fixed annulus's `b/a`), to a complementarity residual of 1e-11.
fn our_grid_bem(
    punch: &PunchKind,
    eps: f64,
    depth: f64,
    cells: usize,
    extent: Option<f64>,
) -> Result<Solution> {
    let scene = crate::harness::studies::unit_spec(punch.clone(), eps)
        .depth(depth)
        .tolerance(1e-11)
        .validate()?;
    let options = MethodOptions {
        grid: Some(cells),
        grid_extent: extent,
        grid_without_estimate: true,
        ..crate::harness::settings::method_options()
    };
    methods::solve_with(&scene, Method::GridBem, &options)
}

/// Number of disagreements, plus one if nothing was compared.
pub fn failures(rows: &[PeerComparison]) -> usize {
    rows.iter().filter(|r| !r.passed).count() + usize::from(rows.is_empty())
}

/// The stored peer results against our grid BEM on the same grids.
pub fn table(rows: &[PeerComparison]) -> Table {
    let mut t = Table::new(
        "Tamaas and ContactMechanics (stored) against our grid BEM on the same grids",
        vec![
            Column::text("result", "stored result"),
            Column::number("grid", "grid", Format::Fixed(0)),
            Column::number("peer_force", "peer force", Format::Fixed(10)),
            Column::number(
                "relative_difference",
                "rel. diff",
                Format::SignedScientific(1),
            ),
            Column::text("verdict", "verdict"),
        ],
    );
    for r in rows {
        t.push(vec![
            r.file.clone().into(),
            (r.stored.grid as f64).into(),
            r.stored.force.into(),
            r.relative_difference.into(),
            verdict(r.passed, "FAIL"),
        ]);
    }
    t
}

/// Human-readable: [`table`] under its pass rule.
pub fn render(rows: &[PeerComparison]) -> String {
    let mut out = format!("\nPass: force within {PEER_AGREEMENT:.0e}.\n");
    out += &table(rows).to_terminal();
    if rows.is_empty() {
        out += "  (no stored results; run bash scripts/peers/run_peers.sh --out verify/peers)\n";
    }
    out
}
