//! FEniCSx as the external finite-element reference (results stored by `scripts/fenicsx/`).
//!
//! Each stored result is re-solved here with exactly FEniCSx's model (same mesh file, element
//! degree, quadrature, boundary conditions, no truncation correction: `--mesh M --degree k`), and
//! the two codes must agree to solver tolerance: force within 1e-8 relative and the same active
//! contact set. A result whose mesh file changed since it was stored (SHA-256 mismatch) is stale:
//! it is reported and not used. Both codes are also shown against the ring BEM, so discretisation
//! error and code agreement are seen apart.

use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::{Deserialize, Serialize};

use crate::harness::report::table::{verdict, Cell, Column, Format, Table};
use crate::harness::studies::{unit_scene, UnitLoad};
use ringcontact::error::{Error, Result};
use ringcontact::methods::Degree;
use ringcontact::methods::FarField;
use ringcontact::methods::{Fem, RingBem};
use ringcontact::punch::{Contact, PunchKind};

/// Relative force agreement required of two codes solving the identical discrete problem.
pub const FORCE_AGREEMENT: f64 = 1e-8;

/// One stored FEniCSx result (`verify/fenicsx/*.json`).
#[derive(Clone, Debug, Deserialize, Serialize)]
pub struct FenicsxResult {
    #[serde(flatten)]
    pub punch: PunchKind,
    pub mesh: String,
    pub mesh_sha256: String,
    pub degree: u8,
    pub depth: f64,
    pub eps: Option<f64>,
    pub force: f64,
    pub inner_radius: Option<f64>,
    pub active_contact_radii: Vec<f64>,
    pub dofs: usize,
    pub iterations: usize,
    pub wall_s: f64,
    pub dolfinx_version: String,
    pub petsc_version: String,
    pub date: String,
    pub reproduce: String,
    /// For a mesh made by gmsh (not committed): the `-setnumber` parameters that remake it from
    /// `meshes/half_space.geo` (`verify mesh` prints them). The harness remakes the mesh when the
    /// stored path is missing and checks its SHA-256.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mesh_parameters: Option<Vec<(String, f64)>>,
}

/// What the harness made of one stored result.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct FenicsxComparison {
    pub file: String,
    pub stored: FenicsxResult,
    /// `current`, `stale` (mesh changed), `missing-mesh`, or `needs-gmsh` (a generated mesh that
    /// cannot be remade here).
    pub status: String,
    pub our_force: Option<f64>,
    pub relative_difference: Option<f64>,
    pub same_active_set: Option<bool>,
    pub our_wall_s: Option<f64>,
    /// Ours / FEniCSx's wall time on the same problem: this run's single solve over the stored
    /// run's, measured apart (no speed result: `benches/records/fenicsx-speed.json` is).
    pub wall_time_ratio: Option<f64>,
    /// Ring-BEM force at the same state (the yardstick) and both codes' errors against it.
    pub ring_bem_force: Option<f64>,
    pub fenicsx_error: Option<f64>,
    pub our_error: Option<f64>,
    pub passed: bool,
}

/// Root of the repository (where `meshes/` and `verify/` live): the project root the mesh
/// provider uses ([`crate::harness::settings::project_root`]).
pub(crate) fn repository_root() -> PathBuf {
    crate::harness::settings::project_root()
}

/// Directory of the stored FEniCSx results.
pub fn results_directory() -> PathBuf {
    repository_root().join("verify").join("fenicsx")
}

/// Directory of the stored FEniCSx results on the largest meshes (5e5 to 1.5e6 unknowns): compared
/// only on request (`verify fenicsx --large`, the nightly run), since our solves of them take
/// 4-12 s each and their meshes 5-9 s of gmsh when not cached.
pub fn large_results_directory() -> PathBuf {
    results_directory().join("large")
}

/// Read every stored result, sorted by file name.
pub fn load_results(dir: &Path) -> Result<Vec<(String, FenicsxResult)>> {
    crate::harness::records::stored::load_json_dir(dir, "FEniCSx result")
}

