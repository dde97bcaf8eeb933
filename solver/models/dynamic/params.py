"""The parameter record of the dynamic model's kernels, and the ellipse quadrature.

:class:`ModelParams` is a NamedTuple of scalars, flags, integer modes (constants in ``layout``)
and small arrays; numba compiles it as a typed record, so a kernel reads ``par.ball_mass`` and a new
parameter is one new field here (with its unit) plus one line in :func:`build_params`.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from solver.history import Drive, HistoryRecord, drive_at, steady_history
from solver.inputs import Inputs
from solver.materials import Material, effective_modulus
from solver.physics.cage_contact import (
    land_contact_stiffness_estimate,
    land_parameters,
    pocket_parameters,
    pocket_stiffness_estimate,
)
from solver.physics.drag import cage_drag_coefficients
from solver.physics.hertz_race import race_table
from solver.physics.traction import (
    LAW_RHEOLOGY,
    LAW_SLIP_CURVE,
    ellipse_quadrature,
    split_ellipse_rule,
    traction_curve_parameters,
)

from . import layout as L
from .options import (
    DEFAULT_ELLIPSE_RULE,
    DEFAULT_QUADRATURE,
    DEFAULT_SPLIT_COUNTS,
    SimulationOptions,
)

STEEL_DENSITY = 7800.0
#: Air at about 40 degC, the gas of the oil-air mixture around the balls.
AIR_DENSITY = 1.13  # kg/m^3
AIR_VISCOSITY = 1.9e-5  # Pa s
CAGE_FACE_HALF_HEIGHT = 0.35  # radial half-height of the cage's side faces, in ball diameters
#: Assumed cage material (the case format has no cage material): glass-filled polyamide 66.
CAGE_MATERIAL = Material("glass_filled_polyamide", 8.0e9, 0.4, 1400.0)


class ModelParams(NamedTuple):
    """Everything the dynamic model's kernels read besides the state, SI units.

    Frames and signs as in ``layout`` and ``kernels`` (inertial x = bearing axis, gravity -z).
    The imposed inputs (ring speeds, applied forces and moment, imposed tilt) are not here: they
    are the operating history's (:func:`model_history`), which the kernels take as an argument of
    its own and read at the time they are evaluated at (:func:`solver.history.drive_at`;
    :func:`drive_at_start` for t = 0). Kept out of this record because numba passes every array
    of a record as separate call arguments to each of the many small kernels that receive it.
    """

    # ---- geometry and masses
    ball_count: int
    ball_diameter: float  # D [m]
    pitch_diameter: float  # d_m [m]
    ball_mass: float  # [kg]
    ball_inertia: float  # ball polar inertia [kg m^2]
    inner_groove_radius: float  # r_i [m]
    outer_groove_radius: float  # r_o [m]
    inner_centre_axial: float  # inner groove curvature-centre axial position, ring frame [m]
    inner_centre_radius: float  # inner groove curvature-centre circle radius [m]
    outer_centre_axial: float  # outer groove curvature-centre axial position [m]
    outer_centre_radius: float  # outer groove curvature-centre circle radius [m]
    inner_conformity: float  # f_i = r_i / D
    outer_conformity: float  # f_o
    eprime: float  # effective modulus E' [Pa]
    inner_hertz: np.ndarray  # Hertz table of the inner race (solver.physics.hertz_race.race_table)
    outer_hertz: np.ndarray  # of the outer race
    # ---- rings, loads and modes
    ring_mass: float  # inner ring (+ shaft share) mass [kg]
    ring_diametral_inertia: float  # [kg m^2]
    ring_polar_inertia: float  # [kg m^2]
    tilt_mode: int  # layout.TILT_FIXED_IN_SPACE / TILT_TURNING_WITH_RING / TILT_FREE
    ring_free: bool  # ring translations are DOF (False: held at the initial position)
    gravity: float  # gravitational acceleration along -z [m/s^2]
    # ---- ball-race contacts
    damping_ratio: float  # critical-damping ratio of the ball-race normal contacts
    traction: bool  # ellipse-integrated traction on (False: frictionless)
    traction_law: int  # solver.physics.traction.LAW_RHEOLOGY or LAW_SLIP_CURVE
    traction_curve: tuple  # (A, B, C, D) of mu(u) = (A + B u) exp(-C u) + D
    rheology: tuple  # solver.physics.rheology parameters (RH_* slots)
    viscosity: float  # oil viscosity at the inlet temperature [Pa s]
    pressure_viscosity: float  # Barus alpha [1/Pa]
    hysteresis: float  # elastic hysteresis loss fraction of the ball-race contacts
    slip_regularisation: float  # regularisation speed of Coulomb-type friction laws [m/s]
    heathcote: bool  # slip evaluated on the curved (deformed) ellipse surface
    # ---- cage
    cage: bool  # cage modelled
    cage_mass: float  # [kg]
    cage_polar_inertia: float  # [kg m^2]
    cage_diametral_inertia: float  # [kg m^2]
    pocket_radius: float  # pocket-centre radius in the cage [m]
    pocket_clearance: float  # pocket diametral clearance [m]
    pocket_stiffness: float  # linear pocket contact stiffness [N/m]
    pocket: tuple  # pocket law parameters of solver.physics.cage_contact.pocket_parameters
    guidance: int  # layout.GUIDE_OUTER_RING / GUIDE_INNER_RING / GUIDE_BALL
    land_clearance: float  # guiding radial clearance [m]
    land: tuple  # land law parameters of solver.physics.cage_contact.land_parameters
    # ---- oil-air mixture around the balls (drag)
    mixture_density: float  # [kg/m^3]
    mixture_viscosity: float  # [Pa s]
    # ---- drag of the mixture on the cage's side faces (solver.physics.drag)
    cage_drag_laminar: float  # laminar coefficient of cage_drag_moment_from [N m s^1.5]
    cage_drag_turbulent: float  # turbulent coefficient of cage_drag_moment_from [N m s^1.8]


def ring_mass_properties(inputs: Inputs, options: SimulationOptions):
    """(mass [kg], diametral inertia, polar inertia [kg m^2]) of the inner ring.

    Estimate (no ring data in the case): a steel annulus of width 2 D from the bore d_m - 2 D to the
    inner groove-bottom diameter; ``options.inner_ring_mass`` overrides the mass.
    """
    g = inputs.geometry
    D, dm = g.ball_diameter, g.pitch_diameter
    r_out = 0.5 * g.inner_groove_bottom_diameter
    r_in = max(0.5 * dm - D, 0.25 * dm)
    if r_in >= r_out:
        r_in = 0.5 * r_out
    width = 2.0 * D
    mass = STEEL_DENSITY * math.pi * (r_out**2 - r_in**2) * width
    if options.inner_ring_mass is not None:
        mass = float(options.inner_ring_mass)
    polar = 0.5 * mass * (r_out**2 + r_in**2)
    diametral = 0.25 * mass * (r_out**2 + r_in**2) + mass * width**2 / 12.0
    return mass, diametral, polar


def outer_ring_mass(geometry, width: float) -> float:
    """Mass [kg] of an outer ring of the bearing ``geometry`` (a BearingGeometry) and width
    ``width`` [m]: an annulus of its ring material's density from the outer groove-bottom diameter
    to d_m + 2 D (the outside diameter of an angular contact bearing of the usual series, e.g.
    68.3 mm for a 7008C's 68 mm). The dynamic set model's floating outer rings (spring preload)."""
    D, dm = geometry.ball_diameter, geometry.pitch_diameter
    r_in = 0.5 * geometry.outer_groove_bottom_diameter
    r_out = 0.5 * dm + D
    if r_out <= r_in:
        r_out = r_in + 0.5 * D
    return geometry.ring_material.density * math.pi * (r_out**2 - r_in**2) * width


def build_quadrature(options: SimulationOptions, par: ModelParams) -> np.ndarray:
    """Node table of the ellipse traction rule: ``options.ellipse_rule`` (None: "product" when
    ``options.quadrature`` is given, else the default rule of the traction law of ``par``,
    :data:`~solver.models.dynamic.options.DEFAULT_ELLIPSE_RULE`) with the counts
    ``options.quadrature`` or the rule's default (:data:`~solver.models.dynamic.options.
    DEFAULT_QUADRATURE` of the traction law, :data:`~solver.models.dynamic.options.
    DEFAULT_SPLIT_COUNTS`). Product rule: solver.physics.traction.ellipse_quadrature; split rule:
    solver.physics.traction.split_ellipse_rule."""
    rule = options.ellipse_rule
    if rule is None:
        rule = "product" if options.quadrature else DEFAULT_ELLIPSE_RULE[par.traction_law]
    if rule == "split":
        return np.ascontiguousarray(
            split_ellipse_rule(*(options.quadrature or DEFAULT_SPLIT_COUNTS))
        )
    n_roll, n_trans = options.quadrature or DEFAULT_QUADRATURE[par.traction_law]
    return np.ascontiguousarray(ellipse_quadrature(n_roll, n_trans))


def build_params(inputs: Inputs, options: SimulationOptions) -> ModelParams:
    """Parameter record for the numba kernels.

    The physics switches are those of ``options`` where given, else the case's
    (``inputs.simulation``)."""
    options = options.resolved(inputs.simulation)
    g = inputs.geometry
    op = inputs.operating
    cage = inputs.cage
    lubricant = inputs.lubricant
    D, dm = g.ball_diameter, g.pitch_diameter
    if op.tilting_moment is not None:
        tilt_mode = L.TILT_FREE
    else:
        tilt_mode = (
            L.TILT_TURNING_WITH_RING if op.misalignment_frame == "ring" else L.TILT_FIXED_IN_SPACE
        )
    ring_mass, ring_diametral, ring_polar = ring_mass_properties(inputs, options)
    guide = {
        "outer_ring": L.GUIDE_OUTER_RING,
        "inner_ring": L.GUIDE_INNER_RING,
        "ball": L.GUIDE_BALL,
    }[cage.guidance]
    if guide == L.GUIDE_OUTER_RING:
        shoulder = g.outer_shoulder_diameter
        land = 0.5 * shoulder if math.isfinite(shoulder) else 0.5 * dm + 0.35 * D
    else:
        shoulder = g.inner_shoulder_diameter
        land = 0.5 * shoulder if math.isfinite(shoulder) else 0.5 * dm - 0.35 * D
    # cage contact laws of solver.physics.cage_contact; the case gives no cage material: a
    # glass-filled polyamide cage (linear pocket law, secant of the Hertz law at 10 N) is assumed
    pocket_k = options.pocket_stiffness
    if pocket_k is None:
        pocket_k = pocket_stiffness_estimate(
            D, cage.pocket_clearance, g.ball_material, CAGE_MATERIAL, exponent=1.0
        )
    land_k = options.land_stiffness
    if land_k is None:
        land_k = land_contact_stiffness_estimate(
            cage.guide_land_width, effective_modulus(CAGE_MATERIAL, g.ring_material)
        )
    # the mixture's oil fraction follows the lubrication method (solver.inputs.lubrication); its
    # oil has the supply's viscosity (jet temperature) when the case gives one
    mix = lubricant.oil_volume_fraction
    rho_mix = mix * lubricant.density + (1.0 - mix) * AIR_DENSITY
    eta_mix = mix * lubricant.mixture_viscosity_of_oil + (1.0 - mix) * AIR_VISCOSITY
    # the case gives no cage section: its side faces are taken to span d_m/2 +- 0.35 D, the band
    # between the estimated shoulders of the rings
    cage_drag = cage_drag_coefficients(
        rho_mix, eta_mix, 0.5 * dm + CAGE_FACE_HALF_HEIGHT * D, 0.5 * dm - CAGE_FACE_HALF_HEIGHT * D
    )
    return ModelParams(
        ball_count=int(g.ball_count),
        ball_diameter=D,
        pitch_diameter=dm,
        ball_mass=g.ball_mass,
        ball_inertia=g.ball_inertia,
        inner_groove_radius=g.inner_groove_radius,
        outer_groove_radius=g.outer_groove_radius,
        inner_centre_axial=g.inner_curvature_center_axial,
        inner_centre_radius=g.inner_curvature_center_radius,
        outer_centre_axial=g.outer_curvature_center_axial,
        outer_centre_radius=g.outer_curvature_center_radius,
        inner_conformity=g.inner_conformity,
        outer_conformity=g.outer_conformity,
        eprime=g.effective_modulus,
        inner_hertz=race_table(D, dm, g.inner_conformity, True),
        outer_hertz=race_table(D, dm, g.outer_conformity, False),
        ring_mass=ring_mass,
        ring_diametral_inertia=ring_diametral,
        ring_polar_inertia=ring_polar,
        tilt_mode=tilt_mode,
        ring_free=bool(options.ring_free),
        gravity=float(options.gravity),
        damping_ratio=float(options.damping_ratio),
        traction=bool(options.traction),
        traction_law=LAW_RHEOLOGY if lubricant.traction_model == "rheology" else LAW_SLIP_CURVE,
        traction_curve=_floats(traction_curve_parameters(*lubricant.traction.values())),
        rheology=_floats(rheology_parameters(lubricant)),
        viscosity=lubricant.viscosity,
        pressure_viscosity=lubricant.pressure_viscosity,
        hysteresis=0.5 * (g.ball_material.hysteresis_loss + g.ring_material.hysteresis_loss),
        slip_regularisation=float(options.friction_regularisation),
        heathcote=bool(options.heathcote),
        cage=bool(options.cage),
        cage_mass=cage.mass,
        # cage as a thin ring of radius d_m/2 and width D: polar m R^2, diametral
        # m R^2 / 2 + m D^2 / 12
        cage_polar_inertia=cage.mass * (0.5 * dm) ** 2,
        cage_diametral_inertia=0.5 * cage.mass * (0.5 * dm) ** 2 + cage.mass * D**2 / 12.0,
        pocket_radius=0.5 * dm,
        pocket_clearance=cage.pocket_clearance,
        pocket_stiffness=float(pocket_k),
        pocket=_floats(
            pocket_parameters(
                pocket_k,
                1.0,
                options.pocket_damping_ratio,
                g.ball_mass,
                cage.pocket_friction,
                cage.pocket_clearance,
                D,
                slip_regularisation=options.friction_regularisation,
            )
        ),
        guidance=guide,
        land_clearance=0.5 * cage.guide_clearance,
        land=_floats(
            land_parameters(
                land,
                cage.guide_land_width,
                0.5 * cage.guide_clearance,
                # a partly flooded land: the hydrodynamic force scales with the wetted width
                lubricant.mixture_viscosity_of_oil * cage.land_flooding,
                land_k,
                cage.mass,
                guide != L.GUIDE_INNER_RING,
                slip_regularisation=options.friction_regularisation,
            )
        ),
        mixture_density=rho_mix,
        mixture_viscosity=eta_mix,
        cage_drag_laminar=cage_drag[0],
        cage_drag_turbulent=cage_drag[1],
    )


def model_history(inputs: Inputs) -> HistoryRecord:
    """The operating history the dynamic model follows (:class:`solver.history.HistoryRecord`:
    ring speeds, loads, tilt or moment against time): the case's time histories
    (``inputs.history``), or for a steady case the constant history of its operating point."""
    if inputs.history is not None:
        return inputs.history
    return steady_history(inputs.operating)


def drive_at_start(history: HistoryRecord) -> Drive:
    """The imposed inputs of the operating history ``history`` at t = 0 (ring speeds, forces,
    tilt; :class:`solver.history.Drive`): those the initial state is balanced under."""
    return drive_at(history, 0.0, 0.0)


def _floats(values) -> tuple:
    """A parameter array as a tuple of floats: numba passes a tuple of scalars by value, where an
    array in the record would cost two atomic reference-count updates at every kernel call that
    receives the record."""
    return tuple(float(v) for v in values)


def rheology_parameters(lubricant) -> np.ndarray:
    """Parameter array of solver.physics.rheology (RH_* slots) of a LubricantInputs (SI)."""
    return lubricant.rheology_array()
