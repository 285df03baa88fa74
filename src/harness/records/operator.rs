//! The assembled operator compared with FEniCSx's: the identical discrete problem checked at the
//! matrix, not only at the force.
//!
//! `scripts/fenicsx/export.py` writes FEniCSx's stiffness matrix, unit-pressure load vector and
//! dof positions for a mesh and degree; [`compare_operator`] assembles ours on the same mesh,
//! matches the dofs by position and component (to `1e-11 max(1, |x|)`: dolfinx recomputes node
//! coordinates, 1e-12 off at `r = 1e5 a`), and reports the largest entry-wise difference relative
//! to the largest entry, `max |K_ours - P K_fenicsx Pᵀ| / max |K_ours|`, and the same for the load.
//!
//! The matrices are too large to commit (a P2 model of 3.4 k dofs is 2.5 MB): each comparison
//! made is stored as a small JSON under `verify/fenicsx/operators/` ([`OperatorRecord`]), and
//! `verify fenicsx` re-makes it where FEniCSx's export directory is present.

use std::collections::HashMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::harness::report::table::{verdict, Column, Format, Table};
use ringcontact::discretisation::export::{
    assemble_system, load_mesh, read_dofs, read_matrix, DofRecord,
};
use ringcontact::error::{Error, Result};
use ringcontact::methods::Degree;

/// What one operator comparison found.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct OperatorComparison {
    /// Mesh file compared on, as given.
    pub mesh: String,
    /// SHA-256 of that file.
    pub mesh_sha256: String,
    pub degree: u8,
    pub dofs: usize,
    /// Stored entries of our matrix and of FEniCSx's.
    pub nnz_ours: usize,
    pub nnz_fenicsx: usize,
    /// `max |K_ours - P K_fenicsx Pᵀ| / max |K_ours|` over the union of both patterns.
    pub stiffness_difference: f64,
    /// `max |f_ours - P f_fenicsx| / max |f_ours|`.
    pub load_difference: f64,
    /// Largest distance between matched dof positions.
    pub position_difference: f64,
}

impl OperatorComparison {
    /// Whether both differences are at most [`OPERATOR_GOAL`].
    pub fn meets_goal(&self) -> bool {
        self.stiffness_difference <= OPERATOR_GOAL && self.load_difference <= OPERATOR_GOAL
    }
}

/// The comparisons as a [`Table`] (terminal, Markdown, CSV, JSON, HTML).
pub fn table(rows: &[OperatorComparison]) -> Table {
    let mut t = Table::new(
        &format!(
            "Assembled operator against FEniCSx's (dofs matched by position; goal: max \
             entry-wise difference / max entry <= {OPERATOR_GOAL:e}):"
        ),
        vec![
            Column::number("mesh", "mesh", Format::Fixed(0)),
            Column::number("degree", "degree", Format::Fixed(0)),
            Column::number("dofs", "dofs", Format::Fixed(0)),
            Column::number("nnz", "nnz", Format::Fixed(0)),
            Column::number("nnz_fenicsx", "nnz FEniCSx", Format::Fixed(0)),
            Column::number("stiffness_difference", "K diff", Format::Scientific(1)),
            Column::number("load_difference", "load diff", Format::Scientific(1)),
            Column::number("verdict", "verdict", Format::Fixed(0)),
        ],
    );
    for r in rows {
        t.push(vec![
            r.mesh.clone().into(),
            format!("P{}", r.degree).into(),
            (r.dofs as f64).into(),
            (r.nnz_ours as f64).into(),
            (r.nnz_fenicsx as f64).into(),
            r.stiffness_difference.into(),
            r.load_difference.into(),
            verdict(r.meets_goal(), "ABOVE GOAL"),
        ]);
    }
    t
}

/// A terminal table of comparisons.
pub fn render(rows: &[OperatorComparison]) -> String {
    table(rows).to_terminal()
}

/// A stored comparison (`scripts/fenicsx/operators.py`): what was compared, FEniCSx's
/// versions, when, and the commands that remake it.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct OperatorRecord {
    #[serde(flatten)]
    pub comparison: OperatorComparison,
    pub dolfinx_version: String,
    pub petsc_version: String,
    /// Lagrange variant of FEniCSx's element (`equispaced`: the nodes ours uses).
    pub fenicsx_lagrange_variant: String,
    pub date: String,
    pub reproduce: String,
}

/// A stored record and whether its mesh is still the one compared.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct OperatorStatus {
    pub file: String,
    #[serde(flatten)]
    pub record: OperatorRecord,
    /// `current` (the mesh file is there with the stored SHA-256), `stale` (it changed) or
    /// `mesh absent` (neither at its stored path nor made from its `reproduce` parameters:
    /// gmsh is needed for a generated mesh).
    pub status: String,
}