/// Compare one stored result with our FEM on the identical problem.
pub fn compare(file: &str, stored: &FenicsxResult, ring: &RingBem) -> Result<FenicsxComparison> {
    let mesh_path = repository_root().join(&stored.mesh);
    let mut out = FenicsxComparison {
        file: file.to_string(),
        stored: stored.clone(),
        status: "current".into(),
        our_force: None,
        relative_difference: None,
        same_active_set: None,
        our_wall_s: None,
        wall_time_ratio: None,
        ring_bem_force: None,
        fenicsx_error: None,
        our_error: None,
        passed: false,
    };
    let mesh_path = match (&stored.mesh_parameters, mesh_path.exists()) {
        (_, true) => mesh_path,
        (Some(parameters), false) => {
            match ringcontact::mesh::provider::generate(
                &crate::harness::settings::data_paths(),
                parameters,
                &format!("FEniCSx result {file}"),
            ) {
                Ok(provided) => provided.path,
                Err(_) => {
                    out.status = "needs-gmsh".into();
                    return Ok(out);
                }
            }
        }
        (None, false) => {
            out.status = "missing-mesh".into();
            return Ok(out);
        }
    };
    if ringcontact::mesh::provider::sha256_file(&mesh_path)? != stored.mesh_sha256 {
        out.status = "stale".into();
        return Ok(out);
    }
    let degree = Degree::from_number(stored.degree).ok_or_else(|| Error::Unsupported {
        method: "fenicsx".into(),
        reason: format!("{file}: degree {}", stored.degree),
    })?;
    let (eps, load) = match stored.punch.contact() {
        Contact::Disk => (0.0, UnitLoad::Flat),
        Contact::FixedAnnulus => (stored.eps.unwrap_or(0.0), UnitLoad::Flat),
        Contact::RimAndFreeInner | Contact::FreeBand => (0.0, UnitLoad::Depth(stored.depth)),
    };
    // FEniCSx's model: its mesh and degree, the far arc held fixed, the FEM's default tolerance.
    let fem = Fem {
        mesh: Some(mesh_path),
        degree: Some(degree),
        far_field: Some(FarField::Fixed),
        ..crate::harness::settings::fem()
    };
    let scene = unit_scene(stored.punch.clone(), eps, load, None)?;
    let start = Instant::now();
    let ours = fem.state(&scene)?;
    let our_wall = start.elapsed().as_secs_f64();
    // Flat punches: F = 2 γ d; concave (h = 1): F = 2 γ2.
    let our_force = match load {
        UnitLoad::Flat => 2.0 * ours.gamma.unwrap_or(f64::NAN) * stored.depth,
        UnitLoad::Depth(_) => 2.0 * ours.gamma2.unwrap_or(f64::NAN),
    };
    let relative = (our_force - stored.force) / stored.force;
    let same_active = same_active_set(&ours.active_radii, &stored.active_contact_radii, degree);
    let ring_force = match load {
        UnitLoad::Flat => ring.flat(eps, 1e-10)?.gamma.map(|g| 2.0 * g * stored.depth),
        UnitLoad::Depth(_) => ring
            .concave_at_depth(&stored.punch, stored.depth, 1e-10)?
            .gamma2
            .map(|g| 2.0 * g),
    };
    out.our_force = Some(our_force);
    out.relative_difference = Some(relative);
    out.same_active_set = Some(same_active);
    out.our_wall_s = Some(our_wall);
    out.wall_time_ratio = Some(our_wall / stored.wall_s);
    out.ring_bem_force = ring_force;
    out.fenicsx_error = ring_force.map(|r| (stored.force - r) / r);
    out.our_error = ring_force.map(|r| (our_force - r) / r);
    out.passed = relative.abs() <= FORCE_AGREEMENT && same_active;
    Ok(out)
}

/// Whether our contact nodes `ours` are FEniCSx's `theirs`. P1/P2: the contact dofs sit at the
/// same points in both codes, compared one by one. P3: dolfinx places the edge dofs at warped
/// (GLL) points, ours at thirds (the same space, so the same solution of a linear problem): the
/// count and the ring's ends are compared, an end that is an edge dof to within the distance of
/// those two points (GLL 0.2764 against 1/3 of the edge: 0.057 of the element, a sixth of the
/// dof spacing there).
fn same_active_set(ours: &[f64], theirs: &[f64], degree: Degree) -> bool {
    if ours.len() != theirs.len() {
        return false;
    }
    if degree != Degree::Cubic {
        return ours.iter().zip(theirs).all(|(a, b)| (a - b).abs() <= 1e-9);
    }
    let inner_spacing = match ours.len() {
        0 | 1 => 0.0,
        _ => ours[1] - ours[0],
    };
    let outer_spacing = match ours.len() {
        0 | 1 => 0.0,
        n => ours[n - 1] - ours[n - 2],
    };
    let ends = |r: &[f64]| (r.first().copied(), r.last().copied());
    let (a, b) = (ends(ours), ends(theirs));
    let close = |x: Option<f64>, y: Option<f64>, spacing: f64| match (x, y) {
        (Some(x), Some(y)) => (x - y).abs() <= 1e-9_f64.max(spacing / 5.0),
        _ => false,
    };
    close(a.0, b.0, inner_spacing) && close(a.1, b.1, outer_spacing)
}

/// Compare every stored result of `verify/fenicsx/` (the default set).
pub fn run() -> Result<Vec<FenicsxComparison>> {
    run_with(false)
}

/// Compare every stored result, and with `large` those of [`large_results_directory`] too
/// (their files named `large/NAME.json`), printing one progress line per large model to stderr.
pub(crate) fn run_with(large: bool) -> Result<Vec<FenicsxComparison>> {
    let ring = RingBem::new();
    let mut rows = load_results(&results_directory())?
        .iter()
        .map(|(file, stored)| compare(file, stored, &ring))
        .collect::<Result<Vec<_>>>()?;
    if large {
        let stored = load_results(&large_results_directory())?;
        for (i, (file, result)) in stored.iter().enumerate() {
            eprintln!(
                "fenicsx --large: {}/{} large/{file} ({} dofs)",
                i + 1,
                stored.len(),
                result.dofs
            );
            rows.push(compare(&format!("large/{file}"), result, &ring)?);
        }
    }
    Ok(rows)
}

