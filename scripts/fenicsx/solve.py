"""Solve one punch scene with FEniCSx (dolfinx 0.5) on a gmsh mesh; print or store the result.

The discrete problem is the one `verify solve --method fem --mesh M --degree k --far-field fixed`
solves:
  * axisymmetric linear elasticity in (r, z), E = 1, nu = 0 (so E* = 1), Lagrange P1, P2 or P3 on
    the mesh's straight-sided triangles;
  * weak form  a(u, v) = int sigma(u) : eps(v) 2 pi r dx  with a FIXED quadrature degree (2p:
    basix's default rules, the same points the Rust code uses);
  * u = 0 on the far arc (tag 3), u_r = 0 on the axis (tag 4);
  * flat punches: u_z = -d on the contact line (tag 1); concave punches: u_z <= -d + h g(r) on every
    contact-line z-dof, solved by PETSc's SNES variational-inequality solver (vinewtonrsls);
  * force = -(sum of K u over the contact-line z-dofs): the consistent nodal reactions.

How it is solved, as a competent FEniCSx user would: one matrix assembly (the stiffness with the
Dirichlet rows and columns replaced by the identity; the residual of the contact problem is its
product with the iterate, the reactions one vector assembly of the form's action), a direct
factorisation chosen by --solver (PETSc's own LU, MUMPS's LU or Cholesky, CHOLMOD's Cholesky;
the matrix is symmetric positive definite), in one process or under `mpirun -n K` (MUMPS).

Timed region (wall_s): from reading the mesh file to the force (read, function space, assembly,
solve, reactions), after the imports; the phases are in `timings`. `verify solve --json` reports
the same region of ours as its `wall_s`.

Usage (from the repository root; needs FEniCSx: bash scripts/fenicsx/setup.sh):
  /usr/bin/python3 scripts/fenicsx/solve.py --punch cone --mesh meshes/disk-L1.msh --degree 2 --depth 2
  mpirun -n 2 /usr/bin/python3 scripts/fenicsx/solve.py --punch flat --mesh meshes/disk-L2.msh
  /usr/bin/python3 scripts/fenicsx/solve.py --punch flat-annulus --eps 0.3 \\
      --mesh-parameters a=1,b=0.3,R=1e7,... --degree 2      (the mesh made by `verify mesh`)
Prints one JSON object; --out FILE writes it there instead (through a temporary file and a
rename; the directory must exist). Nothing else is written.
"""

import argparse
import datetime
import hashlib
import json
import os
import subprocess
import sys
import time

import numpy as np
import ufl
from mpi4py import MPI
from petsc4py import PETSc

import dolfinx
from dolfinx import fem
from dolfinx.fem.petsc import apply_lifting, assemble_matrix, assemble_vector, set_bc

from common import read_mesh, stiffness_form

CONTACT, FREE, FAR, AXIS, HOLE = 1, 2, 3, 4, 5
BIG = 1e20
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))

# --solver: (PETSc factor type, PETSc solver package, serial only).
SOLVERS = {
    "petsc-lu": ("lu", "petsc", True),
    "mumps-lu": ("lu", "mumps", False),
    "mumps-cholesky": ("cholesky", "mumps", False),
    "cholmod": ("cholesky", "cholmod", True),
}
# The fastest configuration measured on the stored rows (benches/records/fenicsx-speed.json).
DEFAULT_SOLVER = "mumps-cholesky"
TIMED_REGION = "mesh file to force: read, function space, assembly, solve, reactions (after imports)"


CONCAVE = ("cone", "sphere", "power")


def gap_shape(punch, r, exponent=None):
    """The gap at zero depth over h: 1 - r (cone), 1 - r^2 (sphere), 1 - r^n (power), 0 (flat)."""
    if punch == "cone":
        return 1.0 - r
    if punch == "sphere":
        return 1.0 - r * r
    if punch == "power":
        return 1.0 - r ** exponent
    return 0.0 * r


