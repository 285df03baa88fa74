//! The node ordering a model's sparse factorisation runs in: the vertex-led elimination order
//! ([`crate::discretisation::vertex_ordering`]) and, for the native backend, a split of the
//! nodes by a separator ([`crate::discretisation::separator`]), found side by side from one
//! vertex graph and handed to the SPD seam as a [`NodeOrdering`].

use crate::discretisation::separator::split_nodes_of;
use crate::discretisation::vertex_ordering::{
    vertex_graph, vertex_led_node_order_of, vertex_order, VertexCells,
};
use crate::mesh::triangulation::Mesh;
use crate::sparse::{Backend, NodeOrdering};

/// What a model's analysis ([`crate::sparse::Analysis`]) needs from its mesh alone:
/// the vertex-led node order ([`crate::discretisation::vertex_ordering::vertex_led_node_order`]) and, for the native backend and a model
/// of at least [`Backend::split_min_dofs`] unknowns, a split by a separator read off that order's
/// elimination tree or a ring of the mesh, whichever promises the shorter factorisation
/// ([`crate::discretisation::separator`]). Needs no pattern, so it is computed while the pattern
/// is built (one vertex graph and one minimum-degree order of it serve the node order and the
/// split, which are then found side by side).
pub(crate) fn node_ordering(mesh: &Mesh, backend: Backend) -> NodeOrdering {
    node_ordering_of_raised(mesh, backend, || mesh)
}

/// [`node_ordering`] of the mesh `raised` gives, `vertex_mesh` with its degree raised: the vertex
/// graph and its minimum-degree order, which need only the cells' vertices, are found on
/// `vertex_mesh` before `raised` is called, so that the raising can run beside them. If the
/// raised mesh's cells do not have `vertex_mesh`'s vertices (in the same order), they are
/// found again on the raised mesh.
pub(crate) fn node_ordering_of_raised<'m>(
    vertex_mesh: &Mesh,
    backend: Backend,
    raised: impl FnOnce() -> &'m Mesh,
) -> NodeOrdering {
    let incidence = VertexCells::new(vertex_mesh);
    let graph = vertex_graph(vertex_mesh, &incidence);
    let vertices = vertex_order(&graph);
    let mesh = raised();
    if !same_vertices(vertex_mesh, mesh) {
        return node_ordering(mesh, backend);
    }
    let wants_split = backend
        .split_min_dofs()
        .is_some_and(|least| 2 * mesh.nodes.len() >= least);
    let (order, split) = rayon::join(
        || vertex_led_node_order_of(mesh, &incidence, &graph, &vertices),
        || {
            wants_split
                .then(|| split_nodes_of(mesh, &graph, &vertices))
                .flatten()
        },
    );
    NodeOrdering { order, split }
}

/// Whether `raised` has the cells of `vertex_mesh`, in the same order, with the same vertex
/// nodes (each cell's first three), and keeps `vertex_mesh`'s nodes' numbers (or is the same
/// mesh, as in [`node_ordering`]): then both have the same vertex graph.
fn same_vertices(vertex_mesh: &Mesh, raised: &Mesh) -> bool {
    std::ptr::eq(vertex_mesh, raised)
        || vertex_mesh.cell_count() == raised.cell_count()
            && raised.nodes.len() >= vertex_mesh.nodes.len()
            && (0..vertex_mesh.cell_count())
                .all(|c| vertex_mesh.cell(c)[..3] == raised.cell(c)[..3])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::triangulation::{structured_rectangle, Degree};

    /// The ordering found with the vertex graph of the vertex mesh, beside the raising, is the
    /// ordering of the raised mesh; a "raised" mesh with other vertices gets its own.
    #[test]
    fn the_ordering_beside_the_raising_is_the_raised_meshs_own() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../meshes/annulus-0.5-L1.msh");
        let vertex_mesh = crate::mesh::msh::read_msh(&path).unwrap();
        assert_eq!(vertex_mesh.degree, Degree::Linear);
        let same = |a: &NodeOrdering, b: &NodeOrdering| {
            a.order == b.order
                && a.split.as_ref().map(|s| &s.sides) == b.split.as_ref().map(|s| &s.sides)
        };
        for degree in [Degree::Quadratic, Degree::Cubic] {
            let raised = vertex_mesh.with_degree(degree);
            let beside = node_ordering_of_raised(&vertex_mesh, Backend::BUILT_IN, || &raised);
            let own = node_ordering(&raised, Backend::BUILT_IN);
            assert!(beside.split.is_some(), "{degree:?}: the split is exercised");
            assert!(same(&beside, &own), "{degree:?}");
        }
        let other = structured_rectangle(2.0, 1.0, 30, 20, 1, 2, 3).with_degree(Degree::Quadratic);
        let beside = node_ordering_of_raised(&vertex_mesh, Backend::BUILT_IN, || &other);
        assert_eq!(beside.order.len(), other.nodes.len());
        assert!(same(&beside, &node_ordering(&other, Backend::BUILT_IN)));
    }
}
