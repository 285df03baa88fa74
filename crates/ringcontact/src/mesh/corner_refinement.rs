//! Geometric refinement of a linear triangle mesh around a singular point (a punch's sharp edge).
//!
//! gmsh's 2-D mesher keeps its elements' shape only down to about `1e-8` of the coordinates'
//! magnitude: asked for elements of `1e-10 a` at the rim `r = a`, it placed the surface nodes but
//! filled the corner with slivers (quality `4 √3 A / Σ l²` of 0.007-0.03 against 0.5-0.6 at
//! `1e-8 a`), and the force error grew as the size fell below `1e-8 a` (fixed annulus
//! `b/a = 0.97`, cubic elements: 5.6e-9 at `1e-8 a`, 2.1e-8 at `1e-9 a`, 1.4e-8 at `1e-10 a`).
//! The finest elements are therefore made here: every triangle touching the corner `P` is
//! replaced by its copy scaled by [`CORNER_RATIO`] about `P` and the two triangles of the
//! trapezoid left over, repeatedly, until the elements at `P` are no larger than asked. Each
//! step is a similarity transformation of the corner patch, so the shape quality stays that of
//! gmsh's elements, and the new vertices `P + σ (A - P)` are computed from `P`, exact to the
//! coordinates' rounding (`1e-16 a`) whatever the element size.

use std::collections::HashMap;

use crate::error::{Error, Result};
use crate::mesh::triangulation::{BoundaryEdge, Degree, Mesh};

/// Ratio `σ` of the element sizes of consecutive corner layers (halving).
const CORNER_RATIO: f64 = 0.5;

/// Most halvings made around one corner (from `1e-8 a` down to `1e-10 a` takes 7).
const MAX_CORNER_STEPS: usize = 40;

/// A request to refine around points of the surface `z = 0` until the elements there are no
/// larger than `size`.
#[derive(Clone, Debug, PartialEq)]
pub struct CornerRefinement {
    /// Radii `r` of the corners on `z = 0` (each must be a node of the mesh).
    pub radii: Vec<f64>,
    /// Largest edge length wanted at each corner.
    pub size: f64,
}

impl CornerRefinement {
    /// One line for provenance: what was refined, and to what size.
    pub fn describe(&self) -> String {
        let radii: Vec<String> = self.radii.iter().map(|r| format!("{r}")).collect();
        format!(
            "refined by halving around r = {} to elements of {:e} a",
            radii.join(", "),
            self.size
        )
    }

    /// Apply the refinement to a linear mesh.
    pub fn apply(&self, mesh: &Mesh) -> Result<Mesh> {
        let mut refined = mesh.clone();
        for &radius in &self.radii {
            let corner = find_surface_node(&refined, radius)?;
            refined = refine_around(&refined, corner, self.size)?;
        }
        refined.source = format!("{} ({})", mesh.source, self.describe());
        Ok(refined)
    }
}

/// Index of the node at `(radius, 0)` (to within `1e-12 (1 + radius)`).
fn find_surface_node(mesh: &Mesh, radius: f64) -> Result<usize> {
    let tolerance = 1e-12 * (1.0 + radius.abs());
    mesh.nodes
        .iter()
        .position(|p| (p[0] - radius).abs() <= tolerance && p[1].abs() <= tolerance)
        .ok_or_else(|| Error::InvalidMesh {
            path: mesh.source.clone(),
            message: format!("no node at the edge r = {radius}, z = 0 to refine around"),
        })
}

/// Largest length of an edge from `corner` in the triangles that contain it.
fn corner_size(mesh: &Mesh, corner: usize) -> f64 {
    let p = mesh.nodes[corner];
    let mut size: f64 = 0.0;
    for c in 0..mesh.cell_count() {
        let cell = mesh.cell(c);
        if cell.contains(&corner) {
            for &v in cell {
                let q = mesh.nodes[v];
                size = size.max((q[0] - p[0]).hypot(q[1] - p[1]));
            }
        }
    }
    size
}

/// Halve the corner patch of `corner` until its edges are no longer than `size`.
///
/// A triangle `(P, A, B)` (counter-clockwise) becomes `(P, A', B')`, with
/// `A' = P + σ (A - P)`, `B' = P + σ (B - P)`, and the trapezoid `A' A B B'` cut along its
/// shorter diagonal; a boundary edge `(P, A)` becomes `(P, A')` and `(A', A)` with its tag.
fn refine_around(mesh: &Mesh, corner: usize, size: f64) -> Result<Mesh> {
    if mesh.degree != Degree::Linear {
        return Err(Error::InvalidMesh {
            path: mesh.source.clone(),
            message: "corner refinement needs the linear mesh (before raising the degree)".into(),
        });
    }
    let mut mesh = mesh.clone();
    for _ in 0..MAX_CORNER_STEPS {
        if corner_size(&mesh, corner) <= size {
            return Ok(mesh);
        }
        halve_corner_patch(&mut mesh, corner);
    }
    if corner_size(&mesh, corner) <= size {
        return Ok(mesh);
    }
    Err(Error::InvalidMesh {
        path: mesh.source.clone(),
        message: format!(
            "{MAX_CORNER_STEPS} halvings around {} did not bring its elements to {size:e}",
            mesh.node_name(corner)
        ),
    })
}

