"""Solve one punch scene with FEniCSx (dolfinx 0.5) on a committed gmsh mesh and store the result.

The discrete problem is the one `verify solve --method fem --mesh M --degree k` solves:
  * axisymmetric linear elasticity in (r, z), E = 1, nu = 0 (so E* = 1), Lagrange P1 or P2 on the
    mesh's straight-sided triangles;
  * weak form  a(u, v) = int sigma(u) : eps(v) 2 pi r dx  with a FIXED quadrature degree (2 for P1,
    4 for P2: basix's default rules, the same points the Rust code uses);
  * u = 0 on the far arc (tag 3), u_r = 0 on the axis (tag 4);
  * flat punches: u_z = -d on the contact line (tag 1); concave punches: u_z <= -d + h g(r) on every
    contact-line z-dof, solved by PETSc's SNES variational-inequality solver (vinewtonrsls);
  * force = -(sum of K u over the contact-line z-dofs): the consistent nodal reactions.

Usage: /usr/bin/python3 solve.py --punch cone --mesh meshes/disk-L1.msh --degree 2 --depth 2
       [--eps B_OVER_A] --out verify/fenicsx/NAME.json      (run from the repository root)
Under MPI (PETSc's distributed vectors and matrices, MUMPS's LU), the same problem:
       mpirun -n 2 /usr/bin/python3 solve.py ...             (scripts/fenicsx/run_mpi.sh)
"""

import argparse
import datetime
import hashlib
import json
import os
import sys
import time

import numpy as np
import ufl
from mpi4py import MPI
from petsc4py import PETSc

import dolfinx
from dolfinx import fem
from dolfinx.fem.petsc import (apply_lifting, assemble_matrix, assemble_vector,
                               create_matrix, create_vector, set_bc)

from common import read_mesh, stiffness_form

CONTACT, FREE, FAR, AXIS, HOLE = 1, 2, 3, 4, 5
BIG = 1e20
# PETSc's own LU is serial; under `mpirun -n K` (K > 1) the factorisation is MUMPS's, distributed
# (--lu chooses; the stored serial results use PETSc's).
LU_SOLVER = "mumps" if MPI.COMM_WORLD.size > 1 else "petsc"


def gap_shape(punch, r):
    if punch == "cone":
        return 1.0 - r
    if punch == "sphere":
        return 1.0 - r * r
    return 0.0 * r


