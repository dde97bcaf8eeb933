"""The shipped catalogue: bearings (``assets/bearings``) and example cases (``assets/cases``).

A bearing file is a case file's ``title`` and ``[bearing]`` section (plus optional ``[materials]``);
:meth:`CatalogueEntry.case_text` turns it into a complete case to start from. A case file is a full
case. Names are the file names without ``.toml``. :func:`resolve_case` is the one place where a CLI
argument (a path or a catalogue name) becomes a :class:`solver.case.Case`.
"""

from __future__ import annotations

import difflib
import math
import tomllib
from dataclasses import dataclass
from importlib.resources import files
from pathlib import Path

from solver.case import Case, load_case
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
        """A complete, valid case file: the case as shipped, or for a bearing one to start from."""
        text = self.text()
        if self.kind == "case":
            return text
        data = tomllib.loads(text)
        b = data["bearing"]
        speed, load = modest_operating_point(
            b["ball_count"], b["ball_diameter_mm"], b["pitch_diameter_mm"]
        )
        return (
            text.rstrip("\n")
            + f"""

# [cage]                                 # optional; estimated from the bearing when absent
# guidance = "outer_ring"                # outer_ring | inner_ring | ball
# pocket_diametral_clearance_mm = ...
# guide_diametral_clearance_mm = ...
# mass_g = ...

# [lubricant]                            # optional; used by the dynamic model
# viscosity_Pas = 0.01
# pressure_viscosity_per_GPa = 20.0
# traction = {{ mu_zero = 0.0, mu_max = 0.05, slip_at_max_m_s = 1.0, mu_infinity = 0.036 }}

[operating]                              # a modest starting point: d_m n = 500 000 mm rpm
inner_ring_speed_rpm = {speed!r}
outer_ring_speed_rpm = 0.0
axial_load_N = {load!r}
radial_load_N = 0.0
radial_load_angle_deg = 0.0
# misalignment_deg = 0.0                 # give at most one of misalignment_deg, tilting_moment_Nm
# tilting_moment_Nm = 0.0

[simulation]                             # dynamic model only
shaft_revolutions = 10.0
samples_per_revolution = 180
"""
        )

    def load(self) -> Case:
        """The validated case (for a bearing: :meth:`case_text`)."""
        return load_case(self.case_text())


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
        close = difflib.get_close_matches(name, self.names, n=3, cutoff=0.5)
        hint = f"did you mean {', '.join(close)}? " if close else ""
        raise CaseError(
            Problem(
                "catalogue",
                f"no catalogue entry named {name!r}: {hint}"
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
    if isinstance(path_or_name, Path):
        return load_case(path_or_name)
    text = str(path_or_name)
    path = Path(text)
    if path.is_file():
        return load_case(path)
    cat = catalogue()
    if text in cat:
        return cat.get(text).load()
    if path.is_dir():
        raise CaseError(Problem("file", f"{text} is a folder, not a case file: give a .toml file"))
    if path.suffix == ".toml" or "/" in text or "\\" in text:
        raise CaseError(Problem("file", f"case file not found: {text}"))
    close = difflib.get_close_matches(text, cat.names, n=3, cutoff=0.5)
    hint = f"did you mean {', '.join(close)}? " if close else ""
    raise CaseError(
        Problem(
            "catalogue",
            f"{text!r} is neither a case file nor a catalogue name: "
            f"{hint}catalogue names: {', '.join(cat.names)}",
        )
    )
