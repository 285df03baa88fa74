"""The notebook-style example runs, top to bottom, as a reader would run it."""

import pathlib
import runpy

EXAMPLE = pathlib.Path(__file__).resolve().parents[1] / "examples" / "quickstart.py"


def test_the_quickstart_runs(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    names = runpy.run_path(str(EXAMPLE), run_name="__main__")
    printed = capsys.readouterr().out
    assert "ringcontact" in printed and "pull-off force" in printed
    # The example's numbers are the library's: its one state has the sphere's gamma1 = d/h = 1.
    assert abs(names["state"]["gamma1"] - 1.0) < 1e-9
    assert len(names["cone"]) == 9 and names["graded"]["within"].dtype == bool
    assert list(tmp_path.iterdir()) == []
