"""The validated case: frozen dataclasses, one per section, attributes named exactly as the
case keys.

The section classes (:class:`Bearing`, :class:`Cage`, :class:`Lubricant` with its :class:`Traction`,
:class:`Operating`, :class:`Simulation`) are generated from :data:`solver.case.schema.FIELDS`, so a
new key in the table is a new attribute here. Values are in the units of the key names (mm, deg,
rpm, N, g); every key not given holds its schema default or estimate, except optional keys
without a default (``Default.OPTIONAL``), which are ``None``. Build cases with
:func:`solver.case.load_case`, :func:`solver.case.parse_case`, :meth:`Case.from_dict` or
:meth:`Case.with_values`: these validate (:mod:`.validate`); the constructors do not.
"""

from __future__ import annotations

import copy
import dataclasses
from dataclasses import dataclass, field, make_dataclass

from solver.errors import CaseError, Problem
from solver.inputs import bearing_geometry, material_from_table
from solver.materials import BUILTIN_MATERIALS, Material

from .bearing_set import read_set
from .schema import (
    ASSUMED_METHOD,
    ASSUMED_OIL_VOLUME_FRACTION,
    FIELDS,
    LUBRICATION_METHODS,
    MATERIAL_FIELDS,
    OPTIONAL,
)
from .validate import CaseValues, validate
from .writer import case_to_toml

_PY_TYPES = {
    "float": "float",
    "int": "int",
    "str": "str",
    "choice": "str",
    "bool": "bool",
    "material": "str | dict",
}


def _make_section(class_name: str, prefix: tuple[str, ...]):
    """Frozen dataclass with one attribute per FIELDS key under ``prefix`` (sub-tables nested)."""
    attributes: list[tuple[str, str]] = []
    seen_subtables: set[str] = set()
    lines = []
    for f in FIELDS:
        path = f.path
        if path[: len(prefix)] != prefix or len(path) <= len(prefix):
            continue
        name = path[len(prefix)]
        if len(path) == len(prefix) + 1:
            optional = " | None" if f.default is OPTIONAL else ""
            attributes.append((name, _PY_TYPES[f.type] + optional))
            unit = f" [{f.unit}]" if f.unit else ""
            lines.append(f"    {name}{unit}: {f.help}")
        elif name not in seen_subtables:
            seen_subtables.add(name)
            attributes.append((name, name.capitalize()))
            lines.append(f"    {name}: inline table ({name.capitalize()})")
    doc = f"[{'.'.join(prefix)}] of a case file (units as in the key names).\n\n" + "\n".join(lines)
    cls = make_dataclass(class_name, attributes, frozen=True, namespace={"__doc__": doc})
    cls.__module__ = __name__  # so that pickle finds the class (app worker processes)
    return cls


Traction = _make_section("Traction", ("lubricant", "traction"))
Bearing = _make_section("Bearing", ("bearing",))
Cage = _make_section("Cage", ("cage",))
Lubricant = _make_section("Lubricant", ("lubricant",))
Operating = _make_section("Operating", ("operating",))
Simulation = _make_section("Simulation", ("simulation",))

#: section name -> class; sub-table (section, key) -> class
SECTION_CLASSES = {
    "bearing": Bearing,
    "cage": Cage,
    "lubricant": Lubricant,
    "operating": Operating,
    "simulation": Simulation,
}
SUBTABLE_CLASSES = {("lubricant", "traction"): Traction}


def _section(prefix: tuple[str, ...], values: dict):
    """Section (or sub-table) object of ``prefix`` from its validated values."""
    cls = SUBTABLE_CLASSES[prefix] if len(prefix) > 1 else SECTION_CLASSES[prefix[0]]
    kwargs = {
        name: _section(prefix + (name,), value) if prefix + (name,) in SUBTABLE_CLASSES else value
        for name, value in values.items()
    }
    return cls(**kwargs)


def case_from_values(checked: CaseValues, source_dir: str = "") -> Case:
    """The :class:`Case` of validated values (:func:`solver.case.validate.validate`);
    ``source_dir``: the folder of the case file they were read from ("" for none)."""
    sections = {name: _section((name,), values) for name, values in checked.sections.items()}
    return Case(
        title=checked.title,
        description=checked.description,
        materials=checked.materials,
        estimated=checked.estimated,
        lubricant_given="lubricant" not in checked.absent_sections,
        traction_given=checked.traction_given,
        from_oil=checked.from_oil,
        histories=dict(checked.histories),
        source_dir=str(source_dir or ""),
        **sections,
    )


