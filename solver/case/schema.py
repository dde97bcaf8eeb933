"""The case-file schema: one table entry per key (docs/case-format.md is the prose version).

Everything that knows about case keys reads this table: the validator (types, bounds, defaults,
messages), the writer (order, units, comments), the section dataclasses (attribute names) and the
browser app (form fields, element ids ``field-<last segment>``, help texts). Adding a key is one new
:class:`Field` in :data:`FIELDS`.

Units are those written in the key names (mm, deg, rpm, N, g, ...); they become SI in one place,
:func:`solver.inputs.to_inputs`. Every numeric key has bounds: besides physics, they keep every
value within what the solvers can compute without overflow.
"""

from __future__ import annotations

import enum
import math
from collections.abc import Callable
from dataclasses import dataclass

from solver.lubricants import oil_names


class Default(enum.Enum):
    """Default markers that are not plain values."""

    REQUIRED = "required"  # the key must be given
    OPTIONAL = "optional"  # may be absent; the attribute is then None


REQUIRED = Default.REQUIRED
OPTIONAL = Default.OPTIONAL


@dataclass(frozen=True)
class Estimated:
    """A default computed from the validated ``[bearing]`` section.

    ``description`` is the plain-language rule (shown in docs, the app and ``to_toml`` comments);
    ``function(bearing) -> value`` receives the validated :class:`solver.case.model.Bearing`
    (case units) and returns the value in the key's unit.
    """

    description: str
    function: Callable
    #: what ``function`` receives: ``"bearing"`` (the validated bearing) or ``"history"`` (a
    #: namespace with ``top_relative_speed_rpm``, the highest |inner - outer| ring speed along the
    #: case's time histories; a key estimated from the history has no value in a steady case)
    reads: str = "bearing"


@dataclass(frozen=True)
class Field:
    """One case key.

    ``key`` is dotted (``operating.axial_load_N``; ``lubricant.traction.mu_zero`` for a key of an
    inline table). ``type`` is one of float, int, str, choice, bool, material. ``default`` is a
    value, :data:`REQUIRED`, :data:`OPTIONAL` or an :class:`Estimated`. Bounds: ``minimum`` and
    ``maximum`` with
    ``*_inclusive`` flags (None = unbounded). ``reason`` explains the lower bound (or the rule) in
    messages; ``reason_high`` the upper bound (defaults to ``reason``).
    """

    key: str
    type: str
    label: str
    help: str
    unit: str = ""
    default: object = REQUIRED
    minimum: float | None = None
    minimum_inclusive: bool = True
    maximum: float | None = None
    maximum_inclusive: bool = True
    choices: tuple[str, ...] = ()
    reason: str = ""
    reason_high: str = ""
    #: False for a key that no model reads (only the metrics of a result do): it does not enter a
    #: result's fingerprint (solver.results.provenance), so changing it keeps a result current.
    solved: bool = True
    #: True for an operating key that may be a time history instead of a number
    #: (solver.case.history; docs/case-format.md, "Time histories").
    history: bool = False
    #: ``"steady"``: read only by a case without time histories; ``"history"``: only by a case with
    #: one; "": by every case. A key given where it is not read is an error.
    applies: str = ""

    @property
    def path(self) -> tuple[str, ...]:
        """The key split at dots: ('operating', 'axial_load_N')."""
        return tuple(self.key.split("."))

    @property
    def section(self) -> str:
        """Top-level section name ('' for top-level keys such as ``title``)."""
        return self.path[0] if len(self.path) > 1 else ""

    @property
    def name(self) -> str:
        """Last segment of the key (attribute name, and the app's element id suffix)."""
        return self.path[-1]

    @property
    def required(self) -> bool:
        return self.default is REQUIRED

    @property
    def estimated(self) -> bool:
        return isinstance(self.default, Estimated)

    def allowed_text(self) -> str:
        """What is allowed, in words (for help and messages)."""
        if self.type == "choice":
            return "one of " + ", ".join(f'"{c}"' for c in self.choices)
        if self.type == "material":
            return "a material name or an inline table of material properties"
        if self.type == "str":
            return "a text string"
        if self.type == "bool":
            return "true or false"
        kind = "an integer" if self.type == "int" else "a number"
        parts = []
        if self.minimum is not None:
            parts.append(_bound_text(self.minimum, self.minimum_inclusive, low=True))
        if self.maximum is not None:
            parts.append(_bound_text(self.maximum, self.maximum_inclusive, low=False))
        unit = f" in {self.unit}" if self.unit else ""
        return kind + unit + (", " + " and ".join(parts) if parts else "")


def _bound_text(value: float, inclusive: bool, low: bool) -> str:
    v = format_number(value)
    if low:
        return f"at least {v}" if inclusive else f"greater than {v}"
    return f"at most {v}" if inclusive else f"less than {v}"


