"""`ringcontact.references` and `ringcontact.jkr`: closed forms and the command line's output."""

import json

import pytest

import ringcontact as rc
from conftest import REPOSITORY, run_verify


def test_references_are_the_command_lines():
    refs = rc.references()
    assert refs == json.loads(run_verify("references", "--json"))
    assert any(r["name"] == "boussinesq" and r["kind"] == "exact" for r in refs)


def test_flat_annulus_with_a_small_hole_pulls_off_as_kendalls_punch():
    # Kendall (1971): the flat circular punch pulls off at F = -sqrt(8 pi a^3 E* dw) = -F0 and
    # d = -d0; a hole of b/a = 1e-3 changes that by far less than 1e-6.
    r = rc.jkr("flat-annulus", eps=1e-3)
    assert r["governing_edge"] == "outer"
    assert r["fc_outer"] == pytest.approx(-1.0, abs=1e-6)
    assert r["dc_outer"] == pytest.approx(-1.0, abs=1e-6)


def test_jkr_of_a_concave_punch_is_the_command_lines():
    mine = rc.jkr("cone", d0h=0.5)
    theirs = json.loads(run_verify("jkr", "--punch", "cone", "--d0h", "0.5", "--json"))
    assert mine == theirs
    assert mine["fixed_load"]["force"] < 0


def test_jkr_of_a_table_punch_tends_to_the_sphere_it_samples():
    # The committed table of the sphere's profile at 21 points: its pull-offs lie within the
    # second-order interpolation error of the sphere's (measured 1.8e-4 under fixed load,
    # 1.6e-5 from full contact); the result names the table it read.
    table = REPOSITORY / "verify" / "profiles" / "sphere-21.csv"
    mine = rc.jkr("table", profile=table, d0h=0.5)
    sphere = rc.jkr("sphere", d0h=0.5)
    for route in (lambda r: r["fixed_load"]["force"], lambda r: r["full_contact"]["pulloff"]["force"]):
        assert route(mine) == pytest.approx(route(sphere), rel=5e-4)
    assert mine["punch"] == "table" and mine["profile_file"].endswith("sphere-21.csv")
    with pytest.raises(rc.RingContactError, match="--profile FILE"):
        rc.jkr("table", d0h=0.5)


def test_jkr_errors_name_the_keyword():
    # The library's own messages, in the keywords a Python call gives (not the command line's
    # flags).
    with pytest.raises(rc.RingContactError, match="`d0h` is needed: the cone's work of adhesion"):
        rc.jkr("cone")
    with pytest.raises(rc.RingContactError, match=r'unknown punch "blob" \(one of flat, '):
        rc.jkr("blob", d0h=1)
    with pytest.raises(rc.RingContactError, match="0 < b/a < 1"):
        rc.jkr("flat-annulus", eps=0.0)
    with pytest.raises(rc.RingContactError, match="`eps` fixes the hole of a fixed annulus"):
        rc.jkr("sphere", eps=0.5, d0h=1)
    with pytest.raises(rc.RingContactError, match="`d0h` is a concave punch's work of adhesion"):
        rc.jkr("flat-annulus", eps=0.5, d0h=1)
    with pytest.raises(rc.RingContactError, match="Kendall's"):
        rc.jkr("flat", d0h=1)


def test_jkr_sweep_is_the_command_lines(tmp_path):
    # The fixed annulus's sweep over b/a through the library's call: the same rows as
    # `verify jkr --sweep --json`, and its CSV and chart written where asked.
    mine = rc.jkr("flat-annulus", sweep=True, out=tmp_path / "python")
    theirs = json.loads(run_verify("jkr", "--punch", "flat-annulus", "--sweep", "--json",
                                   "--out", str(tmp_path / "cli")))
    assert mine == theirs and len(mine) > 10
    assert (tmp_path / "python" / "critical-flat-annulus.csv").is_file()
    with pytest.raises(rc.RingContactError, match="`eps` fixes the hole of a fixed annulus"):
        rc.jkr("cone", sweep=True, eps=0.5, out=tmp_path)
    with pytest.raises(rc.RingContactError, match="`d0h` is a concave punch's work of adhesion"):
        rc.jkr("flat-annulus", sweep=True, d0h=1.0, out=tmp_path)
