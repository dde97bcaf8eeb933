"""Assemble the dynamic model's xarray.Dataset (results-schema.md) from stored states."""

from __future__ import annotations

import math
from datetime import datetime, timezone

import numpy as np
import xarray as xr

import solver
from solver.physics.hertz import truncation_margin

from . import layout as L
from .inputs import DEFAULT_OIL_NOTE
from .observe import (
    N_OBS,
    O_ANGLE,
    O_AZIMUTH,
    O_DEFLECTION,
    O_FILM,
    O_LATITUDE,
    O_LOAD,
    O_LONGITUDE,
    O_PMAX,
    O_POINT,
    O_SEMI_MAJOR,
    O_SEMI_MINOR,
    O_SLIDE,
    O_SPIN_TO_ROLL,
    observe,
)

# name -> (units, long_name). Used when the project registry (solver.results.variables) lacks a name.
_META = {
    "contact_load": ("N", "normal contact load"),
    "contact_angle": ("degree", "contact angle in the ring's meridian plane"),
    "contact_deflection": ("m", "elastic approach of the contact"),
    "ellipse_semi_major": ("m", "Hertz semi-axis across the groove"),
    "ellipse_semi_minor": ("m", "Hertz semi-axis in the rolling direction"),
    "max_pressure": ("Pa", "peak Hertz pressure"),
    "raceway_azimuth": ("degree", "azimuth of the contact centre in the ring's own frame"),
    "raceway_contact_point": ("m", "contact centre in the ring's own frame"),
    "ball_latitude": ("degree", "latitude of the contact on the ball (ball-fixed frame)"),
    "ball_longitude": ("degree", "longitude of the contact on the ball (ball-fixed frame)"),
    "spin_to_roll": ("1", "spin-to-roll ratio"),
    "sliding_speed": ("m/s", "sliding speed at the contact centre"),
    "film_thickness": ("m", "central EHL film thickness (Hamrock-Dowson)"),
    "truncation_margin": ("degree", "angular margin between ellipse edge and shoulder"),
    "ball_azimuth": ("degree", "ball azimuth psi in the inertial frame"),
    "orbital_speed": ("rad/s", "orbital speed of the ball centre"),
    "ball_center": ("m", "ball centre, inertial frame"),
    "ball_angular_velocity": ("rad/s", "ball angular velocity, inertial components"),
    "attitude_angle": ("degree", "attitude angle beta of the ball spin axis"),
    "ball_orientation": ("1", "unit quaternion ball-fixed to inertial"),
    "cage_pocket_force": ("N", "normal force between ball and cage pocket"),
    "inner_ring_offset": ("m", "inner ring centre relative to the just-touching position"),
    "inner_ring_tilt": ("degree", "inner ring tilt"),
    "cage_speed": ("rad/s", "cage angular speed"),
    "cage_center": ("m", "cage centre, inertial frame"),
    "trajectory_band_width": ("degree", "contact-angle range of the race's contact track"),
    "trajectory_band_width_arc": ("m", "groove radius times the contact-angle range"),
}


def _attrs(name: str) -> dict:
    units, long_name = _META[name]
    return {"units": units, "long_name": long_name}


def truncation_margins(geometry, angle: np.ndarray, semi_major: np.ndarray) -> np.ndarray:
    """Margin [degree] between the ellipse edge and the loaded shoulder, per race (B's
    solver.physics.hertz.truncation_margin); NaN where the case gives no shoulder (results-schema.md).
    ``angle`` [rad] and ``semi_major`` [m] have a last axis race = (inner, outer)."""
    out = np.empty(angle.shape)
    for k, race in enumerate(("inner", "outer")):
        try:
            out[..., k] = truncation_margin(geometry, angle[..., k], semi_major[..., k], race)
        except ValueError:  # shoulder not on the groove arc: no margin can be stated
            out[..., k] = np.nan
    return out