/// Directory of the stored operator comparisons.
pub(crate) fn records_directory() -> std::path::PathBuf {
    crate::harness::records::fenicsx::results_directory().join("operators")
}

/// Every stored operator comparison, with its status (none when the directory is missing:
/// [`failures`] then counts one, and [`render_records`] says that nothing was compared).
pub fn load_records() -> Result<Vec<OperatorStatus>> {
    let root = crate::harness::records::fenicsx::repository_root();
    if !records_directory().is_dir() {
        return Ok(Vec::new());
    }
    crate::harness::records::stored::load_json_dir::<OperatorRecord>(
        &records_directory(),
        "operator comparison",
    )?
    .into_iter()
    .map(|(file, record)| {
        let status = match locate_mesh(&root, &record, &file) {
            None => "mesh absent".to_string(),
            Some(mesh)
                if ringcontact::mesh::provider::sha256_file(&mesh)?
                    == record.comparison.mesh_sha256 =>
            {
                "current".to_string()
            }
            Some(_) => "stale".to_string(),
        };
        Ok(OperatorStatus {
            file,
            record,
            status,
        })
    })
    .collect()
}

/// A record's mesh: at its stored path, else made (or found in the cache) by gmsh from the
/// `--mesh-parameters` of its `reproduce` command. A generated mesh's cache name follows the
/// geometry file's bytes, so a stored cache path goes stale when that file changes while the
/// mesh it named (its SHA-256, which the caller checks) is made again unchanged. `None` when
/// neither is there (no parameters, or gmsh is not installed or fails).
fn locate_mesh(root: &Path, record: &OperatorRecord, file: &str) -> Option<std::path::PathBuf> {
    let stored = root.join(&record.comparison.mesh);
    if stored.exists() {
        return Some(stored);
    }
    let parameters = mesh_parameters_of(&record.reproduce)?;
    let why = format!("FEniCSx operator comparison {file}");
    ringcontact::mesh::provider::generate(
        &crate::harness::settings::data_paths(),
        &parameters,
        &why,
    )
    .ok()
    .map(|made| made.path)
}

/// The `NAME=VALUE,...` after `--mesh-parameters` in a `reproduce` command, parsed.
fn mesh_parameters_of(reproduce: &str) -> Option<Vec<(String, f64)>> {
    let mut words = reproduce.split_whitespace();
    words.find(|word| *word == "--mesh-parameters")?;
    ringcontact::mesh::provider::parse_parameters(words.next()?).ok()
}

/// Stored comparisons that are current and above the goal (1 when there are none: nothing was
/// compared).
pub fn failures(rows: &[OperatorStatus]) -> usize {
    if rows.is_empty() {
        return 1;
    }
    rows.iter()
        .filter(|r| r.status == "current" && !r.record.comparison.meets_goal())
        .count()
}

/// Terminal table of the stored comparisons.
pub(crate) fn render_records(rows: &[OperatorStatus]) -> String {
    if rows.is_empty() {
        return format!(
            "Assembled operator against FEniCSx's: NOTHING COMPARED (no stored comparisons in \
             {}; make them with python3 scripts/fenicsx/operators.py --out verify/fenicsx/operators)\n",
            records_directory().display()
        );
    }
    let mut out = render(
        &rows
            .iter()
            .map(|r| r.record.comparison.clone())
            .collect::<Vec<_>>(),
    );
    out.push_str(&format!(
        "  {} stored comparisons (verify/fenicsx/operators/), {} current, {} above the goal; \
         remake them with python3 scripts/fenicsx/operators.py --out verify/fenicsx/operators\n",
        rows.len(),
        rows.iter().filter(|r| r.status == "current").count(),
        rows.iter()
            .filter(|r| !r.record.comparison.meets_goal())
            .count()
    ));
    out
}

/// Goal of the issue for the relative entry-wise difference.
pub const OPERATOR_GOAL: f64 = 1e-12;

fn mismatch(path: &Path, message: String) -> Error {
    Error::InvalidMesh {
        path: path.display().to_string(),
        message,
    }
}

