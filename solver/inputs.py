"""The models' inputs in SI units, built once from a validated case by :func:`to_inputs`.

This module is the one place where the units of the case keys (mm, rpm, degree, g, GPa, 1/GPa)
become SI (m, rad/s, rad, kg, Pa, 1/Pa); both models read :class:`Inputs` and never a case. Every
value arrives filled in: defaults and estimates come from the case schema
(:data:`solver.case.schema.FIELDS`), not from here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .geometry import BearingGeometry, free_contact_angle_from_clearance
from .history import (
    CH_AXIAL_LOAD,
    CH_INNER_SPEED,
    CH_MISALIGNMENT,
    CH_MISALIGNMENT_AXIS,
    CH_MOMENT_AXIS,
    CH_OUTER_SPEED,
    CH_RADIAL_LOAD,
    CH_RADIAL_LOAD_ANGLE,
    CH_TILTING_MOMENT,
    FRAME_INNER_RING,
    FRAME_SPACE,
    HistoryRecord,
    channel_value,
    history_record,
    operating_values,
)
from .history.integral import channel_integral
from .materials import Material
from .physics import rheology as rh
from .physics.rheology import rheology_at_temperature
from .units import GPA, GRAM, MM, PER_GPA, RPM  # SI value of one case unit


def rpm_to_rad_s(rpm: float) -> float:
    """A speed in rpm as rad/s."""
    return float(rpm) * RPM


def rad_s_to_rpm(omega: float) -> float:
    """A speed in rad/s as rpm (for messages and tables)."""
    return omega * 30.0 / math.pi


@dataclass(frozen=True)
class OperatingPoint:
    """Operating condition in SI units, loads on the inner ring (case-format.md signs).

    ``misalignment`` is the imposed tilt angle [rad] about the axis at azimuth
    ``misalignment_axis``; when ``tilting_moment`` [N m] is not None the tilt is solved instead and
    the moment acts about the axis at azimuth ``moment_axis`` (0 = moment-free tilt).
    """

    inner_ring_speed: float  # rad/s about +x
    outer_ring_speed: float  # rad/s about +x
    axial_load: float  # N, +x presses the inner ring into the balls
    radial_load: float  # N
    radial_load_angle: float  # rad, azimuth psi of the radial load
    misalignment: float  # rad
    misalignment_axis: float  # rad
    misalignment_frame: str  # "space" | "ring"
    tilting_moment: float | None  # N m; None = tilt imposed
    moment_axis: float  # rad

    @property
    def tilt_is_free(self) -> bool:
        return self.tilting_moment is not None

    def applied_loads(self) -> np.ndarray:
        """(Fx, Fy, Fz, My, Mz) [N, N m] applied to the inner ring (moments zero for imposed
        tilt)."""
        moment = self.tilting_moment if self.tilting_moment is not None else 0.0
        return np.array(
            [
                self.axial_load,
                self.radial_load * np.cos(self.radial_load_angle),
                self.radial_load * np.sin(self.radial_load_angle),
                moment * np.cos(self.moment_axis),
                moment * np.sin(self.moment_axis),
            ]
        )

    def imposed_tilt(self) -> np.ndarray:
        """(theta_y, theta_z) [rad] of the imposed misalignment: rotation vector along the tilt
        axis."""
        if self.tilt_is_free:
            return np.zeros(2)
        return self.misalignment * np.array(
            [np.cos(self.misalignment_axis), np.sin(self.misalignment_axis)]
        )


@dataclass(frozen=True)
class CageInputs:
    """The cage, SI units. Clearances are diametral."""

    guidance: str  # "outer_ring" | "inner_ring" | "ball"
    pocket_clearance: float  # m
    guide_clearance: float  # m
    mass: float  # kg
    pocket_friction: float
    guide_land_width: float  # m
    land_flooding: float  # flooded fraction of the guiding land


@dataclass(frozen=True)
class TractionCurve:
    """Properties of the traction curve mu(slip speed) (solver.physics.traction)."""

    mu_zero: float
    mu_max: float
    slip_at_max: float  # m/s
    mu_infinity: float

    def values(self) -> tuple[float, float, float, float]:
        """(mu_zero, mu_max, slip_at_max, mu_infinity), the argument order of
        :func:`solver.physics.traction.traction_curve_parameters`."""
        return (self.mu_zero, self.mu_max, self.slip_at_max, self.mu_infinity)


@dataclass(frozen=True)
class LubricantInputs:
    """The lubricant, SI units. ``given`` is False when the case has no ``[lubricant]`` section
    and these are the schema's default oil. The rheology values (viscosity, pressure-viscosity,
    Eyring stress, limiting shear stress, film shear modulus) are those of the inlet temperature
    (solver.physics.rheology.rheology_at_temperature)."""

    viscosity: float  # Pa s, at the inlet temperature
    pressure_viscosity: float  # 1/Pa
    traction: TractionCurve
    given: bool
    traction_model: str  # "rheology" | "slip_curve"
    inlet_temperature: float  # degC
    temperature_viscosity: float  # beta, 1/K
    eyring_stress: float  # Pa
    limiting_shear_stress: float  # tau_L0, Pa
    limiting_shear_coefficient: float  # Lambda
    film_shear_modulus: float  # Pa
    thermal_conductivity: float  # W/(m K)
    thermal_softening: float  # c [1/K] of the film's shear heating, 0 = isothermal film
    density: float  # kg/m^3
    oil_volume_fraction: float  # of the oil-air mixture around the balls and cage (drag)
    oil: str = ""  # the named oil (lubricant.oil) the values come from, "" for none
    method: str = "oil_jet"  # lubricant.method, or the one assumed (docs/lubrication.md)
    method_assumed: bool = False  # True: the case names no method, ``method`` was assumed
    supply_viscosity: float = 0.0  # Pa s of the oil in the mixture and on the cage land; 0: inlet
    mixture_basis: str = ""  # how oil_volume_fraction and the land flooding follow, in words

    @property
    def mixture_viscosity_of_oil(self) -> float:
        """Viscosity [Pa s] of the oil in the drag mixture and on the cage land: that of the
        supply (jet temperature) when given, else the inlet viscosity."""
        return self.supply_viscosity if self.supply_viscosity > 0.0 else self.viscosity

    def rheology_array(self):
        """Parameter array of solver.physics.rheology (its RH_* slots, SI) of this lubricant."""
        r = np.zeros(rh.RHEOLOGY_SIZE)
        r[rh.RH_VISCOSITY] = self.viscosity
        r[rh.RH_PRESSURE_VISCOSITY] = self.pressure_viscosity
        r[rh.RH_EYRING_STRESS] = self.eyring_stress
        r[rh.RH_LIMITING_STRESS] = self.limiting_shear_stress
        r[rh.RH_LIMITING_SLOPE] = self.limiting_shear_coefficient
        r[rh.RH_SHEAR_MODULUS] = self.film_shear_modulus
        r[rh.RH_TEMPERATURE_VISCOSITY] = self.temperature_viscosity
        r[rh.RH_CONDUCTIVITY] = self.thermal_conductivity
        r[rh.RH_SOFTENING] = self.thermal_softening
        return r

    @property
    def lubrication_text(self) -> str:
        """The lubrication method and what follows from it, in words."""
        named = "assumed (the case names no lubricant.method)" if self.method_assumed else "given"
        return f"lubrication {self.method}, {named}: {self.mixture_basis}"

    @property
    def description(self) -> str:
        """Where the lubricant data come from and how the bearing is lubricated, in words
        (results attribute ``lubricant``)."""
        if self.given:
            if self.oil:
                source = f"from the case [lubricant], named oil {self.oil} (solver/data/oils.toml)"
            else:
                source = "from the case [lubricant]"
        else:
            t = self.traction
            source = (
                "no [lubricant] in the case: the default oil of the case schema was used "
                f"(viscosity {self.viscosity:g} Pa s at the inlet, traction model "
                f"{self.traction_model}, pressure-viscosity {self.pressure_viscosity / PER_GPA:g} "
                f"/GPa, traction mu_zero {t.mu_zero:g}, mu_max {t.mu_max:g} at "
                f"{t.slip_at_max:g} m/s, mu_infinity {t.mu_infinity:g}; docs/case-format.md)"
            )
        return f"{source}; {self.lubrication_text}"


@dataclass(frozen=True)
class SimulationInputs:
    """Length, sampling and physics switches of a dynamic run, and the quasi-static model's
    source of the ball speeds."""

    shaft_revolutions: float | None  # None: a history case (it runs for ``duration``)
    samples_per_revolution: int | None  # None: a history case (``samples_per_second``)
    traction: bool  # EHL traction at the ball-race contacts (False: frictionless)
    damping_ratio: float  # critical-damping ratio of the ball-race normal contacts
    gravity: float  # m/s^2, along -z
    tolerance: float  # local error tolerance of the integrator (relative to the state scales)
    cage: bool  # model the cage (False: balls free to bunch)
    quasistatic_ball_speeds: str = "traction"  # or "race_control" (quasi-static model)
    # a case with time histories (Inputs.history) runs for a duration, sampled per second
    duration: float | None = None  # s; None: a steady case (shaft_revolutions)
    samples_per_second: float | None = None  # 1/s; None: a steady case (samples_per_revolution)


@dataclass(frozen=True)
class Inputs:
    """Everything the models read from a case, SI units. ``case_text`` is for provenance only."""

    geometry: BearingGeometry
    operating: OperatingPoint
    cage: CageInputs
    lubricant: LubricantInputs
    simulation: SimulationInputs
    case_text: str = ""
    designation: str = ""  # bearing.designation as written ("" when not given)
    # the operating inputs as functions of time (solver.history); None: steady (``operating`` holds
    # at every time). ``operating`` is then the history's value at t = 0.
    history: HistoryRecord | None = None


# ---- from a validated case ----------------------------------------------------------------------
def material_from_table(name: str, table: dict) -> Material:
    """SI :class:`Material` from a validated material table (GPa, -, kg/m^3 as written)."""
    return Material(
        name,
        float(table["youngs_modulus_GPa"]) * GPA,
        float(table["poisson_ratio"]),
        float(table["density_kg_m3"]),
    )


def bearing_geometry(case) -> BearingGeometry:
    """Geometry of ``case.bearing`` with the case's resolved materials (mm and degrees → SI)."""
    b = case.bearing
    D = b.ball_diameter_mm * MM
    f_i, f_o = b.inner_groove_radius_ratio, b.outer_groove_radius_ratio
    if b.free_contact_angle_deg is not None:
        alpha0 = math.radians(b.free_contact_angle_deg)
        nominal = math.nan  # an angular contact bearing: rated at its free contact angle
    else:
        alpha0 = free_contact_angle_from_clearance(D, f_i, f_o, b.diametral_clearance_mm * MM)
        nominal = 0.0  # a radial deep-groove bearing: rated at 0 (ISO 281)

    def mm(value):
        return math.nan if value is None else value * MM

    return BearingGeometry(
        ball_count=int(b.ball_count),
        ball_diameter=D,
        pitch_diameter=b.pitch_diameter_mm * MM,
        inner_conformity=f_i,
        outer_conformity=f_o,
        free_contact_angle=alpha0,
        ball_material=case.ball_material,
        ring_material=case.ring_material,
        inner_shoulder_diameter=mm(b.inner_shoulder_diameter_mm),
        outer_shoulder_diameter=mm(b.outer_shoulder_diameter_mm),
        nominal_contact_angle=nominal,
    )