def build_dataset(inputs, options, par, quad, times, states, period, complete, stop_reason, stats):
    """Dataset of the dynamic run from the stored states (S, n) at ``times`` (S,)."""
    z = int(par[L.P_Z])
    s_count = states.shape[0]
    obs = np.zeros((s_count, z, 2, N_OBS))
    pocket = np.zeros((s_count, z))
    observe(states, par, quad, inputs.viscosity, inputs.pressure_viscosity, obs, pocket)
    balls = np.stack([states[:, L.ball_base(j) : L.ball_base(j) + L.BALL_STRIDE] for j in range(z)], axis=1)
    pos = balls[..., L.B_POS : L.B_POS + 3]
    vel = balls[..., L.B_VEL : L.B_VEL + 3]
    quat = balls[..., L.B_QUAT : L.B_QUAT + 4]
    omega = balls[..., L.B_OMEGA : L.B_OMEGA + 3]
    rb = L.ring_base(z)
    cb = L.cage_base(z)
    r2 = pos[..., 1] ** 2 + pos[..., 2] ** 2
    orbital = (pos[..., 1] * vel[..., 2] - pos[..., 2] * vel[..., 1]) / r2
    psi = np.arctan2(pos[..., 2], pos[..., 1])
    # attitude angle from the ball's angular velocity relative to its orbiting frame
    w_x = omega[..., 0] - orbital
    w_r = omega[..., 1] * np.cos(psi) + omega[..., 2] * np.sin(psi)
    sgn = -1.0 if (par[L.P_WI] - par[L.P_WO]) >= 0 else 1.0
    attitude = np.degrees(np.arctan2(-sgn * w_r, sgn * w_x))
    angle = obs[..., O_ANGLE]
    semi_major = obs[..., O_SEMI_MAJOR]
    tilt = states[:, rb + L.R_TILT : rb + L.R_TILT + 2]
    # analysed window for the band metrics
    first = int(math.floor(options.analysis_skip_fraction * (s_count - 1)))
    window = slice(first, s_count)
    band = np.zeros(2)
    for k in range(2):
        a = angle[window, :, k]
        loaded = obs[window, :, k, O_LOAD] > 0.0
        if loaded.any():
            band[k] = np.degrees(a[loaded].max() - a[loaded].min())
    groove = np.array([par[L.P_RI], par[L.P_RO]])
    window_text = (
        f"t from {times[first]:.6g} s to {times[-1]:.6g} s (shaft revolutions "
        f"{times[first] / period:.3f} to {times[-1] / period:.3f}; the first "
        f"{options.analysis_skip_fraction:.0%} of the run is skipped); loaded contacts only"
    )
    tc = ("time", "ball", "race")
    tb = ("time", "ball")
    data = {
        "contact_load": (tc, obs[..., O_LOAD]),
        "contact_angle": (tc, np.degrees(angle)),
        "contact_deflection": (tc, obs[..., O_DEFLECTION]),
        "ellipse_semi_major": (tc, semi_major),
        "ellipse_semi_minor": (tc, obs[..., O_SEMI_MINOR]),
        "max_pressure": (tc, obs[..., O_PMAX]),
        "raceway_azimuth": (tc, np.degrees(obs[..., O_AZIMUTH]) % 360.0),
        "raceway_contact_point": (tc + ("axis",), obs[..., O_POINT : O_POINT + 3]),
        "ball_latitude": (tc, np.degrees(obs[..., O_LATITUDE])),
        "ball_longitude": (tc, np.degrees(obs[..., O_LONGITUDE])),
        "spin_to_roll": (tc, obs[..., O_SPIN_TO_ROLL]),
        "sliding_speed": (tc, obs[..., O_SLIDE]),
        "film_thickness": (tc, obs[..., O_FILM]),
        "truncation_margin": (tc, truncation_margins(inputs.geometry, angle, semi_major)),
        "ball_azimuth": (tb, np.degrees(psi) % 360.0),
        "orbital_speed": (tb, orbital),
        "ball_center": (tb + ("axis",), pos),
        "ball_angular_velocity": (tb + ("axis",), omega),
        "attitude_angle": (tb, attitude),
        "ball_orientation": (tb + ("quaternion",), quat),
        "cage_pocket_force": (tb, pocket),
        "inner_ring_offset": (("time", "axis"), states[:, rb + L.R_POS : rb + L.R_POS + 3]),
        "inner_ring_tilt": (("time", "tilt_axis"), np.degrees(tilt)),
        "cage_speed": (("time",), states[:, cb + L.C_SPEED]),
        "cage_center": (("time", "axis"), states[:, cb + L.C_POS : cb + L.C_POS + 3]),
        "trajectory_band_width": (("race",), band),
        "trajectory_band_width_arc": (("race",), groove * np.radians(band)),
    }
    variables = {}
    for name, (dims, values) in data.items():
        attrs = _attrs(name)
        if name.startswith("trajectory_band_width"):
            attrs["analysed_window"] = window_text
        variables[name] = (dims, np.asarray(values, dtype=np.float64), attrs)
    coords = {
        "time": ("time", np.asarray(times, dtype=np.float64), {"units": "s", "long_name": "time"}),
        "ball": np.arange(z),
        "race": ["inner", "outer"],
        "axis": ["x", "y", "z"],
        "tilt_axis": ["y", "z"],
        "quaternion": ["w", "x", "y", "z"],
    }
    attrs = {
        "model": "dynamic",
        "case": inputs.case_text,
        "software": f"racetrace {solver.__version__}",
        "created": datetime.now(timezone.utc).isoformat(timespec="seconds"),
        "complete": int(bool(complete)),
        "stop_reason": stop_reason,
        "analysed_window": window_text,
        "gravity": f"{options.gravity:g} m/s^2 along -z of the inertial frame",
        "traction_model": "ellipse-integrated ADORE-type curve" if options.traction else "off (frictionless)",
        "damping_ratio": float(options.damping_ratio),
        "cage_model": "4 DOF (translations + rotation about x)" if options.cage else "off",
        "lubricant": DEFAULT_OIL_NOTE if inputs.default_lubricant else "from the case [lubricant]",
        "integrator": f"Dormand-Prince 5(4), PI step control, tolerance {options.tolerance:g}",
        "steps": stats.steps,
        "rejected_steps": stats.rejected,
        "rhs_evaluations": stats.rhs_evaluations,
        "wall_time_s": float(stats.wall_time),
        "shaft_period_s": float(period),
    }
    return xr.Dataset(variables, coords=coords, attrs=attrs)