fn halve_corner_patch(mesh: &mut Mesh, corner: usize) {
    let p = mesh.nodes[corner];
    let mut scaled: HashMap<usize, usize> = HashMap::new();
    let mut scaled_node = |v: usize, nodes: &mut Vec<[f64; 2]>| -> usize {
        *scaled.entry(v).or_insert_with(|| {
            let q = nodes[v];
            nodes.push([
                p[0] + CORNER_RATIO * (q[0] - p[0]),
                p[1] + CORNER_RATIO * (q[1] - p[1]),
            ]);
            nodes.len() - 1
        })
    };
    let length = |nodes: &[[f64; 2]], u: usize, v: usize| {
        (nodes[u][0] - nodes[v][0]).hypot(nodes[u][1] - nodes[v][1])
    };
    let mut added = Vec::new();
    for c in 0..mesh.cell_count() {
        let cell = [
            mesh.cells[3 * c],
            mesh.cells[3 * c + 1],
            mesh.cells[3 * c + 2],
        ];
        let Some(k) = cell.iter().position(|&v| v == corner) else {
            continue;
        };
        // Rotate to (P, A, B), keeping the orientation.
        let (a, b) = (cell[(k + 1) % 3], cell[(k + 2) % 3]);
        let a_scaled = scaled_node(a, &mut mesh.nodes);
        let b_scaled = scaled_node(b, &mut mesh.nodes);
        mesh.cells[3 * c..3 * c + 3].copy_from_slice(&[corner, a_scaled, b_scaled]);
        if length(&mesh.nodes, a_scaled, b) <= length(&mesh.nodes, a, b_scaled) {
            added.extend_from_slice(&[a_scaled, a, b, a_scaled, b, b_scaled]);
        } else {
            added.extend_from_slice(&[a_scaled, a, b_scaled, a, b, b_scaled]);
        }
    }
    mesh.cells.extend_from_slice(&added);
    let mut boundary = Vec::with_capacity(mesh.boundary.len() + 4);
    for edge in &mesh.boundary {
        let (u, v) = (edge.nodes[0], edge.nodes[1]);
        let other = if u == corner {
            v
        } else if v == corner {
            u
        } else {
            boundary.push(edge.clone());
            continue;
        };
        let middle = scaled_node(other, &mut mesh.nodes);
        boundary.push(BoundaryEdge {
            nodes: vec![u, middle],
            tag: edge.tag,
        });
        boundary.push(BoundaryEdge {
            nodes: vec![middle, v],
            tag: edge.tag,
        });
    }
    mesh.boundary = boundary;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::triangulation::{structured_rectangle, tags};

    fn area(mesh: &Mesh) -> f64 {
        (0..mesh.cell_count())
            .map(|c| {
                let t = mesh.cell(c);
                let [p, q, s] = [mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]]];
                0.5 * ((q[0] - p[0]) * (s[1] - p[1]) - (s[0] - p[0]) * (q[1] - p[1]))
            })
            .sum()
    }

    #[test]
    fn halving_keeps_the_area_orientation_and_conformity() {
        let mesh = structured_rectangle(2.0, 1.0, 4, 2, tags::CONTACT, tags::FREE, tags::FAR);
        let corner = find_surface_node(&mesh, 1.0).unwrap();
        let refined = refine_around(&mesh, corner, 1e-6).unwrap();
        // Area is preserved exactly up to rounding, and no triangle is inverted.
        assert!((area(&refined) - area(&mesh)).abs() < 1e-14);
        for c in 0..refined.cell_count() {
            let t = refined.cell(c);
            let [p, q, s] = [
                refined.nodes[t[0]],
                refined.nodes[t[1]],
                refined.nodes[t[2]],
            ];
            assert!((q[0] - p[0]) * (s[1] - p[1]) - (s[0] - p[0]) * (q[1] - p[1]) > 0.0);
        }
        assert!(corner_size(&refined, corner) <= 1e-6);
        // Conformity: every interior edge is shared by exactly two triangles, every boundary
        // edge by one, and the boundary edges of the refined mesh are exactly those.
        let mut count: HashMap<(usize, usize), usize> = HashMap::new();
        for c in 0..refined.cell_count() {
            let t = refined.cell(c);
            for i in 0..3 {
                let (u, v) = (t[i], t[(i + 1) % 3]);
                *count.entry((u.min(v), u.max(v))).or_default() += 1;
            }
        }
        let once: std::collections::BTreeSet<_> = count
            .iter()
            .filter(|(_, &n)| n == 1)
            .map(|(&e, _)| e)
            .collect();
        assert!(count.values().all(|&n| n <= 2));
        let tagged: std::collections::BTreeSet<_> = refined
            .boundary
            .iter()
            .map(|e| (e.nodes[0].min(e.nodes[1]), e.nodes[0].max(e.nodes[1])))
            .collect();
        assert_eq!(once, tagged);
        // The boundary length is unchanged.
        let perimeter = |m: &Mesh| -> f64 {
            m.boundary
                .iter()
                .map(|e| {
                    let (p, q) = (m.nodes[e.nodes[0]], m.nodes[e.nodes[1]]);
                    (p[0] - q[0]).hypot(p[1] - q[1])
                })
                .sum()
        };
        assert!((perimeter(&refined) - perimeter(&mesh)).abs() < 1e-13);
    }

    #[test]
    fn a_missing_corner_is_named() {
        let mesh = structured_rectangle(2.0, 1.0, 4, 2, tags::CONTACT, tags::FREE, tags::FAR);
        let request = CornerRefinement {
            radii: vec![0.3],
            size: 1e-6,
        };
        let message = request.apply(&mesh).unwrap_err().to_string();
        assert!(message.contains("r = 0.3"), "{message}");
    }
}