def operating_point(operating) -> OperatingPoint:
    """SI operating point of a case's ``[operating]`` section (rpm, N, degree, N m)."""
    op = operating
    moment = op.tilting_moment_Nm
    misalignment = op.misalignment_deg
    return OperatingPoint(
        inner_ring_speed=rpm_to_rad_s(op.inner_ring_speed_rpm),
        outer_ring_speed=rpm_to_rad_s(op.outer_ring_speed_rpm),
        axial_load=float(op.axial_load_N),
        radial_load=float(op.radial_load_N),
        radial_load_angle=math.radians(float(op.radial_load_angle_deg)),
        misalignment=0.0 if misalignment is None else math.radians(float(misalignment)),
        misalignment_axis=math.radians(float(op.misalignment_axis_deg)),
        misalignment_frame=str(op.misalignment_frame),
        tilting_moment=None if moment is None else float(moment),
        moment_axis=math.radians(float(op.moment_axis_deg)),
    )


def cage_inputs(cage, land_flooding: float | None = None) -> CageInputs:
    """SI cage of a case's ``[cage]`` section (mm and g). ``land_flooding``: the flooded fraction
    of the guiding land that the lubrication method gives (:func:`lubrication`), used when the
    case does not give ``cage.land_flooding``."""
    if cage.land_flooding is not None:
        land_flooding = cage.land_flooding
    if land_flooding is None:
        raise ValueError("cage.land_flooding is not given: pass the lubrication method's value")
    return CageInputs(
        guidance=str(cage.guidance),
        pocket_clearance=float(cage.pocket_diametral_clearance_mm) * MM,
        guide_clearance=float(cage.guide_diametral_clearance_mm) * MM,
        mass=float(cage.mass_g) * GRAM,
        pocket_friction=float(cage.pocket_friction),
        guide_land_width=float(cage.guide_land_width_mm) * MM,
        land_flooding=float(land_flooding),
    )


