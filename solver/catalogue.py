"""The shipped catalogue: bearings (``assets/bearings``) and example cases (``assets/cases``).

A bearing file is a case file's ``title`` and ``[bearing]`` section (plus optional ``[materials]``);
:meth:`CatalogueEntry.load` completes it with a modest operating point into a case to start from,
and :meth:`CatalogueEntry.case_text` writes that case with the case writer (every other value is the
schema's default or estimate). A case file is a full case. Names are the file names without
``.toml``. :func:`resolve_case` is the one place where a CLI argument (a path or a catalogue name)
becomes a :class:`solver.case.Case`.
"""

from __future__ import annotations

import difflib
import math
import os
import tomllib
from dataclasses import dataclass
from importlib.resources import files
from pathlib import Path

from solver.case import Case, load_case, parse_case
from solver.case.io import parse_toml
from solver.errors import CaseError, Problem

_KINDS = (("bearing", "bearings"), ("case", "cases"))


def _round_sig(value: float, digits: int = 2) -> float:
    """value rounded to ``digits`` significant figures."""
    if value == 0:
        return 0.0
    scale = 10 ** (digits - 1 - math.floor(math.log10(abs(value))))
    return round(value * scale) / scale


def modest_operating_point(ball_count: int, ball_diameter_mm: float, pitch_diameter_mm: float):
    """(speed rpm, axial load N) to start from: d_m n = 500 000 mm rpm, F_a = 0.5 Z D^2 N/mm^2.

    Both rounded to two significant figures; a light-to-moderate load and speed for any size.
    """
    speed = _round_sig(5.0e5 / pitch_diameter_mm)
    load = _round_sig(0.5 * ball_count * ball_diameter_mm**2)
    return speed, load


def did_you_mean(name: str, names: list[str]) -> str:
    """ "did you mean A, B? " with up to three of ``names`` close to ``name``, or ""."""
    close = difflib.get_close_matches(name, names, n=3, cutoff=0.5)
    return f"did you mean {', '.join(close)}? " if close else ""


@dataclass(frozen=True)
class CatalogueEntry:
    """One shipped bearing or case. ``path`` is an importlib.resources Traversable (a file)."""

    name: str
    kind: str  # "bearing" | "case"
    title: str
    provenance: str
    path: object

    def text(self) -> str:
        """The file as shipped."""
        return self.path.read_text(encoding="utf-8")

    def case_text(self) -> str:
        """A complete, valid case file: the case as shipped, or for a bearing the case of
        :meth:`load` as the case writer writes it."""
        if self.kind == "case":
            return self.text()
        case = self.load()
        header = (
            f"# A case to start from: the catalogue bearing {self.name} at a modest operating "
            f"point (d_m n = 500 000 mm rpm, axial load 0.5 Z D^2 N/mm^2).\n"
            "# Keys written as comments take the value shown (a default or an estimate).\n"
        )
        return header + case.to_toml()

    def load(self) -> Case:
        """The validated case; for a bearing, the bearing at a modest operating point
        (:func:`modest_operating_point`) with every other value from the case schema."""
        source = f"catalogue {self.kind} {self.name}"
        if self.kind == "case":  # a history file of a shipped case lies beside it
            return parse_case(self.text(), source, Path(str(self.path)).parent)
        data = parse_toml(self.text(), source)
        b = data["bearing"]
        speed, load = modest_operating_point(
            b["ball_count"], b["ball_diameter_mm"], b["pitch_diameter_mm"]
        )
        data["operating"] = {"inner_ring_speed_rpm": speed, "axial_load_N": load}
        return Case.from_dict(data)


@dataclass(frozen=True)
class Catalogue:
    """All shipped entries, bearings first, each group sorted by name."""

    entries: tuple[CatalogueEntry, ...]

    @property
    def bearings(self) -> tuple[CatalogueEntry, ...]:
        return tuple(e for e in self.entries if e.kind == "bearing")

    @property
    def cases(self) -> tuple[CatalogueEntry, ...]:
        return tuple(e for e in self.entries if e.kind == "case")

    @property
    def names(self) -> list[str]:
        return [e.name for e in self.entries]

    def get(self, name: str) -> CatalogueEntry:
        """The entry called ``name``; CaseError (key "catalogue") with suggestions otherwise."""
        for entry in self.entries:
            if entry.name == name:
                return entry
        raise CaseError(
            Problem(
                "catalogue",
                f"no catalogue entry named {name!r}: {did_you_mean(name, self.names)}"
                f"known names: {', '.join(self.names)} "
                "(list them with `racetrace cases`)",
            )
        )

    def __contains__(self, name: object) -> bool:
        return name in self.names

    def __iter__(self):
        return iter(self.entries)

    def __len__(self) -> int:
        return len(self.entries)


def _entry(kind: str, resource) -> CatalogueEntry:
    data = tomllib.loads(resource.read_text(encoding="utf-8"))
    bearing = data.get("bearing", {})
    return CatalogueEntry(
        name=resource.name.removesuffix(".toml"),
        kind=kind,
        title=str(data.get("title", "")),
        provenance=str(bearing.get("provenance", "estimated")),
        path=resource,
    )


def _assets_root():
    """Traversable root of the ``assets`` package data.

    Falls back to the first real folder of ``assets.__path__`` when ``assets`` was imported as a
    namespace package (an editable install made before ``assets/__init__.py`` existed), which
    ``importlib.resources.files`` cannot read.
    """
    try:
        return files("assets")
    except NotADirectoryError:
        import assets

        for folder in assets.__path__:
            if Path(folder).is_dir():
                return Path(folder)
        raise


def catalogue() -> Catalogue:
    """The shipped catalogue (read from the ``assets`` package data)."""
    root = _assets_root()
    entries = []
    for kind, folder in _KINDS:
        resources = sorted(
            (r for r in root.joinpath(folder).iterdir() if r.name.endswith(".toml")),
            key=lambda r: r.name,
        )
        entries += [_entry(kind, r) for r in resources]
    return Catalogue(tuple(entries))


def resolve_case(path_or_name) -> Case:
    """A case from a :class:`Case`, a path to a case file, or a catalogue name. Raises CaseError.

    An existing file wins over a catalogue name of the same spelling. Used by every CLI command that
    takes a CASE argument.
    """
    if isinstance(path_or_name, Case):
        return path_or_name
    if isinstance(path_or_name, os.PathLike):
        return load_case(path_or_name)
    text = str(path_or_name)
    path = Path(text)
    if path.is_file():
        return load_case(path)
    cat = catalogue()
    if text in cat:
        return cat.get(text).load()
    if os.path.lexists(path) or path.suffix == ".toml" or "/" in text or "\\" in text:
        return load_case(path)  # a folder, a FIFO, a device, a missing file: load_case says which
    raise CaseError(
        Problem(
            "catalogue",
            f"{text!r} is neither a case file nor a catalogue name: "
            f"{did_you_mean(text, cat.names)}catalogue names: {', '.join(cat.names)}",
        )
    )
