//! Global stiffness matrix in compressed sparse column form (`nalgebra-sparse`).
//!
//! The sparsity pattern is built once from the connectivity (two dofs per node, `(u_r, u_z)`),
//! then element matrices are added in place; the pattern never changes afterwards, which lets the
//! Cholesky factorisation reuse its symbolic analysis whatever constraints are applied.

use nalgebra_sparse::CscMatrix;

use super::element::{stiffness, Lame};
use super::mesh::Mesh;
use super::quadrature::TriangleRule;
use crate::error::{Error, Result};

/// Assemble `K = Σ_e K_e` for the whole mesh.
pub fn assemble_stiffness(
    mesh: &Mesh,
    material: &Lame,
    rule: &TriangleRule,
) -> Result<CscMatrix<f64>> {
    let nodes = mesh.nodes.len();
    // Node adjacency (including self), sorted.
    let mut adjacency: Vec<Vec<usize>> = vec![Vec::new(); nodes];
    for c in 0..mesh.cell_count() {
        let cell = mesh.cell(c);
        for &a in cell {
            adjacency[a].extend_from_slice(cell);
        }
    }
    for list in adjacency.iter_mut() {
        list.sort_unstable();
        list.dedup();
    }
    let dofs = 2 * nodes;
    let mut col_offsets = Vec::with_capacity(dofs + 1);
    col_offsets.push(0);
    for list in &adjacency {
        for _ in 0..2 {
            let last = *col_offsets.last().unwrap_or(&0);
            col_offsets.push(last + 2 * list.len());
        }
    }
    let nnz = *col_offsets.last().unwrap_or(&0);
    let mut row_indices = Vec::with_capacity(nnz);
    for list in &adjacency {
        for _ in 0..2 {
            for &m in list {
                row_indices.push(2 * m);
                row_indices.push(2 * m + 1);
            }
        }
    }
    let mut values = vec![0.0; nnz];
    let k = mesh.degree.nodes_per_cell();
    let size = 2 * k;
    let mut local = vec![0.0; size * size];
    for c in 0..mesh.cell_count() {
        let cell = mesh.cell(c);
        let vertices = [
            mesh.nodes[cell[0]],
            mesh.nodes[cell[1]],
            mesh.nodes[cell[2]],
        ];
        stiffness(mesh.degree, vertices, material, rule, &mut local);
        for (b, &nb) in cell.iter().enumerate() {
            let list = &adjacency[nb];
            for (a, &na) in cell.iter().enumerate() {
                let pos = list.binary_search(&na).map_err(|_| Error::InvalidMesh {
                    path: mesh.source.clone(),
                    message: "internal: adjacency misses an element pair".into(),
                })?;
                for cb in 0..2 {
                    let col = 2 * nb + cb;
                    let base = col_offsets[col] + 2 * pos;
                    for ca in 0..2 {
                        values[base + ca] += local[(2 * a + ca) * size + 2 * b + cb];
                    }
                }
            }
        }
    }
    CscMatrix::try_from_csc_data(dofs, dofs, col_offsets, row_indices, values).map_err(|e| {
        Error::InvalidMesh {
            path: mesh.source.clone(),
            message: format!("internal: stiffness pattern rejected: {e}"),
        }
    })
}