@dataclass(frozen=True)
class Lubrication:
    """What the lubrication method gives (docs/lubrication.md): the oil volume fraction of the
    mixture the balls and cage move through, the flooded fraction of the cage's guiding land, the
    viscosity [Pa s] of the supplied oil (0: the inlet viscosity) and the basis of each, in
    words."""

    method: str
    assumed: bool
    oil_volume_fraction: float
    land_flooding: float
    supply_viscosity: float
    basis: str


def supply_speeds_rpm(case) -> tuple[float, float, str]:
    """(inner, outer) ring speeds [rpm] at which an oil flow is held in the bearing, and where
    along the history they are, in words: the case's speeds; for a case whose speeds are time
    histories, those at the knot time of the highest relative ring speed (the running speed the
    supply is set for, not a start from rest)."""
    from solver.case.validate import history_times, key_value_at

    op = case.operating
    histories = getattr(case, "histories", {})
    inner, outer = "operating.inner_ring_speed_rpm", "operating.outer_ring_speed_rpm"
    if inner not in histories and outer not in histories:
        return float(op.inner_ring_speed_rpm), float(op.outer_ring_speed_rpm), ""
    values = {inner: op.inner_ring_speed_rpm, outer: op.outer_ring_speed_rpm}

    def speeds(t):
        return key_value_at(values, histories, inner, t), key_value_at(values, histories, outer, t)

    top = max(history_times(histories), key=lambda t: abs(speeds(t)[0] - speeds(t)[1]))
    wi, wo = speeds(top)
    where = f" at the history's top speed ({wi:g} rpm inner, {wo:g} rpm outer, t = {top:g} s)"
    return wi, wo, where


