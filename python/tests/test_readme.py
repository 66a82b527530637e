"""The Python examples of the READMEs run as written (in a scratch folder, the repository's
models found where the README says)."""

from __future__ import annotations

import os
import re
from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")

ROOT = Path(__file__).resolve().parents[2]


def _blocks():
    for readme in (ROOT / "README.md", ROOT / "python" / "README.md"):
        for n, code in enumerate(re.findall(r"```python\n(.*?)```", readme.read_text(), re.S)):
            yield pytest.param(code, id=f"{readme.relative_to(ROOT)}#{n}")


@pytest.mark.parametrize("code", list(_blocks()))
def test_readme_python_example_runs(code, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "assets").symlink_to(ROOT / "assets")
    exec(compile(code, "README", "exec"), {"__name__": "__readme__"})
    assert any(tmp_path.iterdir())
    assert os.listdir(tmp_path) != ["assets"], "the example writes its files"
