"""The package's functions: arguments to the library's JSON, its JSON back to Python data."""

import json
import math
import os
import reprlib
import tempfile

import numpy as np

from . import _native
from ._native import RingContactError

__version__, __commit__ = _native.build()

#: The keywords of a scene: the keys of a scene file without their sections, ``punch`` (the
#: shape's name, as ``--punch``) and ``eps`` (b/a, as ``--eps``).
SCENE_KEYWORDS = tuple(_native.scene_keywords())

#: The methods ``solve`` takes (as ``verify solve --method``).
METHODS = ("ring-bem", "reference", "fem", "grid-bem", "auto")


def solve(punch=None, *, method="ring-bem", grid=None, grid_extent=None, degree=None, **scene):
    """Solve a punch at one state, or at many, as ``verify solve --json`` does.

    Parameters
    ----------
    punch : str
        ``flat``, ``flat-annulus``, ``cone``, ``sphere``, ``power`` (give ``exponent``),
        ``torus`` (give ``tube_radius``) or ``table`` (give ``profile``, a CSV of ``r/a, g/h``).
    method : str
        ``ring-bem`` (default), ``reference``, ``fem``, ``grid-bem`` or ``auto`` (the cheapest
        method whose own error estimate meets ``tolerance``).
    grid, grid_extent, degree :
        The grid BEM's cells per side and (torus) half-size in units of ``a``; the FEM's element
        degree (1, 2 or 3).
    **scene :
        The scene's keywords (``SCENE_KEYWORDS``), the keys of a scene file:
        ``exponent``, ``tube_radius``, ``profile``; ``rim_radius`` (a), ``inner_radius`` (b, flat
        annulus), ``hole_depth`` (h); ``effective_modulus`` (E*) or ``youngs_modulus`` and
        ``poisson_ratio``; one load: ``depth`` (d), ``force`` (F) or ``contact_ratio`` (b/a of a
        concave punch, prescribed); ``eps`` (b/a: the flat annulus's hole, or a concave punch's
        prescribed contact); ``tolerance`` (relative error wanted).

    Returns
    -------
    dict
        With scalar keywords: the solution (``eps``, ``depth``, ``force``, ``gamma`` or
        ``gamma1``/``gamma2``, stress intensity factors, ``error_estimate``, ``pressure``, ...).
        With one or more keywords given as sequences of one length (``depth=[0.5, 1, 2]``):
        one state per element (scalars repeat), and the answer as columns: each key of the
        solution as a NumPy array (floats with NaN where a state has no value, integers,
        strings) or a list (nested values such as ``pressure``), first ``given_<keyword>`` for
        each keyword that varies. ``pandas.DataFrame(columns)`` makes a table of it.

    Raises
    ------
    RingContactError
        A scene the tool refuses (the message names the keyword and, for many states, the
        state), or a solve that fails.
    """
    keywords = dict(scene)
    if punch is not None:
        keywords["punch"] = punch
    unknown = [k for k in keywords if k not in SCENE_KEYWORDS]
    if unknown:
        raise TypeError(
            f"solve() got an unexpected keyword argument {unknown[0]!r}; a scene takes "
            + ", ".join(SCENE_KEYWORDS)
        )
    varying = {k: _sequence(v) for k, v in keywords.items() if _is_sequence(v)}
    lengths = {len(v) for v in varying.values()}
    if len(lengths) > 1:
        described = ", ".join(f"{k} ({len(v)})" for k, v in varying.items())
        raise RingContactError(f"the keywords given as sequences differ in length: {described}")
    count = lengths.pop() if lengths else None
    if count == 0:
        raise RingContactError(f"no state: {next(iter(varying))} is an empty sequence")
    states = [
        {k: _plain(k, varying[k][i] if k in varying else v) for k, v in keywords.items()}
        for i in range(count or 1)
    ]
    call = _call("solve", punch=punch, method=method, **scene)
    text = _native.solve_scenes(
        json.dumps(states), method, call, grid=grid, grid_extent=grid_extent, degree=degree
    )
    solutions = json.loads(text)
    if count is None:
        return solutions[0]
    columns = {f"given_{k}": _column([_plain(k, x) for x in v]) for k, v in varying.items()}
    columns.update(_columns(solutions))
    return columns