/// Number of failures: disagreements, results that could not be compared because their mesh
/// changed or vanished (`stale`, `missing-mesh`), and a run that compared nothing at all (one
/// failure). Results waiting for gmsh (`needs-gmsh`) are listed with the command that installs it,
/// not failures: a fresh clone has no gmsh.
pub fn failures(rows: &[FenicsxComparison]) -> usize {
    let disagreements = rows
        .iter()
        .filter(|r| r.status == "current" && !r.passed)
        .count();
    let uncompared = rows
        .iter()
        .filter(|r| r.status == "stale" || r.status == "missing-mesh")
        .count();
    let compared = rows.iter().filter(|r| r.status == "current").count();
    disagreements + uncompared + usize::from(compared == 0)
}

/// One line on what was and was not compared: `compared N of M stored; not compared: files`.
pub fn coverage(rows: &[FenicsxComparison]) -> String {
    let compared = rows.iter().filter(|r| r.status == "current").count();
    let missed: Vec<String> = rows
        .iter()
        .filter(|r| r.status != "current")
        .map(|r| format!("{} ({})", r.file, r.status))
        .collect();
    let mut line = format!(
        "compared {compared} of {} stored FEniCSx results",
        rows.len()
    );
    if compared == 0 {
        line.push_str(": NOTHING COMPARED (a failure)");
    }
    if !missed.is_empty() {
        line.push_str(&format!("; not compared: {}", missed.join(", ")));
    }
    line
}

/// The stored FEniCSx results against our FEM: one row each (stale ones with the remedy).
pub fn table(rows: &[FenicsxComparison]) -> Table {
    let mut t = Table::new(
        "FEniCSx (stored) against our FEM on the identical discrete problem",
        vec![
            Column::text("result", "stored result"),
            Column::number("dofs", "dofs", Format::Fixed(0)),
            Column::number(
                "relative_difference",
                "rel. diff",
                Format::SignedScientific(1),
            ),
            Column::text("active_set", "active set"),
            Column::number("fenicsx_error", "FEniCSx err", Format::SignedScientific(2)),
            Column::number("our_error", "our err", Format::SignedScientific(2)),
            Column::text("verdict", "verdict"),
        ],
    );
    for r in rows {
        let current = r.status == "current";
        let active = match r.same_active_set {
            Some(true) => Cell::Text("same".into()),
            Some(false) => Cell::Flag("DIFFERENT".into()),
            None => Cell::Missing,
        };
        let verdict_cell = if current {
            verdict(r.passed, "FAIL")
        } else if r.status == "needs-gmsh" {
            Cell::Text(format!(
                "NEEDS GMSH (mesh {}): not used; bash scripts/install_gmsh.sh remakes it",
                r.stored.mesh
            ))
        } else {
            Cell::Text(format!(
                "{} (mesh {}): not used; refresh with python3 scripts/fenicsx/run_all.py --out verify/fenicsx",
                r.status.to_uppercase(),
                r.stored.mesh
            ))
        };
        t.push(vec![
            r.file.clone().into(),
            (r.stored.dofs as f64).into(),
            r.relative_difference.into(),
            active,
            r.fenicsx_error.into(),
            r.our_error.into(),
            verdict_cell,
        ]);
    }
    t
}

/// Human-readable: [`table`] under the pass rule, and what was covered.
pub fn render(rows: &[FenicsxComparison]) -> String {
    let mut out = format!(
        "\nPass: force within {FORCE_AGREEMENT:.0e} and the same active set; both against the \
         ring BEM.\n"
    );
    out += &table(rows).to_terminal();
    if rows.is_empty() {
        out +=
            "  (no stored results; run python3 scripts/fenicsx/run_all.py --out verify/fenicsx)\n";
    }
    out += &format!("  {}\n", coverage(rows));
    out += &speed_note();
    out
}

/// Where the two codes' speeds are compared: the interleaved benchmark record (the times of the
/// rows above are single runs on different days, so their quotient is no result).
fn speed_note() -> String {
    match crate::harness::records::benchmarks::FenicsxSpeed::load() {
        Ok(record) => {
            let (lo, hi) = record.ratio_range();
            format!(
                "  Speed, measured interleaved ({} rounds, {}, commit {}): our time over \
                 FEniCSx's fastest configuration {lo:.2} to {hi:.2} from the mesh file to the \
                 force (benches/records/fenicsx-speed.md).\n",
                record.provenance.rounds, record.provenance.date, record.provenance.commit
            )
        }
        Err(e) => format!("  Speed: no interleaved record ({e}).\n"),
    }
}
