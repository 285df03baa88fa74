"""`ringcontact.solve`: closed forms, the command line's answers, many states, bad input."""

import json
import math

import numpy as np
import pytest

import ringcontact as rc
from conftest import REPOSITORY, run_verify


def test_flat_punch_force_is_boussinesq_in_the_units_given():
    # Boussinesq's flat circular punch: F = 2 E* a d, E* = E / (1 - nu^2) (closed form).
    e, nu, a, d = 3.0, 0.25, 2.0, 0.1
    s = rc.solve("flat", depth=d, rim_radius=a, youngs_modulus=e, poisson_ratio=nu)
    assert s["force"] == pytest.approx(2 * e / (1 - nu**2) * a * d, rel=1e-12)
    assert s["gamma"] == pytest.approx(1.0, rel=1e-12)


def test_sphere_near_full_contact_reaches_barbers_limit():
    # Barber (1976): the spherical concave punch closes at d = 3h, F = 16/3 E* h a, so
    # gamma1 -> 3 and gamma2 -> 8/3 as eps -> 0 (the error is O(eps^2) here: 1e-8).
    s = rc.solve("sphere", contact_ratio=1e-4)
    assert s["gamma1"] == pytest.approx(3.0, rel=1e-6)
    assert s["gamma2"] == pytest.approx(8.0 / 3.0, rel=1e-6)
    assert s["error_estimate"] < 1e-8


def flat_keywords(scene):
    """A scene of the batch file (sections) as the flat keywords of solve()."""
    flat = {}
    for section, fields in scene.items():
        if section == "punch":
            flat["punch"] = fields.pop("shape")
        flat.update(fields)
    return flat


def test_every_scene_of_the_batch_file_equals_the_command_line():
    # The same library from both ends: the batch file's scenes through `verify solve --batch`
    # and through solve(**keywords) must agree in every key but the wall time.
    batch = REPOSITORY / "verify" / "scenes" / "batch.jsonl"
    answers = [json.loads(l) for l in run_verify("solve", "--batch", str(batch)).splitlines()]
    scenes = [json.loads(l) for l in batch.read_text().splitlines() if l.strip()]
    assert len(answers) == len(scenes) >= 5
    for scene, answer in zip(scenes, answers):
        method = scene.pop("method", "ring-bem")
        mine = rc.solve(method=method, **flat_keywords(scene))
        for key, value in answer.items():
            if key in ("line", "wall_s"):
                continue
            if isinstance(value, float):
                assert mine[key] == pytest.approx(value, rel=1e-13, abs=1e-300), key
            else:
                assert mine[key] == value, key


def test_many_states_come_back_as_columns_equal_to_single_solves():
    depths = np.array([0.5, 1.0, 2.0])
    columns = rc.solve("cone", depth=depths, hole_depth=1)
    assert list(columns)[0] == "given_depth"
    np.testing.assert_array_equal(columns["given_depth"], depths)
    assert columns["force"].dtype == float and columns["unknowns"].dtype == np.int64
    assert list(columns["punch"]) == ["cone"] * 3
    # gamma1 = d/h by definition (h = 1 here).
    np.testing.assert_allclose(columns["gamma1"], depths, rtol=1e-12)
    for i, d in enumerate(depths):
        one = rc.solve("cone", depth=float(d))
        assert columns["force"][i] == pytest.approx(one["force"], rel=1e-14)
    # Several keywords vary together, scalars repeat; NumPy scalars are numbers.
    both = rc.solve("sphere", depth=[1, 2], hole_depth=(np.float64(0.5), np.int64(1)))
    np.testing.assert_allclose(both["gamma1"], [2.0, 2.0], rtol=1e-12)


def test_the_torus_and_the_power_law_take_their_keywords():
    torus = rc.solve("torus", tube_radius=0.25, force=[0.01, 0.1])
    assert np.all(torus["inner_radius"] < 1.0) and np.all(torus["outer_radius"] > 1.0)
    # The power law with n = 2 is the sphere (to the ring BEM's tolerance).
    power = rc.solve("power", exponent=2.0, depth=1.5)
    sphere = rc.solve("sphere", depth=1.5)
    assert power["force"] == pytest.approx(sphere["force"], rel=1e-9)


@pytest.mark.parametrize(
    "keywords, words",
    [
        ({"punch": "flat-annulus", "eps": 1.2}, "`eps` must satisfy 0 <= b < a"),
        ({"punch": "cone", "depth": 1, "effective_modulus": -1}, "effective_modulus` must be > 0"),
        ({"punch": "cone", "depth": float("nan")}, "`depth` must be a finite number"),
        ({"punch": "cone", "depth": [1, 2], "force": [1]}, "differ in length: depth (2), force (1)"),
        ({"punch": "cone", "depth": [1, -2]}, "state 2 of 2: invalid scene: `depth` must be > 0"),
        ({"punch": "cone", "depth": [1, "x"]}, "state 2 of 2: invalid scene: `depth` must be a number"),
        ({"punch": "cone", "depth": []}, "no state: depth is an empty sequence"),
        ({"punch": "cone", "eps": 0.5, "depth": 1}, "do not combine it with `depth`"),
        ({"punch": "cone", "shape": "sphere"}, "`punch` and `shape` both name the shape"),
        ({"punch": "table", "profile": "no-such-tip.csv", "depth": 1}, "no-such-tip.csv"),
        ({"depth": 1}, "`punch` is required"),
        ({"punch": "blob", "depth": 1}, '`punch` is not a punch: "blob" (one of flat, '),
        (
            {"punch": "sphere", "depth": 1, "contact_ratio": 0.5},
            "`depth` and `contact_ratio` are both loads: give exactly one",
        ),
        ({"punch": "cone"}, "the cone punch needs one of depth, force or contact_ratio"),
    ],
)
def test_bad_scenes_raise_the_tools_message(keywords, words):
    with pytest.raises(rc.RingContactError) as caught:
        rc.solve(**keywords)
    assert words in str(caught.value)
    # The user gave keywords: the message names no scene file and no section of one.
    assert "scene file" not in str(caught.value) and "load." not in str(caught.value)


def test_unknown_keywords_and_methods_are_named():
    with pytest.raises(TypeError, match="unexpected keyword argument 'depht'"):
        rc.solve("cone", depht=1)
    with pytest.raises(rc.RingContactError, match='method "magic" is not one of ring-bem'):
        rc.solve("cone", depth=1, method="magic")
    with pytest.raises(rc.RingContactError, match="degree 4"):
        rc.solve("cone", depth=1, method="fem", degree=4)
    with pytest.raises(rc.RingContactError, match="grid 4096 outside 8..=2048 cells per side"):
        rc.solve("flat", method="grid-bem", grid=4096)
    assert issubclass(rc.RingContactError, Exception)
    assert rc.RingContactError.__module__ == "ringcontact"
    assert "tolerance" in rc.SCENE_KEYWORDS and "eps" in rc.SCENE_KEYWORDS


def test_the_version_is_the_librarys():
    cargo = (REPOSITORY / "Cargo.toml").read_text()
    version = next(l.split('"')[1] for l in cargo.splitlines() if l.startswith("version"))
    assert rc.__version__ == version
    assert len(rc.__commit__) >= 7
    assert not math.isnan(rc.solve("flat")["force"])
