//! The assembled linear system written for other codes (`verify export`), and read back.
//!
//! For a mesh and an element degree: the stiffness matrix `K` of the axisymmetric solid
//! (`K_ij = ∫ σ(φ_j) : ε(φ_i) 2π r dA`, `E = 1`, `ν = 0`, no boundary conditions: what
//! `scripts/fenicsx/export.py` assembles as well), the load vector of a unit pressure on the
//! contact line (`f_i = -∫_contact φ_i · e_z 2π r dr`: the consistent nodal forces of `p = 1`
//! pressing the half-space down), and the dofs (`2 n + c` for component `c` of node `n`) with
//! their node, position and component, so that another code's dofs can be matched by position.
//! Matrix Market files are written and read with `sprs` (coordinate, general, real).

use std::path::{Path, PathBuf};

use nalgebra_sparse::CscMatrix;
use sprs::{CsMat, TriMat};

use crate::discretisation::assembly::assemble_stiffness;
use crate::discretisation::element::Lame;
use crate::discretisation::quadrature::gauss_legendre;
use crate::discretisation::quadrature::stiffness_rule;
use crate::error::{Error, Result};
use crate::mesh::triangulation::{tags, Degree, Mesh};

/// One degree of freedom: its index, its node (the file's tag where the node is the file's), its
/// position and its component (0: `u_r`, 1: `u_z`).
#[derive(Clone, Debug, PartialEq)]
pub struct DofRecord {
    pub index: usize,
    pub node_tag: Option<u64>,
    pub r: f64,
    pub z: f64,
    pub component: u8,
}

/// The assembled system of one mesh and degree.
pub struct AssembledSystem {
    pub stiffness: CscMatrix<f64>,
    pub load: Vec<f64>,
    pub dofs: Vec<DofRecord>,
}

fn io_error(path: &Path, message: String) -> Error {
    Error::InvalidMesh {
        path: path.display().to_string(),
        message,
    }
}

/// Consistent nodal forces of a unit pressure on the edges tagged [`tags::CONTACT`]:
/// `f_{2n+1} = -Σ_edges ∫ φ_n(t) 2π r(t) L dt` (5-point Gauss, exact for degree 3 times the
/// linear `r`).
pub(crate) fn unit_pressure_load(mesh: &Mesh) -> Vec<f64> {
    let mut load = vec![0.0; 2 * mesh.nodes.len()];
    let (points, weights) = gauss_legendre(5);
    // Positions of an edge's nodes on [0, 1]: ends, then interior nodes from the first end.
    let positions: &[f64] = match mesh.degree {
        Degree::Linear => &[0.0, 1.0],
        Degree::Quadratic => &[0.0, 1.0, 0.5],
        Degree::Cubic => &[0.0, 1.0, 1.0 / 3.0, 2.0 / 3.0],
    };
    for edge in mesh.boundary.iter().filter(|e| e.tag == tags::CONTACT) {
        let (p, q) = (mesh.nodes[edge.nodes[0]], mesh.nodes[edge.nodes[1]]);
        let length = (q[0] - p[0]).hypot(q[1] - p[1]);
        for (&t, &w) in points.iter().zip(&weights) {
            let r = p[0] + t * (q[0] - p[0]);
            for (a, &node) in edge.nodes.iter().enumerate() {
                let basis: f64 = positions
                    .iter()
                    .enumerate()
                    .filter(|&(b, _)| b != a)
                    .map(|(_, &s)| (t - s) / (positions[a] - s))
                    .product();
                load[2 * node + 1] -= w * basis * 2.0 * std::f64::consts::PI * r * length;
            }
        }
    }
    load
}

/// Assemble the system of `mesh` (already of the wanted degree).
pub fn assemble_system(mesh: &Mesh) -> Result<AssembledSystem> {
    let material = Lame::from_young_poisson(1.0, 0.0);
    let stiffness = assemble_stiffness(mesh, &material, &stiffness_rule(mesh.degree))?;
    let dofs = mesh
        .nodes
        .iter()
        .enumerate()
        .flat_map(|(n, p)| {
            let tag = mesh.file_tags.nodes.get(n).copied();
            (0..2u8).map(move |component| DofRecord {
                index: 2 * n + component as usize,
                node_tag: tag,
                r: p[0],
                z: p[1],
                component,
            })
        })
        .collect();
    Ok(AssembledSystem {
        stiffness,
        load: unit_pressure_load(mesh),
        dofs,
    })
}