/// For every dof of `theirs`, the index of ours at the same position and component.
fn match_dofs(ours: &[DofRecord], theirs: &[DofRecord], dir: &Path) -> Result<(Vec<usize>, f64)> {
    let tolerance = |d: &DofRecord| 1e-11 * d.r.abs().max(d.z.abs()).max(1.0);
    let mut sorted: Vec<&DofRecord> = ours.iter().collect();
    sorted.sort_by(|a, b| (a.component, a.r).partial_cmp(&(b.component, b.r)).unwrap());
    let mut map = vec![usize::MAX; theirs.len()];
    let mut taken = vec![false; ours.len()];
    let mut worst: f64 = 0.0;
    for their in theirs {
        let tol = tolerance(their);
        let start =
            sorted.partition_point(|d| (d.component, d.r) < (their.component, their.r - tol));
        let best = sorted[start..]
            .iter()
            .take_while(|d| d.component == their.component && d.r <= their.r + tol)
            .map(|d| (d, (d.r - their.r).hypot(d.z - their.z)))
            .filter(|(_, distance)| *distance <= tol)
            .min_by(|a, b| a.1.partial_cmp(&b.1).unwrap());
        let Some((ours_dof, distance)) = best else {
            return Err(mismatch(
                dir,
                format!(
                    "FEniCSx dof {} (component {} at r = {}, z = {}) has no dof of ours there",
                    their.index, their.component, their.r, their.z
                ),
            ));
        };
        if their.index >= map.len() || taken[ours_dof.index] {
            return Err(mismatch(
                dir,
                format!("FEniCSx dof {} matched twice or out of range", their.index),
            ));
        }
        taken[ours_dof.index] = true;
        map[their.index] = ours_dof.index;
        worst = worst.max(distance);
    }
    Ok((map, worst))
}

/// Compare our system on `mesh` (degree `degree`) with FEniCSx's export in `dir`.
pub fn compare_operator(mesh: &Path, degree: Degree, dir: &Path) -> Result<OperatorComparison> {
    let system = assemble_system(&load_mesh(mesh, degree)?)?;
    let theirs_dofs = read_dofs(&dir.join("dofs.csv"))?;
    if theirs_dofs.len() != system.dofs.len() {
        return Err(mismatch(
            dir,
            format!(
                "FEniCSx has {} dofs, ours {} on {} with P{}",
                theirs_dofs.len(),
                system.dofs.len(),
                mesh.display(),
                degree as u8
            ),
        ));
    }
    let (map, position_difference) = match_dofs(&system.dofs, &theirs_dofs, dir)?;
    let stiffness = read_matrix(&dir.join("stiffness.mtx"))?;
    let n = system.dofs.len();
    if stiffness.rows() != n || stiffness.cols() != n {
        return Err(mismatch(dir, format!("stiffness.mtx is not {n} x {n}")));
    }
    let mut theirs: HashMap<(usize, usize), f64> = HashMap::with_capacity(stiffness.nnz());
    for (&value, (row, col)) in stiffness.triplet_iter() {
        *theirs.entry((map[row], map[col])).or_insert(0.0) += value;
    }
    let nnz_fenicsx = theirs.len();
    let k = &system.stiffness;
    let mut largest: f64 = 0.0;
    let mut difference: f64 = 0.0;
    for col in 0..n {
        for idx in k.col_offsets()[col]..k.col_offsets()[col + 1] {
            let row = k.row_indices()[idx];
            let ours = k.values()[idx];
            largest = largest.max(ours.abs());
            let their = theirs.remove(&(row, col)).unwrap_or(0.0);
            difference = difference.max((ours - their).abs());
        }
    }
    for value in theirs.values() {
        difference = difference.max(value.abs());
    }
    let load = read_matrix(&dir.join("load.mtx"))?;
    let mut their_load = vec![0.0; n];
    for (&value, (row, _)) in load.triplet_iter() {
        their_load[map[row]] += value;
    }
    let load_largest = system.load.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let load_difference = system
        .load
        .iter()
        .zip(&their_load)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    Ok(OperatorComparison {
        mesh: mesh.display().to_string(),
        mesh_sha256: ringcontact::mesh::provider::sha256_file(mesh)?,
        degree: degree as u8,
        dofs: n,
        nnz_ours: k.nnz(),
        nnz_fenicsx,
        stiffness_difference: difference / largest,
        load_difference: load_difference / load_largest,
        position_difference,
    })
}

#[cfg(test)]
mod tests {
    use super::mesh_parameters_of;

    #[test]
    fn a_records_mesh_parameters_are_read_from_its_reproduce_command() {
        let reproduce = "python3 scripts/fenicsx/operators.py --mesh-parameters \
                         a=1,b=0.3,R=1e7,hmin=1e-8 --degree 2";
        let parameters = mesh_parameters_of(reproduce).unwrap();
        let names: Vec<&str> = parameters.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["a", "b", "R", "hmin"]);
        assert_eq!(parameters[1].1, 0.3);
        assert_eq!(parameters[3].1, 1e-8);
        // A committed mesh's record names a path, no parameters.
        let committed = "python3 scripts/fenicsx/operators.py --mesh meshes/disk-L0.msh --degree 1";
        assert!(mesh_parameters_of(committed).is_none());
        assert!(mesh_parameters_of("operators.py --mesh-parameters").is_none());
    }
}