@dataclass(frozen=True)
class Case:
    """One bearing and one operating condition, validated.

    ``materials`` holds the user material tables as written (``{name: {youngs_modulus_GPa, ...}}``).
    Every section holds values: keys not given hold their schema default, and the cage values not
    given are estimated from the bearing (the rules are in :data:`solver.case.schema.FIELDS` and
    docs/case-format.md); the estimated dotted keys are listed in ``estimated`` and written as
    comments by :meth:`to_toml`, so they follow the bearing when it is edited.
    ``lubricant_given`` is False when the file has no ``[lubricant]`` section: ``lubricant`` then
    holds the schema's default oil, :meth:`to_toml` writes it as comments and the dynamic result
    says that the default oil was used. ``traction_given`` is True when the file has a
    ``lubricant.traction`` table (the slip curve): otherwise ``lubricant.traction`` holds the
    schema's default curve, which :meth:`to_dict` leaves out and :meth:`to_toml` writes as a
    comment. ``from_oil`` lists the ``[lubricant]`` keys whose values come from the named oil
    ``lubricant.oil`` (not given in the file): :meth:`to_dict` leaves them out (the oil's name
    brings them back) and :meth:`to_toml` writes them as comments. ``description`` is the case's
    free-text note of what is known about it (read by no model). ``histories`` maps each
    ``[operating]`` key given as a time history to its :class:`solver.case.history.KeyHistory`
    (the section's attribute then holds its value at t = 0); ``source_dir`` is the folder of the
    case file (where a history file is read from; "" when the case was not read from a file).
    """

    title: str
    bearing: Bearing
    materials: dict = field(default_factory=dict)
    cage: Cage = None
    lubricant: Lubricant = None
    operating: Operating = None
    simulation: Simulation = None
    estimated: frozenset = frozenset()
    lubricant_given: bool = True
    traction_given: bool = False
    from_oil: frozenset = frozenset()
    description: str = ""
    histories: dict = field(default_factory=dict)
    source_dir: str = field(default="", compare=False)
    bearing_set: object = None  # a solver.case.bearing_set.BearingSet for a [set] case, else None

    @property
    def has_history(self) -> bool:
        """True when an operating key is a time history (the run is then a duration in
        seconds)."""
        return bool(self.histories)

    # ---- materials -----------------------------------------------------------------------------
    def resolve_material(self, spec: str | dict, name: str = "inline") -> Material:
        """The :class:`Material` for a name (built-in or user) or an inline table."""
        if isinstance(spec, dict):
            return material_from_table(name, spec)
        if spec in self.materials:
            return material_from_table(spec, self.materials[spec])
        return BUILTIN_MATERIALS[spec]

    @property
    def ball_material(self) -> Material:
        """Resolved ball material (SI)."""
        return self.resolve_material(self.bearing.ball_material, "bearing.ball_material")

    @property
    def ring_material(self) -> Material:
        """Resolved ring material (SI)."""
        return self.resolve_material(self.bearing.ring_material, "bearing.ring_material")

    # ---- conversions ---------------------------------------------------------------------------
    def geometry(self):
        """:class:`solver.geometry.BearingGeometry` of this case (SI)."""
        return bearing_geometry(self)

    def warnings(self) -> list[Problem]:
        """Valid but doubtful data, each naming its key: the CLI and the app show these.

        Shoulder (land) diameters that do not rise above their groove: such a land offers no
        shoulder, so the truncation check reports every contact of that race as truncated. (A land
        at or beyond the pitch diameter is not a warning but a validation error.) A
        ``lubricant.traction`` table given while the traction model is the rheology, which does not
        read it. No ``lubricant.method``: the method assumed (and its mixture) is named.
        """
        g = self.geometry()
        found: list[Problem] = []
        model = self.lubricant.traction_model
        if self.traction_given and model != "slip_curve":
            found.append(
                Problem(
                    "lubricant.traction",
                    f'lubricant.traction is given but lubricant.traction_model = "{model}" does '
                    "not read it (the traction comes from the oil's rheology); set "
                    'lubricant.traction_model = "slip_curve" to use the table, or remove the table',
                    ("lubricant.traction_model",),
                )
            )
        if self.lubricant.method is None:
            found.append(
                Problem(
                    "lubricant.method",
                    "lubricant.method is not given: the drag and the cage land are those of "
                    f'"{ASSUMED_METHOD}" lubrication with an oil-air mixture of '
                    f"{ASSUMED_OIL_VOLUME_FRACTION:g} oil by volume and a flooded cage land "
                    "(docs/lubrication.md); name the method ("
                    + ", ".join(LUBRICATION_METHODS)
                    + ") and its supply so that they follow it",
                )
            )
        checks = (
            (
                "inner",
                self.bearing.inner_shoulder_diameter_mm,
                g.inner_groove_bottom_diameter,
                "above",
            ),
            (
                "outer",
                self.bearing.outer_shoulder_diameter_mm,
                g.outer_groove_bottom_diameter,
                "below",
            ),
        )
        for race, land_mm, bottom_m, side in checks:
            if land_mm is None:
                continue
            bottom_mm = bottom_m * 1e3
            off = land_mm <= bottom_mm if race == "inner" else land_mm >= bottom_mm
            if off:
                key = f"bearing.{race}_shoulder_diameter_mm"
                found.append(
                    Problem(
                        key,
                        f"{key} = {land_mm:g}: the {race} land should lie {side} the {race} "
                        f"groove-bottom diameter ({bottom_mm:.4g} mm) to form a shoulder; "
                        "as given, every contact on this race is reported as truncated "
                        "(truncation_margin < 0)",
                    )
                )
        return found

    def to_dict(self) -> dict:
        """Nested plain dict as it would be written in a case file (absent/estimated keys left out).

        ``Case.from_dict(case.to_dict()) == case``.
        """
        out: dict = {"title": self.title}
        if self.description:
            out["description"] = self.description
        for f in FIELDS:
            if f.section == "" or (f.section == "lubricant" and not self.lubricant_given):
                continue
            if f.path[:2] == ("lubricant", "traction") and not self.traction_given:
                continue
            section_obj = getattr(self, f.section)
            value = section_obj
            for part in f.path[1:]:
                value = getattr(value, part)
            if f.key in self.histories:
                value = self.histories[f.key].spec
            if value is None or f.key in self.estimated or f.key in self.from_oil:
                continue
            target = out
            for part in f.path[:-1]:
                target = target.setdefault(part, {})
            target[f.name] = copy.deepcopy(value)
        if self.materials:
            ordered = {}
            for key, value in out.items():
                ordered[key] = value
                if key == "bearing":
                    ordered["materials"] = copy.deepcopy(self.materials)
            out = ordered
        if self.bearing_set is not None:
            out["set"] = self.bearing_set.to_dict()
        return out

    @classmethod
    def from_dict(cls, data: dict, base_dir=None) -> Case:
        """Validated case from a nested dict (as :func:`tomllib.loads` returns); CaseError.
        ``base_dir``: the case file's folder, where history files are read from. A ``set`` table
        (a bearing set, :mod:`solver.case.bearing_set`) is read after the rest."""
        if isinstance(data, dict) and "set" in data:
            rest = {key: value for key, value in data.items() if key != "set"}
            case = case_from_values(validate(rest, base_dir, bearing_set=True), base_dir or "")
            if case.histories:
                keys = ", ".join(sorted(case.histories))
                raise CaseError(
                    Problem(
                        next(iter(sorted(case.histories))),
                        f"{keys}: a bearing set is solved at one operating point (the quasi-static "
                        "set model); time histories are not modelled for sets. Give numbers, or "
                        "simulate one bearing of the set with its history",
                    )
                )
            bearing_set = read_set(data["set"], rest, _set_bearing_case)
            return dataclasses.replace(case, bearing_set=bearing_set)
        return case_from_values(validate(data, base_dir), base_dir or "")

    def to_toml(self, inline_files: bool = False) -> str:
        """Readable case-file text; loading it gives an equal case. ``inline_files``: a history
        read from a file is written as its inline table of points instead (text that needs no
        other file, as a result keeps it)."""
        text = case_to_toml(self, inline_files)
        if self.bearing_set is not None:
            text = text.rstrip("\n") + "\n\n" + self.bearing_set.to_toml()
        return text

    def with_values(self, values: dict) -> Case:
        """Validated copy with some keys changed: ``{"operating.axial_load_N": 300.0, ...}``.

        Keys are dotted case keys (``lubricant.traction.mu_max``,
        ``materials.my_steel.poisson_ratio``);
        a value of None removes the key (e.g. to switch from a free contact angle to a clearance).
        Estimated cage values are re-estimated from the new bearing unless given. Raises CaseError.
        """
        data = self.to_dict()
        for key, value in values.items():
            parts = str(key).split(".")
            target = data
            for part in parts[:-1]:
                nxt = target.get(part)
                if not isinstance(nxt, dict):
                    if value is None:
                        break
                    nxt = {}
                    target[part] = nxt
                target = nxt
            else:
                if value is None:
                    target.pop(parts[-1], None)
                else:
                    target[parts[-1]] = value
        return Case.from_dict(data, self.source_dir or None)


def _set_bearing_case(data: dict) -> Case:
    """The validated single-bearing case of one bearing of a set (its loads are the set's)."""
    return case_from_values(validate(data, bearing_set=True))


MATERIAL_KEYS = tuple(f.key for f in MATERIAL_FIELDS)