/// Convert a CSC matrix of `nalgebra-sparse` to `sprs`.
fn to_sprs(matrix: &CscMatrix<f64>) -> CsMat<f64> {
    CsMat::new_csc(
        (matrix.nrows(), matrix.ncols()),
        matrix.col_offsets().to_vec(),
        matrix.row_indices().to_vec(),
        matrix.values().to_vec(),
    )
}

/// Write `stiffness.mtx`, `load.mtx` (an `n x 1` matrix) and `dofs.csv` into `dir`.
pub fn write_system(system: &AssembledSystem, dir: &Path) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir)
        .map_err(|e| io_error(dir, format!("cannot create the directory: {e}")))?;
    let stiffness_path = dir.join("stiffness.mtx");
    sprs::io::write_matrix_market(&stiffness_path, &to_sprs(&system.stiffness))
        .map_err(|e| io_error(&stiffness_path, format!("cannot write: {e}")))?;
    let load_path = dir.join("load.mtx");
    let mut load = TriMat::new((system.load.len(), 1));
    for (i, &v) in system.load.iter().enumerate() {
        if v != 0.0 {
            load.add_triplet(i, 0, v);
        }
    }
    sprs::io::write_matrix_market(&load_path, &load)
        .map_err(|e| io_error(&load_path, format!("cannot write: {e}")))?;
    let dofs_path = dir.join("dofs.csv");
    let mut text = String::from("index,node_tag,r,z,component\n");
    for d in &system.dofs {
        let tag = d.node_tag.map(|t| t.to_string()).unwrap_or_default();
        text.push_str(&format!(
            "{},{},{:e},{:e},{}\n",
            d.index, tag, d.r, d.z, d.component
        ));
    }
    std::fs::write(&dofs_path, text)
        .map_err(|e| io_error(&dofs_path, format!("cannot write: {e}")))?;
    Ok(vec![stiffness_path, load_path, dofs_path])
}

/// Assemble the system of `mesh` at `degree` ([`load_mesh`]) and write it into `dir`.
pub fn export_mesh(mesh: &Path, degree: Degree, dir: &Path) -> Result<Vec<PathBuf>> {
    write_system(&assemble_system(&load_mesh(mesh, degree)?)?, dir)
}

/// Read and check `mesh` as the solver does (the contact, far and axis groups, orientation,
/// degenerate elements), raised to `degree`.
pub fn load_mesh(mesh: &Path, degree: Degree) -> Result<Mesh> {
    let raw = crate::mesh::msh::read_msh(mesh)?;
    let required = [
        (tags::CONTACT, "contact"),
        (tags::FAR, "far"),
        (tags::AXIS, "axis"),
    ];
    raw.validate(&required)?;
    let mesh = raw.with_degree(degree);
    mesh.validate(&required)?;
    Ok(mesh)
}

/// Read a Matrix Market file (coordinate, real, general or symmetric) into triplets.
pub fn read_matrix(path: &Path) -> Result<TriMat<f64>> {
    sprs::io::read_matrix_market::<f64, usize, _>(path)
        .map_err(|e| io_error(path, format!("cannot read as Matrix Market: {e}")))
}

/// Read `dofs.csv` as written by [`write_system`] (or `scripts/fenicsx/export.py`).
pub fn read_dofs(path: &Path) -> Result<Vec<DofRecord>> {
    let text =
        std::fs::read_to_string(path).map_err(|e| io_error(path, format!("cannot read: {e}")))?;
    let mut out = Vec::new();
    for (line_number, line) in text.lines().enumerate().skip(1) {
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let bad = || {
            io_error(
                path,
                format!(
                    "line {}: `{line}` is not index,node_tag,r,z,component",
                    line_number + 1
                ),
            )
        };
        if fields.len() != 5 {
            return Err(bad());
        }
        out.push(DofRecord {
            index: fields[0].parse().map_err(|_| bad())?,
            node_tag: if fields[1].is_empty() {
                None
            } else {
                Some(fields[1].parse().map_err(|_| bad())?)
            },
            r: fields[2].parse().map_err(|_| bad())?,
            z: fields[3].parse().map_err(|_| bad())?,
            component: fields[4].parse().map_err(|_| bad())?,
        });
    }
    Ok(out)
}
