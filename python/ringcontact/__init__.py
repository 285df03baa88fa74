"""ringcontact: rigid punches whose contact with an elastic half-space is a ring, from Python.

The same Rust library as the ``verify`` command line (no second implementation): every
function here calls it in-process and returns plain Python data.

Conventions: ``E* = E/(1 - nu**2)`` of the half-space, ``a`` the rim radius, ``h`` the depth of
a concave punch's hole, ``d`` the indentation depth of the rim (positive into the solid), ``F``
the force (positive in compression). Without dimensional keywords ``E* = a = h = 1``: then
``depth = d/h = gamma1`` and ``force = F/(E* h a) = 2 gamma2`` (concave punches), ``force =
F/(E* a d) = 2 gamma`` at ``depth = 1`` (flat punches).

Functions
---------
solve(punch, **scene)       one state (a dict) or many (columns as NumPy arrays)
references()                the analytic references and where each holds
jkr(punch, ...)             the JKR adhesive solution (pull-off under fixed load and grips)
grade(results, tol=1e-3)    another code's results against the converged references
dataset(out=None, small=False)   the converged reference tables as pandas DataFrames

Errors: every refused input and every failed solve raises :class:`RingContactError` with the
message ``verify`` prints. Long calls release the interpreter lock: other threads (and a
notebook's kernel) keep running while the library works.
"""

from ._api import (
    SCENE_KEYWORDS,
    RingContactError,
    __commit__,
    __version__,
    dataset,
    grade,
    jkr,
    references,
    solve,
)

__all__ = [
    "RingContactError",
    "SCENE_KEYWORDS",
    "__commit__",
    "__version__",
    "dataset",
    "grade",
    "jkr",
    "references",
    "solve",
]
