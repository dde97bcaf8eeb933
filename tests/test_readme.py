"""The README's "From Python:" example runs as written.

The code block is read from README.md and executed unchanged, in a temporary folder that holds the
``my.toml`` it loads: the shipped case ``spindle-combined-load`` written out (what the README's
command-line tour does with ``racetrace cases show ... > my.toml``), with its ``[simulation]`` run
shortened to 0.2 shaft revolutions so that the dynamic run takes seconds.
"""

from __future__ import annotations

import re
from pathlib import Path

import xarray as xr

import solver

README = Path(__file__).resolve().parents[1] / "README.md"


def python_example() -> str:
    """The fenced ``python`` block that follows "From Python:" in README.md."""
    match = re.search(r"^From Python:\s*\n```python\n(.*?)^```", README.read_text(), re.M | re.S)
    assert match, 'README.md has no ```python block after "From Python:"'
    return match.group(1)


def test_readme_python_example_runs(tmp_path, monkeypatch):
    case = solver.catalogue().get("spindle-combined-load").load()
    short = case.with_values({"simulation.shaft_revolutions": 0.2})
    (tmp_path / "my.toml").write_text(short.to_toml())
    monkeypatch.chdir(tmp_path)

    code = python_example()
    namespace: dict = {"__name__": "readme_example"}
    exec(compile(code, f"{README}:From Python", "exec"), namespace)

    assert isinstance(namespace["qs"], xr.Dataset) and "time" not in namespace["qs"].dims
    run = namespace["run"]
    assert isinstance(run, xr.Dataset) and run.sizes["time"] > 1
    assert run.attrs["complete"] == 1
    saved = tmp_path / "run.nc"
    assert saved.is_file()
    assert solver.load_dataset(saved).sizes["time"] == run.sizes["time"]