def lubrication(case) -> Lubrication:
    """The :class:`Lubrication` of a validated case: ``lubricant.method`` (or the schema's
    assumed method) with its supply keys, the case's ``oil_volume_fraction`` and
    ``cage.land_flooding`` overriding what the method gives."""
    from solver.case import schema  # here: solver.case imports this module
    from solver.physics import lubrication as lub
    from solver.physics.rheology import viscosity_at_temperature

    oil, bearing = case.lubricant, case.bearing
    assumed = oil.method is None
    method = schema.ASSUMED_METHOD if assumed else str(oil.method)
    supply_viscosity = 0.0
    D = float(bearing.ball_diameter_mm) * MM
    dm = float(bearing.pitch_diameter_mm) * MM
    if assumed:
        fraction = schema.ASSUMED_OIL_VOLUME_FRACTION
        basis = f"oil volume fraction {fraction:g} assumed"
    elif method in ("oil_air", "oil_mist", "oil_jet"):
        if method == "oil_jet":
            flow_text = f"{oil.jet_flow_l_min:g} L/min" if oil.jet_flow_l_min is not None else ""
            flow = None if oil.jet_flow_l_min is None else oil.jet_flow_l_min * 1e-3 / 60.0
            if oil.jet_temperature_C is not None:
                supply_viscosity = viscosity_at_temperature(
                    float(oil.viscosity_Pas),
                    float(oil.reference_temperature_C),
                    float(oil.temperature_viscosity_per_K),
                    float(oil.jet_temperature_C),
                )
        else:
            flow_text = f"{oil.oil_flow_mm3_h:g} mm^3/h" if oil.oil_flow_mm3_h is not None else ""
            flow = None if oil.oil_flow_mm3_h is None else oil.oil_flow_mm3_h * 1e-9 / 3600.0
        if flow is None and oil.oil_volume_fraction is None:
            raise ValueError(f"lubricant.method = {method!r} needs its oil flow (validation)")
        if flow is None:
            fraction, basis = float(oil.oil_volume_fraction), ""
        else:
            geometry = bearing_geometry(case)
            inner_rpm, outer_rpm, when = supply_speeds_rpm(case)
            cage_speed = lub.epicyclic_cage_speed(
                rpm_to_rad_s(inner_rpm),
                rpm_to_rad_s(outer_rpm),
                dm,
                D,
                geometry.free_contact_angle,
            )
            cavity = lub.cavity_volume(dm, D, int(bearing.ball_count))
            fraction = lub.supply_oil_fraction(flow, cage_speed, cavity)
            basis = (
                f"oil flow {flow_text} held for one cage revolution{when} in the free cavity of "
                f"{cavity * 1e6:.4g} cm^3: oil volume fraction {fraction:.3g}"
            )
    elif method == "oil_bath":
        level = float(oil.oil_level_mm) * MM if oil.oil_level_mm is not None else None
        if level is None and oil.oil_volume_fraction is None:
            raise ValueError("lubricant.method = 'oil_bath' needs its oil level (validation)")
        fraction = 0.0 if level is None else lub.bath_oil_fraction(level, dm, D)
        basis = (
            ""
            if level is None
            else f"bath level {oil.oil_level_mm:g} mm: orbit-averaged immersed ball volume "
            f"fraction {fraction:.3g}"
        )
    else:  # grease
        fraction = schema.GREASE_OIL_VOLUME_FRACTION
        basis = f"oil volume fraction {fraction:g} of a run-in grease fill (an estimate)"
    if oil.oil_volume_fraction is not None:
        fraction = float(oil.oil_volume_fraction)
        basis = f"oil volume fraction {fraction:g} given (lubricant.oil_volume_fraction)"
    flooded = method in ("oil_jet", "oil_bath")
    flooding = schema.FLOODED_LAND_FLOODING if flooded else schema.STARVED_LAND_FLOODING
    if case.cage.land_flooding is not None:
        flooding = float(case.cage.land_flooding)
        basis += f"; cage land flooding {flooding:g} given (cage.land_flooding)"
    else:
        state = "flooded" if flooded else "starved (an estimate)"
        basis += f"; cage land {state}, flooding {flooding:g}"
    return Lubrication(method, assumed, fraction, flooding, supply_viscosity, basis)


