"""The Python examples of the README and docs/tasks.md run as written (from the repository's
root, as a reader in a checkout would run them), so the docs cannot drift from the package."""

import re

import pytest

from conftest import REPOSITORY

PAGES = ["README.md", "docs/tasks.md"]


def python_blocks(page):
    text = (REPOSITORY / page).read_text(encoding="utf-8")
    return re.findall(r"```python\n(.*?)```", text, flags=re.S)


@pytest.mark.parametrize("page", PAGES)
def test_the_pages_python_runs(page, monkeypatch):
    blocks = python_blocks(page)
    assert blocks, f"{page} has no python block"
    monkeypatch.chdir(REPOSITORY)
    for code in blocks:
        exec(compile(code, page, "exec"), {"__name__": "__docs__"})