def sha256(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def parameters_text(value):
    """--mesh-parameters as NAME=VALUE,... (a JSON list of [name, value] is accepted too)."""
    value = value.strip()
    if value.startswith("["):
        return ",".join(f"{name}={float(v)!r}" for name, v in json.loads(value))
    return value


def parameters_list(text):
    return [[name, float(v)] for name, v in (item.split("=", 1) for item in text.split(","))]


def make_mesh(parameters):
    """The mesh `verify mesh --parameters` makes (through the project's cache), run by cargo so
    that the binary is found wherever cargo puts it."""
    out = subprocess.run(
        ["cargo", "run", "--release", "--quiet", "--bin", "verify", "--", "mesh", "--parameters",
         parameters], cwd=ROOT, check=True, capture_output=True, text=True)
    return os.path.relpath(json.loads(out.stdout)["path"], ROOT)


def configure(ksp, solver):
    factor, package, _ = SOLVERS[solver]
    ksp.setType("preonly")
    pc = ksp.getPC()
    pc.setType(factor)
    pc.setFactorSolverType(package)
    if package == "mumps":
        # Debian's MUMPS has no METIS; AMD (ICNTL(7) = 0) beats its default PORD ordering here.
        PETSc.Options()["mat_mumps_icntl_7"] = 0
    ksp.setFromOptions()


def blas_library():
    """The BLAS the process loaded (Debian's alternatives: reference, OpenBLAS, BLIS), as the
    path of the mapped library."""
    try:
        with open("/proc/self/maps") as f:
            for line in f:
                path = line.split()[-1]
                if os.path.basename(path).startswith(("libblas", "libopenblas", "libblis")):
                    return os.path.realpath(path)
    except OSError:
        pass
    return "unknown"


def solve(args, mesh_path, comm):
    """The timed solve: (force, active radii on this process, dofs, iterations, timings)."""
    timings = {}
    t0 = time.perf_counter()
    mesh, facet_tags = read_mesh(mesh_path)
    V = fem.VectorFunctionSpace(mesh, ("Lagrange", args.degree))
    t1 = time.perf_counter()
    timings["read_s"] = t1 - t0

    qdeg = 2 * args.degree
    a = stiffness_form(mesh, V, qdeg)
    a_form = fem.form(a)
    fdim = 1
    far_dofs = fem.locate_dofs_topological(V, fdim, facet_tags.find(FAR))
    axis_dofs = fem.locate_dofs_topological(V.sub(0), fdim, facet_tags.find(AXIS))
    # Under MPI each process owns part of the dofs and sees some of its neighbours' (ghosts): the
    # Dirichlet conditions take all of them, the bounds, reactions and active set the owned ones.
    contact_dofs_all = fem.locate_dofs_topological(V.sub(1), fdim, facet_tags.find(CONTACT))
    bs = V.dofmap.index_map_bs
    owned = V.dofmap.index_map.size_local * bs
    contact_dofs = contact_dofs_all[contact_dofs_all < owned]
    bcs = [fem.dirichletbc(np.zeros(2, dtype=PETSc.ScalarType), far_dofs, V),
           fem.dirichletbc(PETSc.ScalarType(0.0), axis_dofs, V.sub(0))]
    coords = V.tabulate_dof_coordinates()
    contact_r = np.array([coords[d // bs][0] for d in contact_dofs])
    flat = args.punch in ("flat", "flat-annulus")
    if flat:
        bcs = bcs + [fem.dirichletbc(PETSc.ScalarType(-args.depth), contact_dofs_all, V.sub(1))]
    A = assemble_matrix(a_form, bcs=bcs)
    A.assemble()
    A.setOption(PETSc.Mat.Option.SPD, True)
    u = fem.Function(V)
    t2 = time.perf_counter()
    timings["assembly_s"] = t2 - t1

    if flat:
        b = u.vector.duplicate()
        with b.localForm() as bl:
            bl.set(0.0)
        apply_lifting(b, [a_form], bcs=[bcs])
        b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        set_bc(b, bcs)
        ksp = PETSc.KSP().create(mesh.comm)
        ksp.setOperators(A)
        configure(ksp, args.solver)
        ksp.solve(b, u.vector)
        if ksp.getConvergedReason() <= 0:
            raise RuntimeError(f"the linear solve failed: reason {ksp.getConvergedReason()}")
        u.x.scatter_forward()
        iterations = 1
        active = np.ones(len(contact_dofs), dtype=bool)
    else:
        # Residual F(u) = A u (A: K with identity rows and columns at the homogeneous Dirichlet
        # dofs, where the iterate is zero), Jacobian A, assembled once; bounds on the contact
        # z-dofs.
        def form_residual(snes, X, B):
            A.mult(X, B)

        def form_jacobian(snes, X, J, P):
            pass

        upper = u.vector.duplicate()
        lower = u.vector.duplicate()
        upper.set(BIG)
        lower.set(-BIG)
        bound = -args.depth + gap_shape(args.punch, contact_r, args.exponent)
        upper.array[contact_dofs] = bound
        snes = PETSc.SNES().create(mesh.comm)
        snes.setFunction(form_residual, u.vector.duplicate())
        snes.setJacobian(form_jacobian, A)
        snes.setType("vinewtonrsls")
        snes.setVariableBounds(lower, upper)
        snes.setTolerances(rtol=1e-14, atol=1e-13, max_it=100)
        configure(snes.getKSP(), args.solver)
        x0 = u.vector.duplicate()
        x0.set(0.0)
        snes.solve(None, x0)
        if snes.getConvergedReason() <= 0:
            raise RuntimeError(f"SNES did not converge: reason {snes.getConvergedReason()}")
        x0.copy(u.vector)
        u.x.scatter_forward()
        iterations = snes.getIterationNumber()
        active = u.vector.array[contact_dofs] >= bound - 1e-10 * args.depth
    t3 = time.perf_counter()
    timings["solve_s"] = t3 - t2

    # Reactions: the unconstrained form's action on the solution, one vector assembly.
    reaction = assemble_vector(fem.form(ufl.action(a, u)))
    reaction.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
    force = -comm.allreduce(float(np.sum(reaction.array[contact_dofs])), op=MPI.SUM)
    comm.Barrier()
    timings["reaction_s"] = time.perf_counter() - t3
    local_active = [float(r) for r, a_ in zip(contact_r, active) if a_]
    dofs = int(V.dofmap.index_map.size_global * bs)
    return force, local_active, dofs, int(iterations), timings


def state_words(args, mesh_rel, parameters):
    """The problem's arguments, shared by our command and this script's: punch, mesh, degree,
    and the hole or the depth."""
    words = f" --punch {args.punch}"
    words += f" --mesh-parameters {parameters}" if parameters else f" --mesh {mesh_rel}"
    words += f" --degree {args.degree}"
    if args.punch == "flat-annulus":
        words += f" --eps {args.eps}"
    if args.punch == "power":
        words += f" --exponent {args.exponent}"
    if args.punch in CONCAVE:
        words += f" --depth {args.depth}"
    return words


def our_command(args, mesh_rel, parameters):
    """The `verify solve` that solves the identical discrete problem (runnable as written)."""
    return ("cargo run --release --quiet -- solve --method fem"
            + state_words(args, mesh_rel, parameters) + " --far-field fixed --json")


def peer_command(args, mesh_rel, parameters, processes):
    """This script's command for the same result (printed, not stored)."""
    launcher = f"mpirun -n {processes} " if processes > 1 else ""
    return (launcher + "/usr/bin/python3 scripts/fenicsx/solve.py"
            + state_words(args, mesh_rel, parameters) + f" --solver {args.solver}")


def write_atomically(path, text):
    tmp = f"{path}.{os.getpid()}.partial"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--punch", required=True,
                   choices=["flat", "flat-annulus", "cone", "sphere", "power"])
    p.add_argument("--exponent", type=float, default=None,
                   help="n of the power-law punch, gap h (1 - (r/a)^n)")
    p.add_argument("--mesh", help="a gmsh .msh file (or give --mesh-parameters)")
    p.add_argument("--degree", type=int, default=2, choices=[1, 2, 3])
    p.add_argument("--depth", type=float, default=1.0)
    p.add_argument("--eps", type=float, default=None, help="b/a of the flat annulus")
    p.add_argument("--out", help="write the JSON here (default: standard output)")
    p.add_argument("--mesh-parameters", default=None,
                   help="NAME=VALUE,... (or a JSON list of [name, value]): the gmsh parameters of "
                        "meshes/half_space.geo that make the mesh (`verify mesh` prints them); "
                        "without --mesh the mesh is made from them; stored with the result")
    p.add_argument("--solver", choices=sorted(SOLVERS), default=None,
                   help=f"direct factorisation (default {DEFAULT_SOLVER}, the fastest measured)")
    p.add_argument("--lu", choices=["auto", "petsc", "mumps"], default=None,
                   help="older spelling: petsc = --solver petsc-lu, mumps = --solver mumps-lu")
    args = p.parse_args()
    comm = MPI.COMM_WORLD
    if args.solver is None:
        args.solver = {"petsc": "petsc-lu", "mumps": "mumps-lu"}.get(args.lu, DEFAULT_SOLVER)
    if SOLVERS[args.solver][2] and comm.size > 1:
        p.error(f"--solver {args.solver} is serial: use mumps-lu or mumps-cholesky under mpirun")
    if args.mesh is None and args.mesh_parameters is None:
        p.error("give --mesh FILE or --mesh-parameters NAME=VALUE,...")
    if (args.punch == "power") != (args.exponent is not None):
        p.error("--exponent N goes with --punch power, and only with it")
    if args.exponent is not None and not args.exponent > 0:
        p.error(f"--exponent must be > 0 (got {args.exponent})")
    if args.punch == "flat-annulus" and args.eps is None:
        p.error("--punch flat-annulus needs --eps B_OVER_A (the mesh's hole)")
    parameters = parameters_text(args.mesh_parameters) if args.mesh_parameters else None
    mesh_path = args.mesh
    if mesh_path is None:
        mesh_path = make_mesh(parameters) if comm.rank == 0 else None
        mesh_path = comm.bcast(mesh_path, root=0)
    mesh_path = os.path.join(ROOT, mesh_path) if not os.path.isabs(mesh_path) else mesh_path

    comm.Barrier()
    start = time.perf_counter()
    try:
        force, local_active, dofs, iterations, timings = solve(args, mesh_path, comm)
    except RuntimeError as e:
        if comm.rank == 0:
            print(f"solve.py: {e}", file=sys.stderr)
        return 1
    wall = time.perf_counter() - start
    all_active = comm.gather(local_active, root=0)
    if comm.rank != 0:
        return 0

    mesh_rel = os.path.relpath(mesh_path, ROOT)
    active_r = sorted(r for part in all_active for r in part)
    factor, package, _ = SOLVERS[args.solver]
    result = {
        "punch": args.punch,
        **({"exponent": args.exponent} if args.punch == "power" else {}),
        "mesh": mesh_rel,
        "mesh_sha256": sha256(mesh_path),
        **({"mesh_parameters": parameters_list(parameters)} if parameters else {}),
        "degree": args.degree,
        "quadrature_degree": 2 * args.degree,
        "depth": args.depth,
        "eps": args.eps if args.punch == "flat-annulus" else None,
        "force": force,
        "inner_radius": (min(active_r) if active_r else None) if args.punch in CONCAVE else None,
        "active_contact_radii": active_r,
        "dofs": dofs,
        "iterations": iterations,
        "wall_s": wall,
        "timings": timings,
        "mpi_processes": comm.size,
        "lu_solver": package,
        "configuration": {
            "solver": args.solver,
            "factorisation": factor,
            "package": package,
            "ordering": "AMD (ICNTL(7) = 0)" if package == "mumps" else "the package's default",
            "mpi_processes": comm.size,
            "blas": blas_library(),
            "blas_threads": os.environ.get("OPENBLAS_NUM_THREADS", "unset"),
            "timed_region": TIMED_REGION,
        },
        "dolfinx_version": dolfinx.__version__,
        "petsc_version": ".".join(str(n) for n in PETSc.Sys.getVersion()),
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "reproduce": our_command(args, mesh_rel, parameters),
        "peer_reproduce": peer_command(args, mesh_rel, parameters, comm.size),
        "notes": "E = 1, nu = 0 (E* = 1), a = h = 1; force includes the 2 pi of the axisymmetric "
                 "weak form; inner_radius is the innermost active contact node (not interpolated)",
    }
    text = json.dumps(result, indent=2) + "\n"
    if args.out:
        write_atomically(args.out, text)
        print(f"{args.out}: force {force:.12g}, {dofs} dofs, {iterations} iterations, {wall:.3f} s",
              file=sys.stderr)
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
