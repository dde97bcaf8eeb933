"""Build the parameter vector (layout ``P_*``) and the ellipse quadrature of the dynamic model."""

from __future__ import annotations

import math

import numpy as np

from solver.inputs import Inputs
from solver.materials import Material, effective_modulus
from solver.physics.cage_contact import (
    LAND_PARAM_SIZE,
    POCKET_PARAM_SIZE,
    land_contact_stiffness_estimate,
    land_parameters,
    pocket_parameters,
    pocket_stiffness_estimate,
)
from solver.physics.traction import ellipse_quadrature, traction_curve_parameters

from . import layout as L
from .options import SimulationOptions

STEEL_DENSITY = 7800.0
#: Assumed cage material (the case format has no cage material): glass-filled polyamide 66.
CAGE_MATERIAL = Material("glass_filled_polyamide", 8.0e9, 0.4, 1400.0)


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


def build_quadrature(options: SimulationOptions) -> np.ndarray:
    """Node table of the ellipse traction rule (solver.physics.traction.ellipse_quadrature)."""
    n_roll, n_trans = options.quadrature
    return np.ascontiguousarray(ellipse_quadrature(n_roll, n_trans))


def build_params(inputs: Inputs, options: SimulationOptions) -> np.ndarray:
    """Parameter vector for the numba kernels (every slot documented in ``layout``).

    The physics switches are those of ``options`` where given, else the case's
    (``inputs.simulation``)."""
    options = options.resolved(inputs.simulation)
    g = inputs.geometry
    op = inputs.operating
    cage = inputs.cage
    lubricant = inputs.lubricant
    p = np.zeros(L.N_PARAMS)
    D, dm = g.ball_diameter, g.pitch_diameter
    p[L.P_Z] = g.ball_count
    p[L.P_D] = D
    p[L.P_DM] = dm
    p[L.P_MB] = g.ball_mass
    p[L.P_JB] = g.ball_inertia
    p[L.P_RI] = g.inner_groove_radius
    p[L.P_RO] = g.outer_groove_radius
    p[L.P_XCI] = g.inner_curvature_center_axial
    p[L.P_RCI] = g.inner_curvature_center_radius
    p[L.P_XCO] = g.outer_curvature_center_axial
    p[L.P_RCO] = g.outer_curvature_center_radius
    p[L.P_FI] = g.inner_conformity
    p[L.P_FO] = g.outer_conformity
    p[L.P_EPRIME] = g.effective_modulus
    p[L.P_WI] = op.inner_ring_speed
    p[L.P_WO] = op.outer_ring_speed
    mass, diametral, polar = ring_mass_properties(inputs, options)
    p[L.P_MR] = mass
    p[L.P_IRD] = diametral
    p[L.P_IRP] = polar
    p[L.P_FX] = op.axial_load
    p[L.P_FY] = op.radial_load * math.cos(op.radial_load_angle)
    p[L.P_FZ] = op.radial_load * math.sin(op.radial_load_angle)
    if op.tilting_moment is not None:
        p[L.P_TILT_MODE] = 2
        p[L.P_MY] = op.tilting_moment * math.cos(op.moment_axis)
        p[L.P_MZ] = op.tilting_moment * math.sin(op.moment_axis)
    else:
        p[L.P_TILT_MODE] = 1 if op.misalignment_frame == "ring" else 0
        p[L.P_TILT_Y] = op.misalignment * math.cos(op.misalignment_axis)
        p[L.P_TILT_Z] = op.misalignment * math.sin(op.misalignment_axis)
    p[L.P_RING_FREE] = 1.0 if options.ring_free else 0.0
    p[L.P_GRAVITY] = options.gravity
    p[L.P_ZETA] = options.damping_ratio
    p[L.P_TRACTION] = 1.0 if options.traction else 0.0
    curve = traction_curve_parameters(*lubricant.traction.values())
    p[L.P_MU_A : L.P_MU_D + 1] = curve
    p[L.P_CAGE_ON] = 1.0 if options.cage else 0.0
    p[L.P_MC] = cage.mass
    p[L.P_CAGE_R] = 0.5 * dm
    # cage as a thin ring of radius d_m/2 and width D: polar m R^2, diametral m R^2 / 2 + m D^2 / 12
    p[L.P_IC] = cage.mass * (0.5 * dm) ** 2
    p[L.P_ICD] = 0.5 * cage.mass * (0.5 * dm) ** 2 + cage.mass * D**2 / 12.0
    p[L.P_CP] = cage.pocket_clearance
    p[L.P_ZETA_P] = options.pocket_damping_ratio
    p[L.P_MU_P] = cage.pocket_friction
    guide = {"outer_ring": 0, "inner_ring": 1, "ball": 2}[cage.guidance]
    p[L.P_GUIDE] = guide
    if guide == 0:
        shoulder = g.outer_shoulder_diameter
        land = 0.5 * shoulder if math.isfinite(shoulder) else 0.5 * dm + 0.35 * D
    else:
        shoulder = g.inner_shoulder_diameter
        land = 0.5 * shoulder if math.isfinite(shoulder) else 0.5 * dm - 0.35 * D
    p[L.P_RG] = land
    p[L.P_CG] = 0.5 * cage.guide_clearance
    p[L.P_LG] = cage.guide_land_width
    p[L.P_ETA] = lubricant.viscosity
    p[L.P_V_REG] = options.friction_regularisation
    p[L.P_HEATHCOTE] = 1.0 if options.heathcote else 0.0
    # cage contact laws of solver.physics.cage_contact; the case gives no cage material: a
    # glass-filled polyamide cage (linear pocket law, secant of the Hertz law at 10 N) is assumed
    pocket_k = options.pocket_stiffness
    if pocket_k is None:
        pocket_k = pocket_stiffness_estimate(
            D, cage.pocket_clearance, g.ball_material, CAGE_MATERIAL, exponent=1.0
        )
    p[L.P_KP] = pocket_k
    p[L.P_POCKET_BLOCK : L.P_POCKET_BLOCK + POCKET_PARAM_SIZE] = pocket_parameters(
        pocket_k,
        1.0,
        options.pocket_damping_ratio,
        g.ball_mass,
        cage.pocket_friction,
        cage.pocket_clearance,
        D,
        slip_regularisation=options.friction_regularisation,
    )
    land_k = options.land_stiffness
    if land_k is None:
        land_k = land_contact_stiffness_estimate(
            cage.guide_land_width, effective_modulus(CAGE_MATERIAL, g.ring_material)
        )
    p[L.P_KG] = land_k
    p[L.P_LAND_BLOCK : L.P_LAND_BLOCK + LAND_PARAM_SIZE] = land_parameters(
        land,
        cage.guide_land_width,
        0.5 * cage.guide_clearance,
        lubricant.viscosity,
        land_k,
        cage.mass,
        guide != 1,
        slip_regularisation=options.friction_regularisation,
    )
    return p