def lubricant_inputs(lubricant, given: bool, method: Lubrication) -> LubricantInputs:
    """SI lubricant of a case's ``[lubricant]`` section (Pa s, 1/GPa, m/s, MPa, GPa); the
    rheology values are taken from the reference to the inlet temperature
    (solver.physics.rheology.rheology_at_temperature). The thermal softening coefficient is the
    limiting shear stress's temperature coefficient, 0 when ``thermal_softening`` is false.
    ``method``: the case's :class:`Lubrication` (:func:`lubrication`)."""
    t = lubricant.traction
    inlet = rheology_at_temperature(
        float(lubricant.reference_temperature_C),
        float(lubricant.inlet_temperature_C),
        viscosity=float(lubricant.viscosity_Pas),
        temperature_viscosity=float(lubricant.temperature_viscosity_per_K),
        pressure_viscosity=float(lubricant.pressure_viscosity_per_GPa) * PER_GPA,
        pressure_viscosity_temperature=float(lubricant.pressure_viscosity_temperature_per_K),
        eyring_stress=float(lubricant.eyring_stress_MPa) * 1.0e6,
        limiting_stress=float(lubricant.limiting_shear_stress_MPa) * 1.0e6,
        limiting_slope=float(lubricant.limiting_shear_coefficient),
        limiting_temperature=float(lubricant.limiting_shear_temperature_per_K),
        shear_modulus=float(lubricant.film_shear_modulus_GPa) * GPA,
        shear_modulus_temperature=float(lubricant.film_shear_modulus_temperature_per_K),
    )
    softening = float(lubricant.limiting_shear_temperature_per_K)
    return LubricantInputs(
        viscosity=inlet["viscosity"],
        pressure_viscosity=inlet["pressure_viscosity"],
        traction=TractionCurve(
            mu_zero=float(t.mu_zero),
            mu_max=float(t.mu_max),
            slip_at_max=float(t.slip_at_max_m_s),
            mu_infinity=float(t.mu_infinity),
        ),
        given=bool(given),
        traction_model=str(lubricant.traction_model),
        inlet_temperature=float(lubricant.inlet_temperature_C),
        temperature_viscosity=float(lubricant.temperature_viscosity_per_K),
        eyring_stress=inlet["eyring_stress"],
        limiting_shear_stress=inlet["limiting_stress"],
        limiting_shear_coefficient=inlet["limiting_slope"],
        film_shear_modulus=inlet["shear_modulus"],
        thermal_conductivity=float(lubricant.thermal_conductivity_W_mK),
        thermal_softening=softening if bool(lubricant.thermal_softening) else 0.0,
        density=float(lubricant.density_kg_m3),
        oil_volume_fraction=float(method.oil_volume_fraction),
        oil=lubricant.oil or "",
        method=method.method,
        method_assumed=method.assumed,
        supply_viscosity=method.supply_viscosity,
        mixture_basis=method.basis,
    )


