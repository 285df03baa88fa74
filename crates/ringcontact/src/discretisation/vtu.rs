//! VTK unstructured-grid output (`.vtu`, ASCII XML) of a finite-element displacement field for
//! ParaView: points `(r, z, 0)`, linear (VTK type 5), quadratic (type 22, same node order as
//! gmsh) or cubic (Lagrange type 69) triangles, point data `displacement = (u_r, u_z, 0)`.

use std::fmt::Write as _;
use std::path::Path;

use crate::error::{Error, Result};
use crate::mesh::triangulation::{Degree, Mesh};

/// Write `mesh` with the nodal displacement `u` (`(u_r, u_z)` per node) to `path`.
pub(crate) fn write_vtu(path: &Path, mesh: &Mesh, u: &[f64]) -> Result<()> {
    let k = mesh.degree.nodes_per_cell();
    let cell_type = match mesh.degree {
        Degree::Linear => 5,
        Degree::Quadratic => 22,
        // VTK_LAGRANGE_TRIANGLE: vertices, edge nodes edge by edge, then the centre (our order).
        Degree::Cubic => 69,
    };
    let mut s = String::new();
    let _ = writeln!(s, "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n<UnstructuredGrid>");
    let _ = writeln!(
        s,
        "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">",
        mesh.nodes.len(),
        mesh.cell_count()
    );
    s += "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for p in &mesh.nodes {
        let _ = writeln!(s, "{:e} {:e} 0", p[0], p[1]);
    }
    s += "</DataArray></Points>\n<Cells><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for c in mesh.cells.chunks(k) {
        let line: Vec<String> = c.iter().map(|v| v.to_string()).collect();
        let _ = writeln!(s, "{}", line.join(" "));
    }
    s += "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for i in 1..=mesh.cell_count() {
        let _ = write!(s, "{} ", i * k);
    }
    s += "\n</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for _ in 0..mesh.cell_count() {
        let _ = write!(s, "{cell_type} ");
    }
    s += "\n</DataArray></Cells>\n<PointData Vectors=\"displacement\"><DataArray type=\"Float64\" Name=\"displacement\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for n in 0..mesh.nodes.len() {
        let _ = writeln!(s, "{:e} {:e} 0", u[2 * n], u[2 * n + 1]);
    }
    s += "</DataArray></PointData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
    std::fs::write(path, s).map_err(|e| Error::file("write the VTK file", path, e))
}
