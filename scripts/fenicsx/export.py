"""FEniCSx's assembled operator on a mesh: what `verify export` writes for ours.

Usage: /usr/bin/python3 export.py --mesh meshes/disk-L0.msh --degree 2 --out DIR

Writes into DIR, for the axisymmetric solid (E = 1, nu = 0) on the mesh with Lagrange elements of
the degree (equispaced variant, the nodes our FEM uses: vertices, edge points at 1/2 or 1/3 and
2/3, the centroid for P3), assembled by dolfinx 0.5.2 with the same quadrature degree (2p):
  stiffness.mtx  K_ij = int sigma(phi_j) : eps(phi_i) 2 pi r dA, no boundary conditions
  load.mtx       f_i = -int_contact phi_i . e_z 2 pi r dr (unit pressure on the contact line)
  dofs.csv       index,node_tag,r,z,component (node_tag empty: dolfinx renumbers nodes)
  meta.json      mesh, sha256, degree, dolfinx and PETSc versions, date, wall time
The harness (`verify fenicsx`) matches the dofs by position and component and reports the
largest entry-wise difference relative to the largest entry.
"""

import argparse
import datetime
import hashlib
import json
import os
import sys
import time

import basix
import basix.ufl_wrapper
import numpy as np
import scipy.io
import scipy.sparse
import ufl
from petsc4py import PETSc

import dolfinx
from dolfinx import fem
from dolfinx.fem.petsc import assemble_matrix, assemble_vector

from common import read_mesh, stiffness_form

CONTACT = 1


def sha256(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--mesh", required=True)
    p.add_argument("--degree", type=int, default=2, choices=[1, 2, 3])
    p.add_argument("--out", required=True)
    args = p.parse_args()
    start = time.perf_counter()

    mesh, facet_tags = read_mesh(args.mesh)
    element = basix.ufl_wrapper.create_vector_element(
        "P", "triangle", args.degree, lagrange_variant=basix.LagrangeVariant.equispaced)
    V = fem.FunctionSpace(mesh, element)
    x = ufl.SpatialCoordinate(mesh)
    v = ufl.TestFunction(V)
    qdeg = 2 * args.degree
    a = stiffness_form(mesh, V, qdeg)
    ds = ufl.Measure("ds", domain=mesh, subdomain_data=facet_tags,
                     metadata={"quadrature_degree": args.degree + 1})
    L = -v[1] * 2 * np.pi * x[0] * ds(CONTACT)

    K = assemble_matrix(fem.form(a))
    K.assemble()
    f = assemble_vector(fem.form(L))
    f.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)

    indptr, indices, values = K.getValuesCSR()
    n = K.getSize()[0]
    matrix = scipy.sparse.csr_matrix((values, indices, indptr), shape=(n, n)).tocoo()
    os.makedirs(args.out, exist_ok=True)
    scipy.io.mmwrite(os.path.join(args.out, "stiffness.mtx"), matrix, precision=17)
    load = f.array.copy()
    rows = np.nonzero(load)[0]
    scipy.io.mmwrite(os.path.join(args.out, "load.mtx"),
                     scipy.sparse.coo_matrix((load[rows], (rows, np.zeros_like(rows))),
                                             shape=(n, 1)), precision=17)
    coords = V.tabulate_dof_coordinates()
    bs = V.dofmap.index_map_bs
    with open(os.path.join(args.out, "dofs.csv"), "w") as out:
        out.write("index,node_tag,r,z,component\n")
        for node in range(coords.shape[0]):
            for c in range(bs):
                out.write(f"{node * bs + c},,{coords[node][0]!r},{coords[node][1]!r},{c}\n")
    meta = {
        "mesh": args.mesh,
        "mesh_sha256": sha256(args.mesh),
        "degree": args.degree,
        "quadrature_degree": qdeg,
        "lagrange_variant": "equispaced",
        "dofs": n,
        "nnz": int(matrix.nnz),
        "wall_s": time.perf_counter() - start,
        "dolfinx_version": dolfinx.__version__,
        "petsc_version": ".".join(str(x) for x in PETSc.Sys.getVersion()),
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
    }
    with open(os.path.join(args.out, "meta.json"), "w") as out:
        json.dump(meta, out, indent=2)
    print(json.dumps(meta))
    return 0


if __name__ == "__main__":
    sys.exit(main())