def references():
    """The analytic references and fits the tool knows, with the range of ``eps`` where each
    holds and its source (``verify references --json``): a list of dicts."""
    return json.loads(_native.references())


def jkr(punch, *, exponent=None, profile=None, eps=None, d0h=None, sweep=False, out=None):
    """The JKR adhesive solution (``verify jkr --json``).

    ``punch="flat-annulus"`` with ``eps`` (b/a): the critical states at either edge. A concave
    punch (``cone``, ``sphere``, ``power`` with ``exponent``, ``table`` with ``profile``, a CSV
    of ``r/a, g/h``) or the ``torus`` with ``d0h``
    (the work of adhesion as ``d0/h``, ``d0 = sqrt(2 pi a dw / E*)``; the torus's ``h = a²/(2
    rho)``): pull-off under fixed load and under fixed grips, and from full contact. With
    ``sweep=True`` (concave punches), ``d0/h`` from 0.1 to 100, CSV and SVG written into ``out``.
    Depths in ``d0``, forces in ``F0 = sqrt(8 pi a^3 E* dw)``, negative when tensile.
    Returns a dict.
    """
    call = _call(
        "jkr",
        punch=punch,
        exponent=exponent,
        profile=profile,
        eps=eps,
        d0h=d0h,
        sweep=sweep,
        out=out,
    )
    given = dict(
        exponent=None if exponent is None else float(exponent),
        profile=None if profile is None else os.fspath(profile),
        eps=None if eps is None else float(eps),
        d0h=None if d0h is None else float(d0h),
    )
    if not sweep:
        return json.loads(_native.jkr(str(punch), call, **given))
    out = None if out is None else os.fspath(out)
    return json.loads(_native.jkr_sweep(str(punch), call, out=out, **given))


def grade(results, *, tol=1e-3):
    """Grade another code's results against the converged references (``verify grade``).

    ``results``: a pandas DataFrame, a list of dicts, or the path of a CSV or JSON file, with
    the columns ``verify grade --help`` lists: ``punch``; the state (``depth``, ``force`` or
    ``eps``); the values graded (``force``, ``depth``, ``eps``, ``gamma``, ``gamma1``,
    ``gamma2``); optional ``exponent``, ``tube_radius``, ``profile``, ``E_star``, ``a``, ``h``,
    ``error_estimate``. Rows of a DataFrame or list are named ``row 1``, ``row 2``, ... in
    messages (the first row is row 1).

    Returns the dict of ``verify grade --json``: ``rows`` (each with ``punch``, ``quantity``,
    ``value``, ``reference``, ``reference_error``, ``relative_error``, ``within``,
    ``resolved``, ``note``), ``max_relative_error``, ``tolerance``, ``summary`` (largest and RMS
    error per punch and quantity), ``beyond`` (values beyond ``tol``: 0 means every value
    passed) and ``provenance``. A value beyond ``tol`` is a result, not an exception; a file
    the tool cannot read (a missing column, an unknown punch, a state out of range) raises
    :class:`RingContactError` naming the row and the column.
    """
    tol = float(tol)
    if isinstance(results, (str, os.PathLike)):
        path = os.fspath(results)
        call = _call("grade", path, tol=tol)
        text, _ = _native.grade_file(path, tol, call)
        return json.loads(text)
    if hasattr(results, "to_dict") and hasattr(results, "columns"):
        rows = results.to_dict(orient="records")
        origin = "DataFrame"
    elif isinstance(results, (list, tuple)):
        rows = list(results)
        origin = "list of rows"
    else:
        raise TypeError(
            "grade() takes a pandas DataFrame, a list of dicts or a file path, "
            f"not {type(results).__name__}"
        )
    # Every digit kept (shortest round-trip form); a missing value (NaN, None) is an empty cell.
    text = json.dumps([_plain_row(r) for r in rows])
    call = f"ringcontact.grade(<{origin} of {len(rows)} rows>, tol={tol!r})"
    text, _ = _native.grade_text(text, origin, True, tol, call)
    return json.loads(text)