def format_number(value) -> str:
    """Short, exact-enough text for a number in messages (0.5, 60, 1e-05, nan)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        if value.bit_length() > 64:  # str() refuses integers of thousands of digits
            digits = int(value.bit_length() * math.log10(2)) + 1
            return f"{'-' if value < 0 else ''}(an integer of about {digits} digits)"
        return str(value)
    if isinstance(value, float):
        if math.isfinite(value) and value == int(value) and abs(value) < 1e15:
            return str(int(value))
        return repr(value)
    return repr(value)


# ---- estimates for [cage] (case units: mm and g) ------------------------------------------------
#: Density assumed for an estimated cage mass: a glass-fibre polyamide / phenolic cage, kg/m^3.
CAGE_DENSITY_ESTIMATE = 1400.0


def _cage_mass_g(bearing) -> float:
    """Ring of width D and radial thickness 0.3 D on the pitch circle, density 1400 kg/m^3, in g."""
    d = bearing.ball_diameter_mm * 1e-3
    dm = bearing.pitch_diameter_mm * 1e-3
    return CAGE_DENSITY_ESTIMATE * math.pi * dm * d * 0.3 * d * 1e3


# ---- lubrication method (docs/lubrication.md) --------------------------------------------------
#: The lubrication methods of lubricant.method; oil_mist is read as oil_air (the same law).
LUBRICATION_METHODS = ("oil_air", "oil_mist", "oil_jet", "oil_bath", "grease")
#: The method assumed when a case names none: oil jet with a fixed oil fraction of the mixture
#: and a flooded cage land, the model of cases written before the method was an input.
ASSUMED_METHOD = "oil_jet"
ASSUMED_OIL_VOLUME_FRACTION = 0.01
#: Oil volume fraction of the mixture in a grease-lubricated bearing [E]: after running in, the
#: grease lies beside the balls' path and the balls and cage move through air that carries bled
#: base oil; a tenth of the 1 % assumed for jet lubrication (docs/lubrication.md).
GREASE_OIL_VOLUME_FRACTION = 0.001
#: Flooded fraction of the cage's guiding land with oil-air, oil mist or grease [E]: a starved
#: film (docs/lubrication.md); jets and baths flood the land (1).
STARVED_LAND_FLOODING = 0.3
FLOODED_LAND_FLOODING = 1.0
#: The keys each method reads (lubricant.*), and those it needs unless oil_volume_fraction is given.
METHOD_KEYS = {
    "oil_air": ("oil_flow_mm3_h",),
    "oil_mist": ("oil_flow_mm3_h",),
    "oil_jet": ("jet_flow_l_min", "jet_temperature_C"),
    "oil_bath": ("oil_level_mm",),
    "grease": (),
}
METHOD_NEEDS = {
    "oil_air": "oil_flow_mm3_h",
    "oil_mist": "oil_flow_mm3_h",
    "oil_jet": "jet_flow_l_min",
    "oil_bath": "oil_level_mm",
}


_PROVENANCES = ("estimated", "manufacturer", "literature", "measured")

# What the inner and outer versions of a key share: bounds and the reasons for them.
_GROOVE_RATIO_BOUNDS = dict(
    minimum=0.501,
    maximum=1.0,
    maximum_inclusive=False,
    reason="a groove tighter than the ball cannot hold it, and a closer fit than 0.501 is "
    "no longer a Hertz point contact; grooves are made from about 0.505",
    reason_high="a groove radius larger than the ball diameter is not a ball groove",
)
_LAND_DIAMETER = dict(
    unit="mm",
    default=OPTIONAL,
    minimum=0.1,
    maximum=21000.0,
    reason="a land lies beyond the bore, at least a tenth of a millimetre across",
    reason_high="a land lies next to the pitch circle, which is at most 20 m across",
)
#: Default RMS roughness Rq of a ball, um [E]: a grade G16-G20 ball (Ra about 0.02 um by the ball
#: grade tables, docs/sources.md) with Rq about 1.25 Ra (a Gaussian profile).
BALL_ROUGHNESS_UM = 0.025
#: Default RMS roughness Rq of a raceway, um [E]: superfinished raceways lie at about 0.05-0.1 um.
RACEWAY_ROUGHNESS_UM = 0.08
_ROUGHNESS_BOUNDS = dict(
    minimum=0.001,
    maximum=10.0,
    reason="a surface is never smoother than about a nanometre RMS, and a polished ball has "
    "about 0.01 um; give the roughness in micrometres",
    reason_high="a rolling surface rougher than 10 um RMS is a turned, not a ground, surface; "
    "give the roughness in micrometres",
    solved=False,
)
_SPEED_BOUNDS = dict(
    minimum=-500000.0,
    maximum=500000.0,
    reason="500 000 rpm either way is beyond any ball bearing, even the air-driven dental "
    "turbines that reach about 400 000 rpm, and keeps the solvers' time scales finite",
)

#: Output samples per shaft revolution: the default of simulation.samples_per_revolution and the
#: rate a history case's estimated sampling gives at its top speed; and the fewest samples per
#: second that estimate gives (a history at
#: rest or at a crawl still draws its loads' changes).
DEFAULT_SAMPLES_PER_REVOLUTION = 180
MIN_HISTORY_SAMPLES_PER_SECOND = 1000.0


def history_samples_per_second(top_relative_speed_rpm: float) -> float:
    """Estimated samples per second of a history case: :data:`DEFAULT_SAMPLES_PER_REVOLUTION` per
    revolution at ``top_relative_speed_rpm``, at least :data:`MIN_HISTORY_SAMPLES_PER_SECOND`,
    rounded up to a whole number."""
    per_second = DEFAULT_SAMPLES_PER_REVOLUTION * abs(top_relative_speed_rpm) / 60.0
    return float(math.ceil(max(per_second, MIN_HISTORY_SAMPLES_PER_SECOND)))


#: Every case key, in the order of case-format.md (sections, then keys).
FIELDS: list[Field] = [
    Field("title", "str", "Title", "A short title for this case.", default=""),
    Field(
        "description",
        "str",
        "Description",
        "What is known about this case, in a few sentences of facts with numbers (what it "
        "checks, how its results compare with published data). The models do not read it; "
        "results keep it (the description attribute) and the report shows it under the title.",
        default="",
    ),
    # ---- [bearing] ----------------------------------------------------------------------------
    Field(
        "bearing.designation",
        "str",
        "Designation",
        "Free text naming the bearing (e.g. 7008C-class hybrid). A bearing number in it (6209, "
        "7218 B, or 209 with the words deep groove / angular contact) tells the friction-torque "
        "estimates the bearing type, series and bore (docs/results-schema.md).",
        default="",
    ),
    Field(
        "bearing.provenance",
        "choice",
        "Provenance",
        "Where the geometry comes from.",
        default="estimated",
        choices=_PROVENANCES,
    ),
    Field(
        "bearing.ball_count",
        "int",
        "Number of balls",
        "Number of balls Z.",
        minimum=3,
        maximum=200,
        reason="a ring needs at least three balls to be centred",
        reason_high="far beyond any ball bearing",
    ),
    Field(
        "bearing.ball_diameter_mm",
        "float",
        "Ball diameter",
        "Ball diameter D.",
        unit="mm",
        minimum=0.1,
        maximum=500.0,
        reason="no ball bearing has smaller balls; smaller values only underflow the contact "
        "mechanics",
        reason_high="half a metre is beyond the balls of any ball bearing",
    ),
    Field(
        "bearing.pitch_diameter_mm",
        "float",
        "Pitch diameter",
        "Diameter d_m of the circle through the ball centres.",
        unit="mm",
        minimum=0.5,
        maximum=20000.0,
        reason="no ball bearing has a smaller pitch circle",
        reason_high="20 m is beyond the largest slewing ball bearings",
    ),
    Field(
        "bearing.inner_groove_radius_ratio",
        "float",
        "Inner groove radius ratio",
        "Inner groove radius over ball diameter, f_i = r_i / D (typically 0.51-0.57).",
        **_GROOVE_RATIO_BOUNDS,
    ),
    Field(
        "bearing.outer_groove_radius_ratio",
        "float",
        "Outer groove radius ratio",
        "Outer groove radius over ball diameter, f_o = r_o / D (typically 0.51-0.57).",
        **_GROOVE_RATIO_BOUNDS,
    ),
    Field(
        "bearing.free_contact_angle_deg",
        "float",
        "Free contact angle",
        "Unloaded contact angle alpha_0 (give this or the diametral clearance).",
        unit="deg",
        default=OPTIONAL,
        minimum=0.0,
        maximum=60.0,
        maximum_inclusive=False,
        reason="a contact angle is measured from the radial plane and cannot be negative",
        reason_high="beyond 60 degrees the ball rides over the shoulder; "
        "no ball bearing is built that way",
    ),
    Field(
        "bearing.diametral_clearance_mm",
        "float",
        "Diametral clearance",
        "Unmounted diametral clearance P_d (give this or the free contact angle).",
        unit="mm",
        default=OPTIONAL,
        minimum=0.0,
        maximum=100.0,
        reason="a negative clearance is a preload; give an axial load instead",
        reason_high="the clearance must also stay below A_0, the distance between the groove "
        "curvature centres, which is far below 100 mm in any ball bearing",
    ),
    Field(
        "bearing.inner_shoulder_diameter_mm",
        "float",
        "Inner shoulder diameter",
        "Optional inner-ring land diameter, for the contact-ellipse truncation check.",
        **_LAND_DIAMETER,
    ),
    Field(
        "bearing.outer_shoulder_diameter_mm",
        "float",
        "Outer shoulder diameter",
        "Optional outer-ring land diameter, for the contact-ellipse truncation check.",
        **_LAND_DIAMETER,
    ),
    Field(
        "bearing.ball_material",
        "material",
        "Ball material",
        "bearing_steel, silicon_nitride, a name defined under [materials], or an inline table.",
    ),
    Field(
        "bearing.ring_material",
        "material",
        "Ring material",
        "bearing_steel, silicon_nitride, a name defined under [materials], or an inline table.",
    ),
    Field(
        "bearing.ball_roughness_um",
        "float",
        "Ball roughness",
        "RMS surface roughness Rq of the balls; with the raceway roughness it gives the film "
        "parameter lambda = h_min / sqrt(Rq_ball^2 + Rq_raceway^2) of the results (no model "
        "reads it). The default is an estimate for a grade G16-G20 ball (Ra about 0.02 um, "
        "Rq about 1.25 Ra; docs/sources.md).",
        unit="um",
        default=BALL_ROUGHNESS_UM,
        **_ROUGHNESS_BOUNDS,
    ),
    Field(
        "bearing.raceway_roughness_um",
        "float",
        "Raceway roughness",
        "RMS surface roughness Rq of both raceways (lambda as for the ball roughness). The "
        "default is an estimate for superfinished raceways (Rq 0.05-0.1 um; docs/sources.md).",
        unit="um",
        default=RACEWAY_ROUGHNESS_UM,
        **_ROUGHNESS_BOUNDS,
    ),
    # ---- [cage] (optional section) ------------------------------------------------------------
    Field(
        "cage.guidance",
        "choice",
        "Cage guidance",
        "Which surface pilots the cage.",
        default="outer_ring",
        choices=("outer_ring", "inner_ring", "ball"),
    ),
    Field(
        "cage.pocket_diametral_clearance_mm",
        "float",
        "Pocket clearance",
        "Diametral clearance between a ball and its cage pocket.",
        unit="mm",
        default=Estimated("0.028 D", lambda b: 0.028 * b.ball_diameter_mm),
        minimum=0.001,
        maximum=100.0,
        reason="a ball must fit in its pocket with some play: at least a micrometre; the "
        "estimate for the smallest ball accepted is 2.8 um",
        reason_high="a pocket 100 mm wider than its ball no longer guides it",
    ),
    Field(
        "cage.guide_diametral_clearance_mm",
        "float",
        "Guide clearance",
        "Diametral clearance between the cage and its guiding land.",
        unit="mm",
        default=Estimated("0.0055 d_m", lambda b: 0.0055 * b.pitch_diameter_mm),
        minimum=0.001,
        maximum=500.0,
        reason="the cage must fit on its land with some play: at least a micrometre; the "
        "estimate for the smallest pitch circle accepted is 2.75 um",
        reason_high="a cage half a metre loose on its land is not guided by it",
    ),
    Field(
        "cage.mass_g",
        "float",
        "Cage mass",
        "Mass of the cage.",
        unit="g",
        default=Estimated(
            "polymer ring (1400 kg/m^3) of width D and radial thickness 0.3 D "
            "on the pitch circle: 1400 pi d_m 0.3 D^2",
            _cage_mass_g,
        ),
        minimum=1.0e-9,
        maximum=1.0e6,
        reason="a cage has mass: at least a nanogram, below the estimate for the smallest "
        "bearing accepted, about 7 ng",
        reason_high="a tonne is beyond the cage of any ball bearing",
    ),
    Field(
        "cage.pocket_friction",
        "float",
        "Pocket friction",
        "Friction coefficient between a ball and its cage pocket.",
        default=0.08,
        minimum=0.0,
        maximum=1.0,
        reason="a friction coefficient is not negative",
        reason_high="a lubricated ball-pocket friction coefficient stays well below 1",
    ),
    Field(
        "cage.guide_land_width_mm",
        "float",
        "Guide land width",
        "Axial width of the cage-guiding land.",
        unit="mm",
        default=Estimated("0.5 D", lambda b: 0.5 * b.ball_diameter_mm),
        minimum=0.01,
        maximum=1000.0,
        reason="a land guides the cage over some width: at least 10 um; the estimate for the "
        "smallest ball accepted is 50 um",
        reason_high="a guiding land a metre wide is beyond any ball bearing",
    ),
    Field(
        "cage.land_flooding",
        "float",
        "Land flooding",
        "Fraction of the guiding land's width that runs in oil (1 = fully flooded, 0 = dry); "
        "the land's hydrodynamic force and friction scale with it. Absent: it follows "
        "lubricant.method (docs/lubrication.md): 1 for oil_jet and oil_bath, "
        f"{STARVED_LAND_FLOODING:g} (a starved land, an estimate) for oil_air, oil_mist and "
        "grease; a value given overrides it.",
        default=OPTIONAL,
        minimum=0.0,
        maximum=1.0,
        reason="a flooded fraction lies between 0 and 1",
    ),
    # ---- [lubricant] (optional section) -------------------------------------------------------
    Field(
        "lubricant.oil",
        "choice",
        "Named oil",
        "A named oil of solver/data/oils.toml (docs/case-format.md, 'Named oils'): its values, "
        "each with its source, fill the [lubricant] keys the case does not give; keys the case "
        "gives override them. Absent: every key not given takes the schema default.",
        default=OPTIONAL,
        choices=oil_names(),
        reason="the oil is one of the named oils",
    ),
    Field(
        "lubricant.viscosity_Pas",
        "float",
        "Viscosity",
        "Dynamic viscosity of the oil at the reference temperature (reference_temperature_C).",
        unit="Pa s",
        default=0.01,
        minimum=0.0,
        minimum_inclusive=False,
        maximum=100.0,
        reason="a fluid has a positive viscosity",
        reason_high="lubricating oils at operating temperature stay far below 100 Pa s",
    ),
    Field(
        "lubricant.pressure_viscosity_per_GPa",
        "float",
        "Pressure-viscosity coefficient",
        "Barus pressure-viscosity coefficient alpha at the reference temperature.",
        unit="1/GPa",
        default=20.0,
        minimum=0.0,
        minimum_inclusive=False,
        maximum=100.0,
        reason="oil viscosity rises with pressure; the coefficient is positive",
        reason_high="lubricants lie between about 5 and 50 /GPa",
    ),
    Field(
        "lubricant.pressure_viscosity_temperature_per_K",
        "float",
        "Pressure-viscosity temperature coefficient",
        "c_alpha of alpha(T) = alpha exp(-c_alpha (T - T_ref)): the fraction by which the "
        "pressure-viscosity coefficient falls per kelvin. The default is that of two spindle "
        "oils (Stachowiak & Batchelor, Table 2.3: 0.74 and 0.79 %/K between 30 and 60 degC).",
        unit="1/K",
        default=0.0077,
        minimum=0.0,
        maximum=0.05,
        reason="the pressure-viscosity coefficient falls, or stays, as temperature rises",
        reason_high="published oils lie below about 0.01 /K",
    ),
    Field(
        "lubricant.traction_model",
        "choice",
        "Traction model",
        "How the ball-race traction is computed at each point of the contact ellipse: "
        '"rheology" (shear stress of the oil film from viscosity at the local pressure, film '
        "thickness and slip: Eyring, elastic and limiting-shear-stress laws, docs/case-format.md) "
        'or "slip_curve" (the fixed traction-coefficient curve of the traction table, which '
        "only this model reads: a measured curve, or for comparison).",
        default="rheology",
        choices=("rheology", "slip_curve"),
        reason="the traction model is one of the listed names",
    ),
    Field(
        "lubricant.reference_temperature_C",
        "float",
        "Viscosity reference temperature",
        "Temperature at which the oil's viscosity, pressure-viscosity coefficient, Eyring "
        "stress, limiting shear stress and film shear modulus are given; each is taken to the "
        "inlet temperature by its temperature law (docs/traction.md).",
        unit="degC",
        default=40.0,
        minimum=-60.0,
        maximum=300.0,
        reason="oils are characterised between about -60 and 300 degC",
    ),
    Field(
        "lubricant.inlet_temperature_C",
        "float",
        "Inlet temperature",
        "Oil temperature at the contact inlets; the viscosity and the other rheology values "
        "there follow from their values at the reference temperature and their temperature "
        "coefficients.",
        unit="degC",
        default=40.0,
        minimum=-60.0,
        maximum=300.0,
        reason="bearing oils run between about -60 and 300 degC",
    ),
    Field(
        "lubricant.temperature_viscosity_per_K",
        "float",
        "Temperature-viscosity coefficient",
        "beta of eta(T) = eta_ref exp(-beta (T - T_ref)); also sets the inlet shear heating.",
        unit="1/K",
        default=0.03,
        minimum=0.0,
        maximum=0.2,
        reason="oil viscosity falls, or stays, as temperature rises",
        reason_high="lubricating oils lie between about 0.01 and 0.07 /K",
    ),
    Field(
        "lubricant.eyring_stress_MPa",
        "float",
        "Eyring stress",
        "Eyring stress tau_0 of the non-Newtonian film: the stress above which shear thins.",
        unit="MPa",
        default=5.0,
        minimum=0.0,
        minimum_inclusive=False,
        maximum=100.0,
        reason="the Eyring stress is positive",
        reason_high="measured Eyring stresses lie between about 1 and 20 MPa",
    ),
    Field(
        "lubricant.limiting_shear_stress_MPa",
        "float",
        "Limiting shear stress at zero pressure",
        "tau_L0 of the limiting shear stress tau_L = tau_L0 + Lambda p.",
        unit="MPa",
        default=2.0,
        minimum=0.0,
        maximum=500.0,
        reason="a limiting shear stress is not negative",
        reason_high="limiting shear stresses stay below a few hundred MPa",
    ),
    Field(
        "lubricant.limiting_shear_coefficient",
        "float",
        "Limiting-shear-stress coefficient",
        "Lambda of the limiting shear stress tau_L = tau_L0 + Lambda p (pressure p).",
        default=0.075,
        minimum=0.0,
        minimum_inclusive=False,
        maximum=0.5,
        reason="the limiting shear stress grows with pressure",
        reason_high="measured values lie between about 0.03 and 0.15",
    ),
    Field(
        "lubricant.limiting_shear_temperature_per_K",
        "float",
        "Limiting-shear-stress temperature coefficient",
        "c_L of tau_L(T) = (tau_L0 + Lambda p) exp(-c_L (T - T_ref)): the fraction by which the "
        "limiting shear stress falls per kelvin, at the inlet and in the film heated by sliding "
        "(thermal softening). The default is an estimate: 0.52 %/K of the Santotrac 50 "
        "correlation in docs/sources.md.",
        unit="1/K",
        default=0.005,
        minimum=0.0,
        maximum=0.05,
        reason="the limiting shear stress falls, or stays, as temperature rises",
        reason_high="a limiting shear stress halving in less than 14 K is beyond measured oils",
    ),
    Field(
        "lubricant.film_shear_modulus_GPa",
        "float",
        "Film shear modulus",
        "Elastic shear modulus G of the film in the contact; it sets the linear part of the "
        "traction curve at small slip.",
        unit="GPa",
        default=0.5,
        minimum=0.0,
        minimum_inclusive=False,
        maximum=100.0,
        reason="the film's shear modulus is positive",
        reason_high="EHL films have shear moduli of about 0.1 to 3 GPa",
    ),
    Field(
        "lubricant.film_shear_modulus_temperature_per_K",
        "float",
        "Film shear modulus temperature coefficient",
        "c_G of G(T) = G exp(-c_G (T - T_ref)): the fraction by which the film's shear modulus "
        "falls per kelvin. The default is an estimate (no measured value found): that of the "
        "central film, 0.67 beta + 0.53 c_alpha of the default oil, so that the elastic slope "
        "G b / h_c of the traction curve at small slip does not rise as the film thins "
        "(docs/traction.md).",
        unit="1/K",
        default=0.024,
        minimum=0.0,
        maximum=0.05,
        reason="the film's shear modulus falls, or stays, as temperature rises",
        reason_high="a shear modulus halving in less than 14 K is beyond measured oils",
    ),
    Field(
        "lubricant.thermal_softening",
        "bool",
        "Thermal softening",
        "Shear heating of the film lowers the traction at large slip (rheology model only): the "
        "mid-film temperature rise tau u h / (8 k) softens the stress with the limiting shear "
        "stress's temperature coefficient, so the traction curve has a maximum "
        "(docs/traction.md). false: the isothermal film.",
        default=True,
    ),
    Field(
        "lubricant.thermal_conductivity_W_mK",
        "float",
        "Thermal conductivity",
        "Thermal conductivity of the oil (inlet shear heating and thermal softening of the film).",
        unit="W/m/K",
        default=0.13,
        minimum=0.0,
        minimum_inclusive=False,
        maximum=10.0,
        reason="a fluid conducts heat",
        reason_high="oils conduct about 0.1 to 0.2 W/m/K",
    ),
    Field(
        "lubricant.method",
        "choice",
        "Lubrication method",
        "How oil reaches the bearing; the drag of the oil-air mixture on the balls and the cage, "
        "the cage land's flooding and the SKF friction estimate follow it (docs/lubrication.md). "
        "oil_air and oil_mist: a small oil flow carried by air (oil_flow_mm3_h); oil_jet: "
        "jets through the bearing (jet_flow_l_min, jet_temperature_C); oil_bath: the lowest "
        "balls dip into a bath (oil_level_mm); grease. Absent: "
        f'"{ASSUMED_METHOD}" is assumed with a mixture of {ASSUMED_OIL_VOLUME_FRACTION:g} oil by '
        "volume and a flooded cage land, and the case warns.",
        default=OPTIONAL,
        choices=LUBRICATION_METHODS,
        reason="the lubrication method is one of the listed names",
    ),
    Field(
        "lubricant.oil_flow_mm3_h",
        "float",
        "Oil flow (oil-air, oil mist)",
        "Oil supplied to this bearing by oil-air or oil-mist lubrication (method oil_air or "
        "oil_mist only).",
        unit="mm3/h",
        default=OPTIONAL,
        minimum=0.0,
        maximum=1.0e8,
        reason="a flow of oil into the bearing is not negative; 0 is air only",
        reason_high="100 litres an hour is a jet, not oil-air: use method oil_jet",
    ),
    Field(
        "lubricant.jet_flow_l_min",
        "float",
        "Jet oil flow",
        "Oil flow of the jets into this bearing (method oil_jet only).",
        unit="L/min",
        default=OPTIONAL,
        minimum=0.0,
        maximum=1000.0,
        reason="a flow of oil into the bearing is not negative; 0 is air only",
        reason_high="a cubic metre a minute is beyond the jets of any ball bearing",
    ),
    Field(
        "lubricant.jet_temperature_C",
        "float",
        "Jet oil temperature",
        "Temperature of the jets' oil (method oil_jet only): the oil in the mixture around the "
        "balls and cage and on the cage land has its viscosity there. Absent: the inlet "
        "temperature.",
        unit="degC",
        default=OPTIONAL,
        minimum=-60.0,
        maximum=300.0,
        reason="bearing oils run between about -60 and 300 degC",
    ),
    Field(
        "lubricant.oil_level_mm",
        "float",
        "Oil bath level",
        "Height of the bath's surface above the lowest point of the outer raceway, horizontal "
        "shaft (method oil_bath only); e.g. half a ball diameter: the centre of the lowest ball.",
        unit="mm",
        default=OPTIONAL,
        minimum=0.0,
        maximum=21000.0,
        reason="the level is measured up from the lowest point of the outer raceway",
        reason_high="a level above a 21 m bearing submerges any ball bearing",
    ),
    Field(
        "lubricant.density_kg_m3",
        "float",
        "Oil density",
        "Density of the oil (ball and cage drag in the oil-air mixture).",
        unit="kg/m3",
        default=870.0,
        minimum=0.0,
        minimum_inclusive=False,
        maximum=3000.0,
        reason="a fluid has a positive density",
        reason_high="lubricating oils have densities of about 800 to 2000 kg/m3",
    ),
    Field(
        "lubricant.oil_volume_fraction",
        "float",
        "Oil volume fraction",
        "Volume fraction of oil in the oil-air mixture around the balls and cage (drag). Absent: "
        "it follows lubricant.method and its supply (docs/lubrication.md); a value given "
        "overrides it.",
        default=OPTIONAL,
        minimum=0.0,
        maximum=1.0,
        reason="a volume fraction lies between 0 and 1",
    ),
    Field(
        "lubricant.traction.mu_zero",
        "float",
        "Traction at zero slip",
        "Traction coefficient at zero slip (slip_curve model only).",
        default=0.0,
        minimum=0.0,
        maximum=1.0,
        reason="a traction coefficient is not negative",
        reason_high="lubricated traction stays well below 1",
    ),
    Field(
        "lubricant.traction.mu_max",
        "float",
        "Peak traction",
        "Peak traction coefficient (slip_curve model only).",
        default=0.05,
        minimum=0.0,
        minimum_inclusive=False,
        maximum=1.0,
        reason="the traction curve needs a positive peak",
        reason_high="lubricated traction stays well below 1",
    ),
    Field(
        "lubricant.traction.slip_at_max_m_s",
        "float",
        "Slip at peak traction",
        "Slip speed at which the traction peaks (slip_curve model only).",
        unit="m/s",
        default=1.0,
        minimum=0.0,
        minimum_inclusive=False,
        maximum=100.0,
        reason="the peak lies at a positive slip speed",
        reason_high="traction peaks at slips of a few m/s at most",
    ),
    Field(
        "lubricant.traction.mu_infinity",
        "float",
        "Traction at high slip",
        "Traction coefficient approached at large slip (slip_curve model only).",
        default=0.036,
        minimum=0.0,
        minimum_inclusive=False,
        maximum=1.0,
        reason="traction at large slip is positive",
        reason_high="lubricated traction stays well below 1; it must also be at most mu_max",
    ),
    # ---- [operating] --------------------------------------------------------------------------
    Field(
        "operating.inner_ring_speed_rpm",
        "float",
        "Inner ring speed",
        "Inner ring (shaft) speed, positive about +x."
        " A number, or a time history (docs/case-format.md).",
        unit="rpm",
        **_SPEED_BOUNDS,
        history=True,
    ),
    Field(
        "operating.outer_ring_speed_rpm",
        "float",
        "Outer ring speed",
        "Outer ring speed, positive about +x. A number, or a time history (docs/case-format.md).",
        unit="rpm",
        default=0.0,
        **_SPEED_BOUNDS,
        history=True,
    ),
    Field(
        "operating.axial_load_N",
        "float",
        "Axial load",
        "Thrust on the inner ring along +x. A number, or a time history (docs/case-format.md).",
        unit="N",
        default=0.0,
        minimum=0.0,
        maximum=1.0e9,
        reason="a single angular contact bearing carries thrust only in +x; "
        "a negative load would lift the inner ring off the balls",
        reason_high="1 GN is beyond the capacity of any ball bearing",
        history=True,
    ),
    Field(
        "operating.radial_load_N",
        "float",
        "Radial load",
        "Magnitude of the radial load on the inner ring."
        " A number, or a time history (docs/case-format.md).",
        unit="N",
        default=0.0,
        minimum=0.0,
        maximum=1.0e9,
        reason="give the direction with radial_load_angle_deg, not a negative magnitude",
        reason_high="1 GN is beyond the capacity of any ball bearing",
        history=True,
    ),
    Field(
        "operating.radial_load_angle_deg",
        "float",
        "Radial load direction",
        "Azimuth of the radial load, from +y towards +z."
        " A number, or a time history (docs/case-format.md).",
        unit="deg",
        default=0.0,
        minimum=-360.0,
        maximum=360.0,
        reason="an azimuth is given within one turn either way",
        history=True,
    ),
    Field(
        "operating.misalignment_deg",
        "float",
        "Misalignment",
        "Imposed tilt of the inner ring (give this or a tilting moment)."
        " A number, or a time history (docs/case-format.md).",
        unit="deg",
        default=OPTIONAL,
        minimum=-5.0,
        maximum=5.0,
        reason="the model assumes small tilts, a few tenths of a degree in practice",
        history=True,
    ),
    Field(
        "operating.misalignment_axis_deg",
        "float",
        "Misalignment axis",
        "Azimuth of the tilt axis in the radial plane."
        " A number, or a time history (docs/case-format.md).",
        unit="deg",
        default=90.0,
        minimum=-360.0,
        maximum=360.0,
        reason="an azimuth is given within one turn either way",
        history=True,
    ),
    Field(
        "operating.misalignment_frame",
        "choice",
        "Misalignment frame",
        "space: tilt fixed in space; ring: tilt turns with the inner ring.",
        default="space",
        choices=("space", "ring"),
    ),
    Field(
        "operating.tilting_moment_Nm",
        "float",
        "Tilting moment",
        "Applied moment on the inner ring; the tilt is then solved (0 = moment-free)."
        " A number, or a time history (docs/case-format.md).",
        unit="N m",
        default=OPTIONAL,
        minimum=-1.0e9,
        maximum=1.0e9,
        reason="a moment of 1 GN m either way is beyond the capacity of any ball bearing",
        history=True,
    ),
    Field(
        "operating.moment_axis_deg",
        "float",
        "Moment axis",
        "Azimuth of the tilting-moment axis in the radial plane."
        " A number, or a time history (docs/case-format.md).",
        unit="deg",
        default=90.0,
        minimum=-360.0,
        maximum=360.0,
        reason="an azimuth is given within one turn either way",
        history=True,
    ),
    # ---- [simulation] -------------------------------------------------------------------------
    Field(
        "simulation.shaft_revolutions",
        "float",
        "Shaft revolutions",
        "Length of the dynamic simulation in shaft revolutions.",
        default=10.0,
        minimum=0.0,
        minimum_inclusive=False,
        maximum=1000.0,
        reason="a simulation must run for some time",
        reason_high="longer runs take hours; split them",
        applies="steady",
    ),
    Field(
        "simulation.samples_per_revolution",
        "int",
        "Samples per revolution",
        "Output samples per shaft revolution.",
        default=DEFAULT_SAMPLES_PER_REVOLUTION,
        minimum=8,
        maximum=3600,
        reason="fewer samples cannot draw a trajectory",
        reason_high="more samples only make the result file larger",
        applies="steady",
    ),
    Field(
        "simulation.duration_s",
        "float",
        "Duration",
        "Length of the dynamic simulation of a case with a time history, in seconds (required "
        "then; a steady case gives shaft_revolutions instead). Beyond a history's last point its "
        "value holds.",
        unit="s",
        default=OPTIONAL,
        minimum=0.0,
        minimum_inclusive=False,
        maximum=100.0,
        reason="a simulation must run for some time",
        reason_high="longer runs take hours; split them",
        applies="history",
    ),
    Field(
        "simulation.samples_per_second",
        "float",
        "Samples per second",
        "Output samples per second of a case with a time history.",
        unit="1/s",
        default=Estimated(
            f"{DEFAULT_SAMPLES_PER_REVOLUTION} samples per revolution at the history's highest "
            f"relative ring speed, at least {MIN_HISTORY_SAMPLES_PER_SECOND:g} per second",
            lambda run: history_samples_per_second(run.top_relative_speed_rpm),
            reads="history",
        ),
        minimum=10.0,
        maximum=1.0e7,
        reason="fewer samples cannot draw a trajectory",
        reason_high="more samples only make the result file larger",
        applies="history",
    ),
    # Dynamic-model switches; the defaults are the full model.
    Field(
        "simulation.ball_race_traction",
        "bool",
        "Ball-race traction",
        "EHL traction at the ball-race contacts (false = frictionless contacts, "
        "for checks such as energy conservation).",
        default=True,
    ),
    Field(
        "simulation.contact_damping_ratio",
        "float",
        "Contact damping ratio",
        "Critical-damping ratio of the ball-race normal contacts (0 = undamped).",
        default=0.05,
        minimum=0.0,
        maximum=1.0,
        reason="damping cannot feed energy into a contact",
        reason_high="a contact damped beyond critical no longer behaves like a Hertz contact",
    ),
    Field(
        "simulation.gravity_m_s2",
        "float",
        "Gravity",
        "Gravitational acceleration, acting along -z of the bearing frame (0 = off).",
        unit="m/s^2",
        default=9.81,
        minimum=0.0,
        maximum=1000.0,
        reason="gravity is given as a magnitude along -z",
        reason_high="beyond 100 g the bearing model's assumptions no longer hold",
    ),
    Field(
        "simulation.tolerance",
        "float",
        "Integrator tolerance",
        "Local error tolerance of the adaptive integrator, relative to each state's scale "
        "(the default keeps the friction torque within 2 % and the energy balance within 1 %; "
        "docs/numerics.md).",
        default=1e-4,
        minimum=0.0,
        minimum_inclusive=False,
        maximum=1e-2,
        reason="a tolerance must be positive",
        reason_high="looser tolerances give wrong contact forces and energy drift",
    ),
    Field(
        "simulation.model_cage",
        "bool",
        "Model the cage",
        "Simulate the cage with its pocket and guiding-land contacts (false = "
        "balls are free to bunch).",
        default=True,
    ),
    # Quasi-static model switch: where the ball speeds come from.
    Field(
        "simulation.quasistatic_ball_speeds",
        "choice",
        "Quasi-static ball speeds",
        "race_control: rolling kinematics of the controlling race, decided per ball (Jones); "
        "traction: from the traction balance of each ball with one cage speed "
        "(friction-based quasi-dynamic).",
        default="traction",
        choices=("race_control", "traction"),
    ),
]

#: Keys of a material table (under [materials.NAME], or inline for ball_material/ring_material).
MATERIAL_FIELDS: list[Field] = [
    Field(
        "youngs_modulus_GPa",
        "float",
        "Young's modulus",
        "Young's modulus E.",
        unit="GPa",
        minimum=0.0,
        minimum_inclusive=False,
        maximum=2000.0,
        reason="a solid has a positive stiffness",
        reason_high="diamond, the stiffest solid, has about 1100 GPa",
    ),
    Field(
        "poisson_ratio",
        "float",
        "Poisson's ratio",
        "Poisson's ratio nu.",
        minimum=0.0,
        maximum=0.5,
        maximum_inclusive=False,
        reason="isotropic solids used in bearings have 0 <= nu < 0.5",
        reason_high="0.5 is an incompressible material, not a bearing solid",
    ),
    Field(
        "density_kg_m3",
        "float",
        "Density",
        "Mass density.",
        unit="kg/m3",
        minimum=0.0,
        minimum_inclusive=False,
        maximum=30000.0,
        reason="a solid has positive density",
        reason_high="osmium, the densest element, has about 22 600 kg/m3",
    ),
]

#: Section order (case-format.md). ``materials`` holds user tables, not FIELDS entries.
SECTION_ORDER = ("bearing", "materials", "cage", "lubricant", "operating", "simulation")
#: Sections that may be absent entirely (defaults or None).
OPTIONAL_SECTIONS = ("materials", "cage", "lubricant", "simulation")


def fields_by_key() -> dict[str, Field]:
    """{dotted key: Field} for every entry of :data:`FIELDS`."""
    return {f.key: f for f in FIELDS}


def field(key: str) -> Field:
    """The :class:`Field` for a dotted key (KeyError if unknown)."""
    return fields_by_key()[key]
