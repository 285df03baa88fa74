"""What solve.py and export.py share: reading a gmsh mesh into dolfinx, and the axisymmetric
elasticity forms (E = 1, nu = 0 unless given) in the (r, z) half-plane."""

import gmsh
import numpy as np
import ufl
from mpi4py import MPI

from dolfinx.io import gmshio


def read_mesh(path):
    """The mesh and its facet tags (dolfinx 0.5.2's gmshio.read_from_msh returns an undefined
    name; do what it meant to do)."""
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("mesh")
    gmsh.merge(path)
    mesh, _, facet_tags = gmshio.model_to_mesh(gmsh.model, MPI.COMM_WORLD, 0, gdim=2)
    gmsh.finalize()
    return mesh, facet_tags


def stiffness_form(mesh, V, quadrature_degree, E=1.0, nu=0.0):
    """a(u, v) = int sigma(u) : eps(v) 2 pi r dA, with the hoop strain u_r / r."""
    x = ufl.SpatialCoordinate(mesh)
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    mu = E / (2 * (1 + nu))

    def strain(w):
        return ufl.sym(ufl.as_tensor([[w[0].dx(0), 0, w[0].dx(1)],
                                      [0, w[0] / x[0], 0],
                                      [w[1].dx(0), 0, w[1].dx(1)]]))

    def stress(w):
        e = strain(w)
        return lam * ufl.tr(e) * ufl.Identity(3) + 2 * mu * e

    u, v = ufl.TrialFunction(V), ufl.TestFunction(V)
    dx = ufl.Measure("dx", domain=mesh, metadata={"quadrature_degree": quadrature_degree})
    return ufl.inner(stress(u), strain(v)) * 2 * np.pi * x[0] * dx
