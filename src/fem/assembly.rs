//! Global stiffness matrix in compressed sparse column form (`nalgebra-sparse`).
//!
//! The sparsity pattern is built once from the connectivity (two dofs per node, `(u_r, u_z)`),
//! then element matrices are added in place; the pattern never changes afterwards, which lets the
//! Cholesky factorisation reuse its symbolic analysis whatever constraints are applied.

use nalgebra_sparse::CscMatrix;
use rayon::prelude::*;

use super::element::{stiffness, Lame};
use super::mesh::Mesh;
use super::quadrature::TriangleRule;
use crate::error::{Error, Result};

/// Cells whose element matrices are computed together (in parallel) before they are added.
const ASSEMBLY_BLOCK: usize = 4096;

/// Sorted neighbours of every node (itself included) in compressed form `(offsets, list)`:
/// node `n`'s are `list[offsets[n]..offsets[n + 1]]`.
fn node_adjacency(mesh: &Mesh) -> (Vec<usize>, Vec<usize>) {
    let nodes = mesh.nodes.len();
    // Cells of each node.
    let mut cell_offsets = vec![0usize; nodes + 1];
    for c in 0..mesh.cell_count() {
        for &a in mesh.cell(c) {
            cell_offsets[a + 1] += 1;
        }
    }
    for i in 0..nodes {
        cell_offsets[i + 1] += cell_offsets[i];
    }
    let mut fill = cell_offsets.clone();
    let mut cells_of = vec![0usize; cell_offsets[nodes]];
    for c in 0..mesh.cell_count() {
        for &a in mesh.cell(c) {
            cells_of[fill[a]] = c;
            fill[a] += 1;
        }
    }
    let mut marker = vec![usize::MAX; nodes];
    let mut offsets = Vec::with_capacity(nodes + 1);
    let mut list = Vec::with_capacity(cells_of.len() * 4);
    offsets.push(0);
    for node in 0..nodes {
        let start = list.len();
        for &c in &cells_of[cell_offsets[node]..cell_offsets[node + 1]] {
            for &b in mesh.cell(c) {
                if marker[b] != node {
                    marker[b] = node;
                    list.push(b);
                }
            }
        }
        list[start..].sort_unstable();
        offsets.push(list.len());
    }
    (offsets, list)
}

/// Assemble `K = Σ_e K_e` for the whole mesh.
pub fn assemble_stiffness(
    mesh: &Mesh,
    material: &Lame,
    rule: &TriangleRule,
) -> Result<CscMatrix<f64>> {
    let nodes = mesh.nodes.len();
    let (adjacency_offsets, adjacency) = node_adjacency(mesh);
    let neighbours = |node: usize| &adjacency[adjacency_offsets[node]..adjacency_offsets[node + 1]];
    let dofs = 2 * nodes;
    let mut col_offsets = Vec::with_capacity(dofs + 1);
    col_offsets.push(0);
    for node in 0..nodes {
        for _ in 0..2 {
            let last = *col_offsets.last().unwrap_or(&0);
            col_offsets.push(last + 2 * neighbours(node).len());
        }
    }
    let nnz = *col_offsets.last().unwrap_or(&0);
    let mut row_indices = Vec::with_capacity(nnz);
    for node in 0..nodes {
        for _ in 0..2 {
            for &m in neighbours(node) {
                row_indices.push(2 * m);
                row_indices.push(2 * m + 1);
            }
        }
    }
    let mut values = vec![0.0; nnz];
    let k = mesh.degree.nodes_per_cell();
    let size = 2 * k;
    // Element matrices are computed in parallel, a block of cells at a time, and added serially.
    let mut locals = vec![0.0; ASSEMBLY_BLOCK * size * size];
    for block_start in (0..mesh.cell_count()).step_by(ASSEMBLY_BLOCK) {
        let block_end = (block_start + ASSEMBLY_BLOCK).min(mesh.cell_count());
        locals[..(block_end - block_start) * size * size]
            .par_chunks_mut(size * size)
            .enumerate()
            .for_each(|(i, local)| {
                let cell = mesh.cell(block_start + i);
                let vertices = [
                    mesh.nodes[cell[0]],
                    mesh.nodes[cell[1]],
                    mesh.nodes[cell[2]],
                ];
                stiffness(mesh.degree, vertices, material, rule, local);
            });
        for c in block_start..block_end {
            let cell = mesh.cell(c);
            let local =
                &locals[(c - block_start) * size * size..(c - block_start + 1) * size * size];
            for (b, &nb) in cell.iter().enumerate() {
                let list = neighbours(nb);
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
    }
    CscMatrix::try_from_csc_data(dofs, dofs, col_offsets, row_indices, values).map_err(|e| {
        Error::InvalidMesh {
            path: mesh.source.clone(),
            message: format!("internal: stiffness pattern rejected: {e}"),
        }
    })
}