def simulation_inputs(simulation) -> SimulationInputs:
    """Run length and switches of a case's ``[simulation]`` section: shaft revolutions and
    samples per revolution for a steady case, a duration [s] and samples per second for a case
    with a time history (the other pair None)."""

    def number(value, kind):
        return None if value is None else kind(value)

    return SimulationInputs(
        shaft_revolutions=number(simulation.shaft_revolutions, float),
        samples_per_revolution=number(simulation.samples_per_revolution, int),
        duration=number(simulation.duration_s, float),
        samples_per_second=number(simulation.samples_per_second, float),
        traction=bool(simulation.ball_race_traction),
        damping_ratio=float(simulation.contact_damping_ratio),
        gravity=float(simulation.gravity_m_s2),
        tolerance=float(simulation.tolerance),
        cage=bool(simulation.model_cage),
        quasistatic_ball_speeds=str(simulation.quasistatic_ball_speeds),
    )


#: Channel of each operating key that may be a time history, and the SI value of one unit of it.
HISTORY_CHANNELS = {
    "operating.inner_ring_speed_rpm": (CH_INNER_SPEED, RPM),
    "operating.outer_ring_speed_rpm": (CH_OUTER_SPEED, RPM),
    "operating.axial_load_N": (CH_AXIAL_LOAD, 1.0),
    "operating.radial_load_N": (CH_RADIAL_LOAD, 1.0),
    "operating.radial_load_angle_deg": (CH_RADIAL_LOAD_ANGLE, math.pi / 180.0),
    "operating.misalignment_deg": (CH_MISALIGNMENT, math.pi / 180.0),
    "operating.misalignment_axis_deg": (CH_MISALIGNMENT_AXIS, math.pi / 180.0),
    "operating.tilting_moment_Nm": (CH_TILTING_MOMENT, 1.0),
    "operating.moment_axis_deg": (CH_MOMENT_AXIS, math.pi / 180.0),
}


def operating_history(histories: dict, operating: OperatingPoint) -> HistoryRecord | None:
    """The :class:`solver.history.HistoryRecord` of a case's time histories (``Case.histories``,
    case units) around its operating point at t = 0 (SI); None for a steady case."""
    if not histories:
        return None
    channels = {}
    frame = FRAME_SPACE
    for key, history in histories.items():
        channel, scale = HISTORY_CHANNELS[key]
        channels[channel] = history.channel(scale)
        if history.with_shaft:
            frame = FRAME_INNER_RING
    return history_record(
        channels, operating_values(operating), frame, operating.tilting_moment is not None
    )


