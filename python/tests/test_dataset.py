"""`ringcontact.dataset`: the committed small copy reproduced, with units and provenance."""

import json

import numpy as np
import pandas as pd
import pytest

import ringcontact as rc
from conftest import REPOSITORY

COMMITTED = REPOSITORY / "verify" / "dataset"


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    out = tmp_path_factory.mktemp("dataset")
    return out, rc.dataset(out, small=True)


def test_the_small_dataset_reproduces_the_committed_copy(small):
    _, tables = small
    package = json.loads((COMMITTED / "datapackage.json").read_text())
    names = [r["name"] for r in package["resources"]]
    assert sorted(tables) == sorted(names)
    for name, frame in tables.items():
        stored = pd.read_csv(COMMITTED / f"{name}.csv")
        assert list(frame.columns) == list(stored.columns), name
        assert len(frame) == len(stored), name
        for column in frame.columns:
            if pd.api.types.is_numeric_dtype(stored[column]):
                mine = frame[column].to_numpy(dtype=float)
                np.testing.assert_allclose(mine, stored[column], rtol=1e-8, atol=1e-12, err_msg=f"{name}.{column}")


def test_each_table_carries_units_and_provenance(small):
    out, tables = small
    cone = tables["functions-cone"]
    units = {f["name"]: f["unit"] for f in cone.attrs["fields"]}
    assert units["gamma1"] == "1" and units["eps"] == "1"
    command = cone.attrs["provenance"]["command"]
    assert command.startswith("ringcontact.dataset(") and "small=True" in command
    assert cone.attrs["provenance"]["ringcontact_version"] == rc.__version__
    assert (out / "datapackage.json").exists() and (out / "functions-cone.csv").exists()


def test_the_spheres_table_ends_at_barbers_full_contact(small):
    # Barber (1976): gamma1 -> 3, gamma2 -> 8/3 as eps -> 0 (the table starts at eps = 1e-4).
    sphere = small[1]["functions-sphere"].sort_values("eps")
    assert sphere["gamma1"].iloc[0] == pytest.approx(3.0, rel=1e-6)
    assert sphere["gamma2"].iloc[0] == pytest.approx(8.0 / 3.0, rel=1e-6)


def test_without_a_directory_nothing_is_left_behind(tmp_path, monkeypatch):
    import tempfile

    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    tables = rc.dataset(small=True)
    assert "fits" in tables
    assert list(tmp_path.iterdir()) == []
