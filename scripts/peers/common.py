"""Shared set-up of the peer runs: the same grid, profile and mask as `verify --method grid-bem`.

Grid: N x N square cells on [-L, L]^2 (a = 1; L = 1 but for the torus, whose square is given),
cell centres x_i = (i + 1/2) dx - L, dx = 2L/N. A cell belongs to the punch when its centre lies
in b <= r <= a (flat annulus), r <= a (the other punches with a rim) or r <= L (the torus).
Gap profile g(r) = h (1 - r) (cone), h (1 - r^2) (sphere), h (1 - r^n) (power law),
h (1 - r)^2 (torus), 0 (flat), h = 1; E* = 1.
"""

import numpy as np


def grid(n, half_size=1.0):
    dx = 2.0 * half_size / n
    c = (np.arange(n) + 0.5) * dx - half_size
    x, y = np.meshgrid(c, c, indexing="ij")
    return np.hypot(x, y), dx


def punch(kind, n, eps=0.0, exponent=None, half_size=1.0):
    """The cells the punch may touch and its gap there, on the grid of `verify --method grid-bem`."""
    if kind != "torus" and half_size != 1.0:
        raise ValueError("only the torus's grid covers a square other than [-a, a]^2")
    r, dx = grid(n, half_size)
    inside = r <= half_size
    if kind == "flat-annulus":
        inside &= r >= eps
    if kind == "cone":
        g = 1.0 - r
    elif kind == "sphere":
        g = 1.0 - r * r
    elif kind == "power":
        g = 1.0 - r ** exponent
    elif kind == "torus":
        g = (1.0 - r) ** 2
    else:
        g = np.zeros_like(r)
    return inside, g, dx


def tamaas_solve(inside, g, dx, load, tol=1e-12):
    """Tamaas (non-periodic, dcfft): solve for a total force; return (depth, iterations text)."""
    import tamaas as tm
    n = inside.shape[0]
    size = n * dx
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [size, size], [n, n])
    model.E = 1.0
    model.nu = 0.0
    tm.ModelFactory.registerNonPeriodic(model, "dcfft")
    heights = np.where(inside, -g, -1e3)
    solver = tm.PolonskyKeerRey(model, heights, tol)
    solver.setIntegralOperator("dcfft")
    solver.solve(load / size ** 2)  # the argument is the mean pressure over the grid
    traction = np.array(model.traction)
    displacement = np.zeros_like(traction)
    model.operators["dcfft"](model.traction, displacement)
    contact = traction > 0
    depth = float(np.mean((displacement - heights)[contact]))
    force = float(traction.sum() * dx * dx)
    return depth, force


def tamaas_at_depth(inside, g, dx, depth, flat):
    """Tamaas is load-controlled: scale (flat punches, linear) or secant on the load."""
    if flat:
        d, f = tamaas_solve(inside, g, dx, 2.0 * depth)
        return f * depth / d, 1
    loads = [2.0 * depth, 2.2 * depth]
    depths = [tamaas_solve(inside, g, dx, w)[0] for w in loads]
    solves = 2
    while abs(depths[-1] - depth) > 1e-12 * depth and solves < 40:
        w = loads[-1] + (depth - depths[-1]) * (loads[-1] - loads[-2]) / (depths[-1] - depths[-2])
        loads.append(w)
        depths.append(tamaas_solve(inside, g, dx, w)[0])
        solves += 1
    return loads[-1], solves


def contactmechanics_at_depth(inside, g, dx, depth):
    from ContactMechanics import FreeFFTElasticHalfSpace, make_system
    from SurfaceTopography import Topography
    n = inside.shape[0]
    size = n * dx
    substrate = FreeFFTElasticHalfSpace((n, n), young=1.0, physical_sizes=(size, size))
    heights = np.ma.masked_where(~inside, -g)
    system = make_system(substrate=substrate, surface=Topography(heights, (size, size)))
    result = system.minimize_proxy(offset=depth, pentol=1e-12 * depth, maxiter=20000)
    return float(result.jac.sum()), int(getattr(result, "nit", -1))