def sha256(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--punch", required=True, choices=["flat", "flat-annulus", "cone", "sphere"])
    p.add_argument("--mesh", required=True)
    p.add_argument("--degree", type=int, default=2, choices=[1, 2, 3])
    p.add_argument("--depth", type=float, default=1.0)
    p.add_argument("--eps", type=float, default=None, help="b/a of the flat annulus")
    p.add_argument("--out", required=True)
    p.add_argument("--mesh-parameters", default=None,
                   help="JSON list of [name, value]: the gmsh parameters that remake a generated "
                        "mesh (printed by `verify mesh`); stored with the result")
    p.add_argument("--lu", choices=["auto", "petsc", "mumps"], default="auto",
                   help="LU factorisation: PETSc's own (serial only) or MUMPS (distributed); "
                        "auto: PETSc's in one process, MUMPS under mpirun -n K > 1")
    args = p.parse_args()
    global LU_SOLVER
    if args.lu != "auto":
        if args.lu == "petsc" and MPI.COMM_WORLD.size > 1:
            p.error("--lu petsc is serial: use mumps (or auto) under mpirun -n K > 1")
        LU_SOLVER = args.lu

    comm = MPI.COMM_WORLD
    comm.Barrier()
    start = time.perf_counter()
    mesh, facet_tags = read_mesh(args.mesh)
    V = fem.VectorFunctionSpace(mesh, ("Lagrange", args.degree))

    # Degree 2p: basix's default rules for 2, 4, 6 are the 3-, 6- and 12-point rules the Rust
    # code uses (for P3 the Lagrange variant of dolfinx places the edge dofs differently, which
    # spans the same space: identical for flat punches, not for node-wise contact).
    qdeg = 2 * args.degree
    a = stiffness_form(mesh, V, qdeg)
    a_form = fem.form(a)

    fdim = 1
    far_dofs = fem.locate_dofs_topological(V, fdim, facet_tags.find(FAR))
    axis_dofs = fem.locate_dofs_topological(V.sub(0), fdim, facet_tags.find(AXIS))
    # Under MPI each process owns part of the dofs and sees some of its neighbours' (ghosts): the
    # Dirichlet conditions take all of them (contact_dofs_all), the bounds, reactions and active
    # set the owned ones only (contact_dofs), so each dof counts once.
    contact_dofs_all = fem.locate_dofs_topological(V.sub(1), fdim, facet_tags.find(CONTACT))
    bs = V.dofmap.index_map_bs
    owned = V.dofmap.index_map.size_local * bs
    contact_dofs = contact_dofs_all[contact_dofs_all < owned]
    bcs = [fem.dirichletbc(np.zeros(2, dtype=PETSc.ScalarType), far_dofs, V),
           fem.dirichletbc(PETSc.ScalarType(0.0), axis_dofs, V.sub(0))]

    # Coordinates of the dofs (r of each z-dof on the contact line).
    coords = V.tabulate_dof_coordinates()
    contact_r = np.array([coords[d // bs][0] for d in contact_dofs])

    u = fem.Function(V)
    K = assemble_matrix(a_form)  # without boundary conditions: K u gives the reactions
    K.assemble()
    iterations = 1

    if args.punch in ("flat", "flat-annulus"):
        bcs_flat = bcs + [fem.dirichletbc(PETSc.ScalarType(-args.depth), contact_dofs_all, V.sub(1))]
        A = assemble_matrix(a_form, bcs=bcs_flat)
        A.assemble()
        b = u.vector.duplicate()  # no body force: the right side comes from the lifting only
        with b.localForm() as bl:
            bl.set(0.0)
        apply_lifting(b, [a_form], bcs=[bcs_flat])
        b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        set_bc(b, bcs_flat)
        ksp = PETSc.KSP().create(mesh.comm)
        ksp.setOperators(A)
        ksp.setType("preonly")
        ksp.getPC().setType("lu")
        ksp.getPC().setFactorSolverType(LU_SOLVER)
        ksp.solve(b, u.vector)
        u.x.scatter_forward()
        active = np.ones(len(contact_dofs), dtype=bool)
    else:
        # Residual F(u) = K u with Dirichlet rows, Jacobian K; bounds on the contact z-dofs.
        residual_form = fem.form(ufl.action(a, u))
        J = create_matrix(a_form)
        F = create_vector(residual_form)

        def form_residual(snes, X, B):
            X.copy(u.vector)
            u.x.scatter_forward()
            with B.localForm() as bl:
                bl.set(0.0)
            assemble_vector(B, residual_form)
            apply_lifting(B, [a_form], bcs=[bcs], x0=[X], scale=-1.0)
            B.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
            set_bc(B, bcs, X, -1.0)

        def form_jacobian(snes, X, A, P):
            A.zeroEntries()
            assemble_matrix(A, a_form, bcs=bcs)
            A.assemble()

        upper = u.vector.duplicate()
        lower = u.vector.duplicate()
        upper.set(BIG)
        lower.set(-BIG)
        bound = -args.depth + gap_shape(args.punch, contact_r)
        upper.array[contact_dofs] = bound
        snes = PETSc.SNES().create(mesh.comm)
        snes.setFunction(form_residual, F)
        snes.setJacobian(form_jacobian, J)
        snes.setType("vinewtonrsls")
        snes.setVariableBounds(lower, upper)
        snes.setTolerances(rtol=1e-14, atol=1e-13, max_it=100)
        ksp = snes.getKSP()
        ksp.setType("preonly")
        ksp.getPC().setType("lu")
        ksp.getPC().setFactorSolverType(LU_SOLVER)
        x0 = u.vector.duplicate()
        x0.set(0.0)
        snes.solve(None, x0)
        if snes.getConvergedReason() <= 0:
            if comm.rank == 0:
                print(f"SNES did not converge: reason {snes.getConvergedReason()}", file=sys.stderr)
            return 1
        x0.copy(u.vector)
        u.x.scatter_forward()
        iterations = snes.getIterationNumber()
        active = u.vector.array[contact_dofs] >= bound - 1e-10 * args.depth

    reaction = u.vector.duplicate()
    K.mult(u.vector, reaction)
    force = -comm.allreduce(float(np.sum(reaction.array[contact_dofs])), op=MPI.SUM)
    comm.Barrier()
    wall = time.perf_counter() - start
    local_active = [float(r) for r, a_ in zip(contact_r, active) if a_]
    all_active = comm.gather(local_active, root=0)
    if comm.rank != 0:
        return 0

    root = os.getcwd()
    mesh_rel = os.path.relpath(os.path.abspath(args.mesh), root)
    cmd = f"verify solve --punch {args.punch} --method fem --mesh {mesh_rel} --degree {args.degree}"
    if args.punch == "flat-annulus":
        cmd += f" --eps {args.eps}"
    if args.punch in ("cone", "sphere"):
        cmd += f" --depth {args.depth}"
    cmd += " --json"
    active_r = sorted(r for part in all_active for r in part)
    result = {
        "punch": args.punch,
        "mesh": mesh_rel,
        "mesh_sha256": sha256(args.mesh),
        **({"mesh_parameters": json.loads(args.mesh_parameters)} if args.mesh_parameters else {}),
        "degree": args.degree,
        "quadrature_degree": qdeg,
        "depth": args.depth,
        "eps": args.eps if args.punch == "flat-annulus" else None,
        "force": force,
        "inner_radius": (min(active_r) if active_r else None) if args.punch in ("cone", "sphere") else None,
        "active_contact_radii": active_r,
        "dofs": int(V.dofmap.index_map.size_global * bs),
        "iterations": int(iterations),
        "wall_s": wall,
        "mpi_processes": comm.size,
        "lu_solver": LU_SOLVER,
        "dolfinx_version": dolfinx.__version__,
        "petsc_version": ".".join(str(n) for n in PETSc.Sys.getVersion()),
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "reproduce": cmd,
        "notes": "E = 1, nu = 0 (E* = 1), a = h = 1; force includes the 2 pi of the axisymmetric "
                 "weak form; inner_radius is the innermost active contact node (not interpolated)",
    }
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out, "w") as f:
        json.dump(result, f, indent=2)
        f.write("\n")
    print(f"{args.out}: force {force:.12g}, {result['dofs']} dofs, {iterations} iterations, {wall:.2f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