def dataset(out=None, *, small=False):
    """The converged reference tables (``verify dataset``) as pandas DataFrames by name.

    The non-adhesive functions of each punch, the edges' stress intensity factors, the JKR
    critical states and pull-off forces against ``d0/h``, and the fitted formulas, each value
    with its error bound. ``small=True`` is the coarse copy (a few seconds; the full set takes
    about a minute). With ``out``, the CSV and JSON files and ``datapackage.json`` are written
    there too. Each DataFrame's ``attrs`` hold its ``title``, ``description``, ``fields``
    (name, type, unit, description of each column), ``interpolation_error`` and
    ``provenance``.
    """
    try:
        import pandas as pd
    except ImportError as e:  # pragma: no cover - the tests install pandas
        raise ImportError("ringcontact.dataset() returns pandas DataFrames: pip install pandas") from e
    call = _call("dataset", out=out, small=small)
    if out is None:
        with tempfile.TemporaryDirectory(prefix="ringcontact-dataset-") as directory:
            return _read_dataset(_write_dataset(directory, small, call), pd)
    return _read_dataset(_write_dataset(os.fspath(out), small, call), pd)


def _write_dataset(directory, small, call):
    """Write the dataset into ``directory``; the names of its tables."""
    summary = json.loads(_native.dataset(directory, bool(small), call))
    return directory, [r["name"] for r in summary["resources"]]


def _read_dataset(written, pd):
    """Each table's JSON file as a DataFrame with its description in ``attrs``."""
    directory, names = written
    tables = {}
    for name in names:
        with open(os.path.join(directory, f"{name}.json"), encoding="utf-8") as f:
            table = json.load(f)
        columns = [field["name"] for field in table["fields"]]
        frame = pd.DataFrame(table["rows"], columns=columns)
        for key in ("title", "description", "fields", "interpolation_error", "provenance"):
            frame.attrs[key] = table.get(key)
        tables[name] = frame
    return tables


def _call(function, *args, **kwargs):
    """The Python call, for the provenance of what it writes (long values shortened)."""
    short = reprlib.Repr()
    short.maxlist = short.maxtuple = 6
    words = [short.repr(a) for a in args]
    words += [f"{k}={short.repr(v)}" for k, v in kwargs.items() if v is not None]
    return f"ringcontact.{function}({', '.join(words)})"


def _is_sequence(value):
    """A list, tuple or array of states (a string or path is one value)."""
    if isinstance(value, (str, bytes, os.PathLike, dict)):
        return False
    if isinstance(value, np.ndarray):
        return value.ndim > 0
    return isinstance(value, (list, tuple, range)) or hasattr(value, "__array__")


def _sequence(value):
    """The elements of a sequence of states."""
    return list(np.asarray(value).tolist()) if hasattr(value, "__array__") else list(value)


def _scalar(value):
    """A NumPy scalar as the Python number it holds; a path as its text; anything else as is."""
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if hasattr(value, "item") and not isinstance(value, (str, bytes)):
        return value.item()
    return value


def _plain(key, value):
    """A keyword's value as JSON takes it; a non-finite number is refused here, where JSON could
    not carry it."""
    value = _scalar(value)
    if isinstance(value, float) and not math.isfinite(value):
        raise RingContactError(f"invalid scene: `{key}` must be a finite number (got {value})")
    return value


def _plain_row(row):
    """One row of results given as a dict, with JSON's types (a missing number, NaN, is an empty
    cell)."""
    if not isinstance(row, dict):
        raise TypeError(f"a row of results is a dict of columns, not {type(row).__name__}")
    plain = {}
    for key, value in row.items():
        value = _scalar(value)
        if isinstance(value, float) and not math.isfinite(value):
            value = None
        plain[str(key)] = value
    return plain


def _columns(rows):
    """Rows of solutions as columns: every key, in the order the solutions give them."""
    keys = list(dict.fromkeys(k for row in rows for k in row))
    return {k: _column([row.get(k) for row in rows]) for k in keys}


def _column(values):
    """One column: a float array (NaN where missing), an int array, a str array, or a list."""
    present = [v for v in values if v is not None]
    numbers = all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in present)
    if present and numbers:
        if len(present) == len(values) and all(isinstance(v, int) for v in present):
            return np.array(values, dtype=np.int64)
        return np.array([np.nan if v is None else v for v in values], dtype=float)
    if present and all(isinstance(v, str) for v in present):
        return np.array(["" if v is None else v for v in values], dtype=str)
    return list(values)
