"""Named oils: the ``[lubricant]`` key values of common bearing oils, each value with its source.

The oils live in the data file ``solver/data/oils.toml`` (its header says how it is laid out). A
case names one with ``lubricant.oil = "NAME"``: the oil's values fill the ``[lubricant]`` keys the
case does not give (solver.case.validate), and keys the case gives override them.
docs/case-format.md ("Named oils") lists them.

Each source names a document of the file's ``[documents]`` table in brackets, or starts with
``ESTIMATE`` and says why the value is an estimate (a class value no document found through the
project's tools states). No published traction curve with numbers was found to fit the rheology
parameters to (docs/sources.md).
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from functools import cache
from pathlib import Path

OILS_FILE = Path(__file__).with_name("data") / "oils.toml"


@dataclass(frozen=True)
class Oil:
    """One named oil: ``values`` (``[lubricant]`` keys, case units), ``sources`` (key -> where
    the value comes from) and a one-line ``description``."""

    name: str
    description: str
    values: dict
    sources: dict

    def estimated_keys(self) -> list[str]:
        """The keys whose values are estimates (no document states them)."""
        return [k for k, source in self.sources.items() if source.startswith("ESTIMATE")]


@cache
def _table() -> tuple[dict, dict]:
    """(documents, {name: Oil}) of the oils file, read once."""
    with OILS_FILE.open("rb") as stream:
        data = tomllib.load(stream)
    oils = {
        name: Oil(name, entry["description"], dict(entry["values"]), dict(entry["sources"]))
        for name, entry in data["oils"].items()
    }
    return dict(data["documents"]), oils


def oil_names() -> tuple[str, ...]:
    """The names of the named oils, in the file's order."""
    return tuple(_table()[1])


def documents() -> dict[str, str]:
    """Reference key (as cited in brackets by a source) -> the document."""
    return dict(_table()[0])


def oil(name: str) -> Oil:
    """The named oil ``name``; ValueError naming the known oils otherwise."""
    oils = _table()[1]
    if name not in oils:
        raise ValueError(f"unknown oil {name!r}; known oils: {', '.join(oils)}")
    return oils[name]


def lubricant_table(name: str) -> dict:
    """The ``[lubricant]`` keys of oil ``name`` (a copy); ValueError for an unknown oil."""
    return dict(oil(name).values)
