//! A two-way split of a mesh's nodes by a small separator, so that the two parts of the
//! stiffness matrix can be factorised on two cores ([`super::split_cholesky`]).
//!
//! The separator is one level of a breadth-first search of the vertex graph, started from a
//! pseudo-peripheral vertex (the last vertex reached from an arbitrary start): the vertices
//! before that level form the first part, those after it the second. The two parts share no cell
//! (a cell's vertices are neighbours, so their levels differ by at most one), hence no entry of
//! `K`. On the graded meshes of this project the levels are rings around the refined points, a
//! few dozen to a few hundred vertices each, so the separator is small wherever the split is
//! balanced: of the levels whose split leaves 47-53 % of the vertices on each side (else
//! 40-60 %), the smallest is taken.
//! Inner nodes of an edge and bubble nodes go with the part of their edge's or cell's vertices
//! off the separator (a cell touches at most one part); those of edges and cells lying wholly on
//! the separator join it.

use std::collections::VecDeque;

use super::mesh::Mesh;
use super::vertex_ordering::{
    bubble_node, edge_inner_nodes, vertex_graph, VertexCells, VertexGraph,
};

/// Which part of the split a node belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    First,
    Second,
    Separator,
}

/// The side of every node of a mesh.
#[derive(Clone, Debug)]
pub struct NodeSplit {
    pub sides: Vec<Side>,
}

impl NodeSplit {
    /// Number of nodes on `side`.
    pub fn count(&self, side: Side) -> usize {
        self.sides.iter().filter(|&&s| s == side).count()
    }
}

/// Fractions of the vertices each part must hold at least, tried in turn: a nearly even split
/// first (the parts' factorisations run side by side, and their cost grows like `n^1.5`), then a
/// looser one.
const MIN_PART_SHARES: [f64; 2] = [0.47, 0.4];

/// Breadth-first levels of the vertex graph from graph vertex `start`: `(level of each vertex,
/// last vertex reached)`; vertices not reached keep `usize::MAX`.
fn levels_from(graph: &VertexGraph, start: usize) -> (Vec<usize>, usize) {
    let mut level = vec![usize::MAX; graph.vertices.len()];
    let mut queue = VecDeque::from([start]);
    level[start] = 0;
    let mut last = start;
    while let Some(v) = queue.pop_front() {
        last = v;
        for &w in graph.neighbours(v) {
            if level[w] == usize::MAX {
                level[w] = level[v] + 1;
                queue.push_back(w);
            }
        }
    }
    (level, last)
}

/// Split the nodes of `mesh` in two parts and a separator level (see the module's
/// documentation), or `None` when the vertex graph is disconnected or too small, or when no
/// level leaves at least the smallest of [`MIN_PART_SHARES`] of the vertices on each side.
pub fn split_nodes(mesh: &Mesh) -> Option<NodeSplit> {
    let incidence = VertexCells::new(mesh);
    split_nodes_of(mesh, &vertex_graph(mesh, &incidence))
}

/// [`split_nodes`] with the mesh's vertex graph given (shared with
/// [`super::vertex_ordering::vertex_led_node_order_of`]).
pub(super) fn split_nodes_of(mesh: &Mesh, graph: &VertexGraph) -> Option<NodeSplit> {
    let count = graph.vertices.len();
    if count < 16 {
        return None;
    }
    let (_, far) = levels_from(graph, 0);
    let (level, _) = levels_from(graph, far);
    if level.contains(&usize::MAX) {
        return None;
    }
    let depth = level.iter().max().copied().unwrap_or(0) + 1;
    let mut per_level = vec![0usize; depth];
    for &l in &level {
        per_level[l] += 1;
    }
    // The smallest level with at least a share of the vertices before and after it.
    let smallest_level = |share: f64| {
        let least = (share * count as f64).ceil() as usize;
        let mut before = 0;
        let mut best: Option<(usize, usize)> = None;
        for (l, &size) in per_level.iter().enumerate() {
            let after = count - before - size;
            if before >= least && after >= least && best.is_none_or(|(_, s)| size < s) {
                best = Some((l, size));
            }
            before += size;
        }
        best.map(|(l, _)| l)
    };
    let cut = MIN_PART_SHARES
        .iter()
        .find_map(|&share| smallest_level(share))?;
    let vertex_side = |node: usize, index: &[usize]| -> Side {
        let l = level[index[node]];
        match l.cmp(&cut) {
            std::cmp::Ordering::Less => Side::First,
            std::cmp::Ordering::Greater => Side::Second,
            std::cmp::Ordering::Equal => Side::Separator,
        }
    };
    let mut index = vec![usize::MAX; mesh.nodes.len()];
    for (i, &v) in graph.vertices.iter().enumerate() {
        index[v] = i;
    }
    // Nodes in no cell couple to nothing: the first part takes them.
    let mut sides = vec![Side::First; mesh.nodes.len()];
    let joined = |a: Side, b: Side| match (a, b) {
        (Side::First, _) | (_, Side::First) => Side::First,
        (Side::Second, _) | (_, Side::Second) => Side::Second,
        _ => Side::Separator,
    };
    for c in 0..mesh.cell_count() {
        let cell = mesh.cell(c);
        let corner: [Side; 3] = std::array::from_fn(|i| vertex_side(cell[i], &index));
        for (i, &side) in corner.iter().enumerate() {
            sides[cell[i]] = side;
        }
        for edge in 0..3 {
            let side = joined(corner[edge], corner[(edge + 1) % 3]);
            for &m in edge_inner_nodes(cell, mesh.degree, edge) {
                sides[m] = side;
            }
        }
        if let Some(bubble) = bubble_node(cell, mesh.degree) {
            sides[bubble] = joined(joined(corner[0], corner[1]), corner[2]);
        }
    }
    Some(NodeSplit { sides })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::mesh::{structured_rectangle, Degree};

    #[test]
    fn the_parts_share_no_cell_and_hold_comparable_shares() {
        for degree in [Degree::Linear, Degree::Quadratic, Degree::Cubic] {
            let mesh = structured_rectangle(4.0, 1.0, 24, 6, 1, 2, 3).with_degree(degree);
            let split = split_nodes(&mesh).expect("a long strip splits");
            for c in 0..mesh.cell_count() {
                let cell = mesh.cell(c);
                let has = |side| cell.iter().any(|&m| split.sides[m] == side);
                assert!(
                    !(has(Side::First) && has(Side::Second)),
                    "{degree:?}: cell {c} couples both parts"
                );
            }
            let (first, second) = (split.count(Side::First), split.count(Side::Second));
            let separator = split.count(Side::Separator);
            assert!(first > 0 && second > 0, "{degree:?}");
            assert!(
                separator < (first + second) / 4,
                "{degree:?}: separator {separator} of {}",
                mesh.nodes.len()
            );
        }
    }

    #[test]
    fn a_tiny_mesh_is_not_split() {
        let mesh = structured_rectangle(1.0, 1.0, 2, 1, 1, 2, 3);
        assert!(split_nodes(&mesh).is_none());
    }
}