def operating_at(inputs: Inputs, t: float) -> OperatingPoint:
    """The operating point of ``inputs`` at time ``t`` [s] (SI): every channel of its history at
    ``t``; a steady case's operating point at any time. A radial load that turns (with the shaft, or
    in space at a speed) has its azimuth in space at ``t``, within [0, 360) degree. ValueError for
    a time that is not a finite number >= 0."""
    t = float(t)
    if not math.isfinite(t) or t < 0.0:
        raise ValueError(f"a time along the history must be a finite number >= 0 s, not {t!r}")
    record, op = inputs.history, inputs.operating
    if record is None:
        return op

    def value(channel):
        return float(channel_value(record, channel, t))

    angle = value(CH_RADIAL_LOAD_ANGLE)
    turning = record.rate[CH_RADIAL_LOAD_ANGLE] != 0.0
    if record.radial_load_frame == FRAME_INNER_RING:
        angle += channel_integral(record, CH_INNER_SPEED, t)  # the inner ring's angle at t
        turning = True
    if turning:
        angle %= 2.0 * math.pi
    return OperatingPoint(
        inner_ring_speed=value(CH_INNER_SPEED),
        outer_ring_speed=value(CH_OUTER_SPEED),
        axial_load=value(CH_AXIAL_LOAD),
        radial_load=value(CH_RADIAL_LOAD),
        radial_load_angle=angle,
        misalignment=value(CH_MISALIGNMENT),
        misalignment_axis=value(CH_MISALIGNMENT_AXIS),
        misalignment_frame=op.misalignment_frame,
        tilting_moment=None if op.tilting_moment is None else value(CH_TILTING_MOMENT),
        moment_axis=value(CH_MOMENT_AXIS),
    )


def to_inputs(case) -> Inputs:
    """SI :class:`Inputs` of a validated :class:`solver.case.Case`: a case with time histories
    gets their record in ``history`` (``operating`` is then its value at t = 0) and its run
    length as a duration."""
    lubricated = lubrication(case)
    operating = operating_point(case.operating)
    return Inputs(
        geometry=bearing_geometry(case),
        operating=operating,
        cage=cage_inputs(case.cage, lubricated.land_flooding),
        lubricant=lubricant_inputs(case.lubricant, case.lubricant_given, lubricated),
        simulation=simulation_inputs(case.simulation),
        case_text=case.to_toml(inline_files=True),
        designation=str(case.bearing.designation or ""),
        history=operating_history(getattr(case, "histories", {}), operating),
    )


def _grouped(value: float) -> str:
    """``value`` rounded to a whole number, thousands grouped with a space (``20 000``), or to
    three significant digits below 10."""
    if abs(value) < 10 and value != round(value):
        return f"{value:.3g}"
    return f"{round(value):,}".replace(",", " ")


def describe_operating_point(op: OperatingPoint) -> str:
    """The operating point as a title names it: ``10 000 rpm, 400 N axial + 0 N radial`` and,
    when present, the outer ring's speed, the radial load's angle, the misalignment and the
    tilting moment (``op`` in SI units and rad)."""
    rpm = 60.0 / (2.0 * math.pi)
    parts = [f"{_grouped(op.inner_ring_speed * rpm)} rpm"]
    if op.outer_ring_speed:
        parts[0] += f" (outer ring {_grouped(op.outer_ring_speed * rpm)} rpm)"
    loads = f"{_grouped(op.axial_load)} N axial + {_grouped(op.radial_load)} N radial"
    if op.radial_load and op.radial_load_angle:
        loads += f" at {_grouped(math.degrees(op.radial_load_angle))} deg"
    parts.append(loads)
    if op.misalignment:
        parts.append(
            f"{_grouped(math.degrees(op.misalignment))} deg misalignment ({op.misalignment_frame})"
        )
    if op.tilting_moment:
        parts.append(f"{_grouped(op.tilting_moment)} N m tilting moment")
    return ", ".join(parts)
