"""The quasi-static model's Dataset: QuasiStaticSolution + case → xarray.Dataset following
results-schema.md.

Hertz results (ellipse, peak pressure) come from :mod:`solver.physics.hertz_fast` (the same
load-deflection law the model was solved with). The sliding speed at the contact centre is reported
as zero (race control imposes pure rolling there; with the traction balance the centre slip is a
small fraction of the rolling speed that is not stored); the variable is kept so that both models
share the schema.
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr
from numba import njit

from solver.physics.ehl import film_thickness_central
from solver.physics.hertz import truncation_margin
from solver.physics.hertz_fast import (
    contact_ellipse_fast,
    curvature_sum_and_difference_fast,
    equivalent_radii_fast,
    hertz_coefficients_fast,
)
from solver.physics.kinematics import contact_latitude_longitude, spin_and_roll
from solver.results.dataset import ResultArrays, case_text, result_arrays
from solver.results.life import snapshot_life_metrics
from solver.results.variables import VARIABLES

MODEL = "quasistatic"


def _rotation_matrix(rotation_vector: np.ndarray) -> np.ndarray:
    """Rodrigues rotation matrix of a rotation vector [rad]."""
    angle = float(np.linalg.norm(rotation_vector))
    if angle == 0.0:
        return np.eye(3)
    k = rotation_vector / angle
    kx = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + math.sin(angle) * kx + (1.0 - math.cos(angle)) * kx @ kx


@njit(cache=True)
def _contact_fields(
    contact_angle,
    contact_load,
    e_contact,
    attitude,
    spin_speed,
    orbital_speed,
    ring_speed,
    geometry,
    lubricant,
):
    """Per-contact arrays (Z, 2) [inner, outer] of a solution, in one compiled loop: the Hertz
    ellipse a, b [m] and peak pressure [Pa] (zeros for open contacts), the contact's latitude and
    longitude on the ball [rad], spin-to-roll ratio and central film [m] (0 at open contacts, and
    everywhere when ``lubricant`` is None).

    ``contact_angle`` [rad], ``contact_load`` [N] (Z, 2); ``e_contact`` (Z, 2, 2): unit vector
    from the ball centre to each contact (axial, radial); ``attitude`` [rad], ``spin_speed`` and
    ``orbital_speed`` [rad/s] (Z); ``ring_speed`` [rad/s] (inner, outer); ``geometry``: (ball
    diameter, pitch diameter, inner and outer conformity, effective modulus), SI; ``lubricant``:
    (viscosity [Pa s], pressure-viscosity coefficient [1/Pa]) or None."""
    D, pitch, inner_conformity, outer_conformity, e_mod = geometry
    z = contact_load.shape[0]
    semi_major = np.zeros((z, 2))
    semi_minor = np.zeros((z, 2))
    pressure = np.zeros((z, 2))
    latitude = np.empty((z, 2))
    longitude = np.empty((z, 2))
    spin_roll = np.zeros((z, 2))
    film = np.zeros((z, 2))
    for j in range(z):
        beta = attitude[j]
        for k in range(2):
            is_inner = k == 0
            alpha = contact_angle[j, k]
            load = contact_load[j, k]
            conformity = inner_conformity if is_inner else outer_conformity
            gamma = D * math.cos(alpha) / pitch
            s, f = curvature_sum_and_difference_fast(D, conformity, gamma, is_inner)
            a, b, _, p = contact_ellipse_fast(load, s, f, e_mod)
            semi_major[j, k], semi_minor[j, k], pressure[j, k] = a, b, p
            lat, lon = contact_latitude_longitude(e_contact[j, k, 0], e_contact[j, k, 1], 0.0, beta)
            latitude[j, k], longitude[j, k] = lat, lon
            in_cage = ring_speed[k] - orbital_speed[j]
            spin, roll = spin_and_roll(alpha, beta, spin_speed[j], in_cage)
            spin_roll[j, k] = spin / roll if roll != 0.0 else 0.0
            if lubricant is not None and load > 0.0:
                # (an open contact has no film: 0) entrainment speed: surface speed of the ring
                # at the contact, relative to the cage
                sign = -1.0 if is_inner else 1.0
                radius = 0.5 * pitch + sign * 0.5 * D * math.cos(alpha)
                film[j, k] = film_thickness_central(
                    abs(in_cage) * radius,
                    lubricant[0],
                    lubricant[1],
                    e_mod,
                    equivalent_radii_fast(D, conformity, gamma, is_inner)[0],
                    load,
                    hertz_coefficients_fast(f)[0],
                )
    return semi_major, semi_minor, pressure, latitude, longitude, spin_roll, film


def solution_to_dataset(
    solution, geometry, case=None, lubricant=None, operating=None, estimates=None
) -> xr.Dataset:
    """Dataset of a :class:`QuasiStaticSolution` (results-schema.md, quasi-static variables):
    the Dataset of :func:`solution_arrays` (same arguments)."""
    return solution_arrays(solution, geometry, case, lubricant, operating, estimates).dataset()


def solution_arrays(
    solution, geometry, case=None, lubricant=None, operating=None, estimates=None
) -> ResultArrays:
    """The :class:`solver.results.dataset.ResultArrays` of the Dataset of a
    :class:`QuasiStaticSolution` (results-schema.md, quasi-static variables).

    ``lubricant`` (a :class:`solver.inputs.LubricantInputs`, SI, or None) adds ``film_thickness``.
    The rating lives (ISO 281, ISO/TS 16281: :mod:`solver.results.life`) are added.
    ``operating`` (SI operating point, see :func:`solver.results.dataset.describing_coordinates`)
    defaults to the one the solution was solved for; ``case`` (a Case or TOML text) is kept in
    ``attrs["case"]`` for provenance. ``estimates`` (the
    :class:`solver.results.estimates.EstimateFields` of the case, or None) adds the friction-torque
    estimates, as :func:`solver.results.estimates.with_estimates` would, in the same build.
    """
    sol = solution
    operating = operating if operating is not None else sol.operating
    if operating is None:
        raise ValueError("solution_arrays: the operating point of the solution is missing")
    z = sol.contact_load.shape[0]
    psi = sol.ball_azimuth
    alpha = sol.contact_angle
    beta = sol.attitude_angle
    cos_psi, sin_psi = np.cos(psi), np.sin(psi)

    # ball centre, inertial
    center = np.column_stack(
        [sol.ball_center[:, 0], sol.ball_center[:, 1] * cos_psi, sol.ball_center[:, 1] * sin_psi]
    )
    # contact points (inertial): ball centre + (D/2 - delta/2) * (unit vector to the contact)
    D = geometry.ball_diameter
    e_contact = np.empty((z, 2, 2))  # (ball, race, [x, r]) unit vector from the ball centre
    e_contact[:, 0, 0] = -np.sin(alpha[:, 0])
    e_contact[:, 0, 1] = -np.cos(alpha[:, 0])
    e_contact[:, 1, 0] = np.sin(alpha[:, 1])
    e_contact[:, 1, 1] = np.cos(alpha[:, 1])
    reach = 0.5 * D - 0.5 * sol.contact_deflection  # (Z, 2)
    px = sol.ball_center[:, 0:1] + reach * e_contact[:, :, 0]
    pr = sol.ball_center[:, 1:2] + reach * e_contact[:, :, 1]
    point = np.stack([px, pr * cos_psi[:, None], pr * sin_psi[:, None]], axis=-1)  # (Z, 2, 3)
    # inner ring frame: undo the ring's displacement (rotation about its reference point)
    rotation = _rotation_matrix(np.array([0.0, *sol.inner_ring_tilt]))
    pivot = np.array([geometry.inner_curvature_center_axial, 0.0, 0.0])
    inner_inertial = point[:, 0, :]
    point[:, 0, :] = (inner_inertial - sol.inner_ring_offset - pivot) @ rotation + pivot
    raceway_azimuth = np.degrees(np.arctan2(point[:, :, 2], point[:, :, 1])) % 360.0
    raceway_azimuth[raceway_azimuth >= 360.0] = 0.0

    a, b, p_max, latitude, longitude, spin_roll, film = _contact_fields(
        alpha,
        sol.contact_load,
        e_contact,
        beta,
        sol.spin_speed,
        sol.orbital_speed,
        np.array([sol.inner_ring_speed, sol.outer_ring_speed], dtype=float),
        (
            float(D),
            float(geometry.pitch_diameter),
            float(geometry.inner_conformity),
            float(geometry.outer_conformity),
            float(geometry.effective_modulus),
        ),
        None
        if lubricant is None
        else (float(lubricant.viscosity), float(lubricant.pressure_viscosity)),
    )
    margin = np.empty((z, 2))
    for k, race in enumerate(("inner", "outer")):
        margin[:, k] = truncation_margin(geometry, np.abs(alpha[:, k]), a[:, k], race)

    data = {
        "contact_load": sol.contact_load,
        "contact_angle": np.degrees(alpha),
        "contact_deflection": sol.contact_deflection,
        "ellipse_semi_major": a,
        "ellipse_semi_minor": b,
        "max_pressure": p_max,
        "raceway_azimuth": raceway_azimuth,
        "raceway_contact_point": point,
        "ball_latitude": np.degrees(latitude),
        "ball_longitude": np.degrees(longitude),
        "spin_to_roll": spin_roll,
        "sliding_speed": np.zeros((z, 2)),
        "truncation_margin": margin,
        "ball_azimuth": np.degrees(psi),
        "orbital_speed": sol.orbital_speed,
        "ball_center": center,
        "ball_angular_velocity": sol.ball_angular_velocity,
        "attitude_angle": np.degrees(beta),
        "ball_spin_speed": sol.spin_speed,
        "centrifugal_force": sol.centrifugal_force,
        "gyroscopic_moment": sol.gyroscopic_moment,
        "race_control": np.asarray(sol.race_control, dtype=str).astype(object),
        "inner_ring_offset": sol.inner_ring_offset,
        "inner_ring_tilt": np.degrees(sol.inner_ring_tilt),
        "inner_ring_moment": sol.applied_moment,
        "cage_speed": np.float64(sol.cage_speed),
    }
    if lubricant is not None:
        data["film_thickness"] = film
    traction = getattr(sol, "ball_speeds", "race_control") == "traction"
    descriptions = {
        "sliding_speed": {
            "description": "; zero in the quasi-static model, which imposes pure rolling at the "
            "contact centres"
            if not traction
            else "; not computed by the quasi-static model with the traction balance (0)"
        }
    }
    if lubricant is not None:
        descriptions["film_thickness"] = {"description": "; 0 at open contacts"}
    if traction:
        kinematics = (
            "Quasi-static model with the ball speeds from the traction balance: one cage speed "
            "for all balls (the cage pocket forces sum to zero), each ball's spin from the "
            "moment balance of the tractions integrated over both contact ellipses (with the "
            "dynamic model's traction law, lubricant.traction_model: the traction curve or the "
            "oil's rheology) against its gyroscopic rate; the transverse tractions take the "
            "gyroscopic moment in the force balances"
        )
    else:
        kinematics = (
            "Jones-Harris quasi-static model: pure rolling at both contact centres, race control "
            "per ball (Jones criterion), gyroscopic moment taken by friction (lambda_o = 2 / "
            "lambda_i = 0 under outer control, 1 / 1 under inner control), cage speed = mean "
            "orbital speed"
        )
    attrs = {
        "solver_iterations": int(sol.iterations),
        "solver_residual": float(sol.residual),
        "solver_force_scale_N": float(sol.force_scale),
        "race_control_note": sol.race_control_note or "race control settled (fixed point)",
        "model_notes": (
            f"{kinematics}; centrifugal force at the ball's actual orbit radius. Inner ring "
            "moments are taken about its centre on the axis in the plane of the inner groove "
            "curvature-centre circle."
        ),
    }
    attrs["kinematics"] = "traction" if traction else "race_control"
    if getattr(sol, "ball_speeds_note", ""):
        attrs["kinematics_note"] = sol.ball_speeds_note
    if operating.misalignment_frame == "ring" and operating.tilting_moment is None:
        attrs["misalignment_note"] = (
            "misalignment_frame = ring: the quasi-static solution is the snapshot at t = 0, when "
            "the ring-fixed tilt axis coincides with the given azimuth"
        )
    # the rating lives (solver.results.life) from the arrays, not read back from the Dataset
    lives = snapshot_life_metrics(geometry, operating, sol.contact_load, alpha)
    for name, (_, values, life_attrs) in lives.items():
        data[name] = values
        if "note" in life_attrs:
            descriptions[name] = {"note": life_attrs["note"]}
    if estimates is not None:
        data.update(estimates.values)
        descriptions.update(estimates.notes)
        attrs.update(estimates.attrs)
    return result_arrays(
        MODEL,
        {name: (VARIABLES[name].dims_for(MODEL), values) for name, values in data.items()},
        geometry,
        operating,
        case=case_text(case),
        attrs=attrs,
        variable_attrs=descriptions,
    )


#: The dynamic result's variables holding its quasi-static start, and the quasi-static result's
#: variable each one copies.
START_VARIABLES = {
    "quasistatic_ball_azimuth": "ball_azimuth",
    "quasistatic_contact_angle": "contact_angle",
    "quasistatic_contact_load": "contact_load",
    "quasistatic_cage_speed": "cage_speed",
}


def start_variables(solution) -> dict:
    """The quasi-static ``solution`` a dynamic run starts from as the dynamic result's
    ``quasistatic_*`` variables (:data:`START_VARIABLES`): ``{name: (dims, values)}`` with the
    values the quasi-static Dataset holds (angles in degree)."""
    return {
        "quasistatic_ball_azimuth": (("ball",), np.degrees(solution.ball_azimuth)),
        "quasistatic_contact_angle": (("ball", "race"), np.degrees(solution.contact_angle)),
        "quasistatic_contact_load": (("ball", "race"), solution.contact_load),
        "quasistatic_cage_speed": ((), np.float64(solution.cage_speed)),
    }


def quasistatic_start(ds: xr.Dataset) -> xr.Dataset | None:
    """The quasi-static start of the dynamic result ``ds`` as a Dataset with the quasi-static
    result's names (``ball_azimuth``, ``contact_angle``, ``contact_load``, ``cage_speed``): the
    ``quasistatic_*`` variables it carries, or, for a result written before it carried them, the
    quasi-static solution (race control) of the operating point and geometry in its coordinates.
    A quasi-static result is its own start. None when there is none (no equilibrium at that
    operating point, or a result without its coordinates); the case text is never read."""
    from solver.errors import NoSolutionError
    from solver.results.dataset import geometry_from_result, operating_from_result

    from .solver import solve_operating_point

    if "time" not in ds.dims:
        return ds
    if all(name in ds for name in START_VARIABLES):
        return xr.Dataset({own: ds[name] for name, own in START_VARIABLES.items()})
    try:
        solution = solve_operating_point(geometry_from_result(ds), operating_from_result(ds))
    except (NoSolutionError, ValueError, KeyError):
        return None
    start = start_variables(solution)
    return xr.Dataset(
        {
            own: (start[name][0], start[name][1], VARIABLES[own].attrs())
            for name, own in START_VARIABLES.items()
        }
    )
