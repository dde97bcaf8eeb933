"""Assemble the dynamic model's xarray.Dataset (results-schema.md) from stored states."""

from __future__ import annotations

import numpy as np
import xarray as xr

from solver.history import (
    CH_INNER_SPEED,
    CH_MISALIGNMENT,
    CH_MISALIGNMENT_AXIS,
    CH_MOMENT_AXIS,
    CH_OUTER_SPEED,
    CH_RADIAL_LOAD_ANGLE,
    CH_TILTING_MOMENT,
    CHANNEL_NAMES,
    FRAME_INNER_RING,
    N_CHANNELS,
    event_times,
)
from solver.inputs import operating_at
from solver.models.quasistatic.result import start_variables
from solver.physics.hertz import truncation_margin
from solver.physics.traction import LAW_RHEOLOGY, LAW_SLIP_CURVE
from solver.results.dataset import build_result, with_data_variables
from solver.results.energy import energy_balance
from solver.results.estimates import with_estimates
from solver.results.phases import phase_attributes
from solver.results.skidding import skidding_variables
from solver.results.summary import trajectory_summary
from solver.results.variables import COORDINATES, variable

from . import layout as L
from .integrate import stepper
from .observe import applied_load_work, channel_series, observe

_TWO_PI = 2.0 * np.pi
#: operating inputs stored in degree (results-schema.md)
ANGLE_CHANNELS = ("radial_load_angle", "misalignment", "misalignment_axis", "moment_axis")

TRACTION_LAW_NAMES = {
    LAW_RHEOLOGY: "rheology (Barus viscosity, Eyring + film elasticity, limiting shear stress)",
    LAW_SLIP_CURVE: "ADORE-type slip curve",
}


def _degrees(v):
    return np.degrees(v)


def _azimuth_degrees(v):
    return np.degrees(v % _TWO_PI) % 360.0


def _clip_negative(v):
    return np.maximum(v, 0.0)


#: Per-contact results variables of the dynamic model: name (a key of the registry
#: solver.results.variables, which gives dims, units and meaning) -> (first slot of the contact
#: record, layout ``K_*``; number of slots, 1 or 3 for an ``axis`` vector; conversion of the stored
#: SI value to the registry's units, or None). Adding a per-contact output: write its slot in the
#: kernel (layout + kernels.py), one line here, one entry in the registry.
CONTACT_OUTPUTS = {
    "contact_load": (L.K_LOAD, 1, None),
    "contact_angle": (L.K_ANGLE, 1, _degrees),
    "contact_deflection": (L.K_DEFLECTION, 1, _clip_negative),
    "ellipse_semi_major": (L.K_SEMI_MAJOR, 1, None),
    "ellipse_semi_minor": (L.K_SEMI_MINOR, 1, None),
    "max_pressure": (L.K_PMAX, 1, None),
    "raceway_azimuth": (L.K_AZIMUTH, 1, _azimuth_degrees),
    "raceway_contact_point": (L.K_POINT, 3, None),
    "ball_latitude": (L.K_LATITUDE, 1, _degrees),
    "ball_longitude": (L.K_LONGITUDE, 1, _degrees),
    "spin_to_roll": (L.K_SPIN_TO_ROLL, 1, None),
    "sliding_speed": (L.K_SLIDE, 1, None),
    "film_thickness": (L.K_FILM, 1, None),
    "contact_heat": (L.K_POWER_ROLLING, 1, None),  # completed in contact_outputs
}

#: Loss sources per ball (registry dimension ``ball_loss_source``) and in total (``loss_source``).
BALL_LOSS_SOURCES = ("rolling", "sliding", "spin", "drag", "cage_pocket")
LOSS_SOURCES = BALL_LOSS_SOURCES + ("cage_land", "cage_drag")


def contact_outputs(records: np.ndarray) -> dict:
    """Data variables (dims, values) of :data:`CONTACT_OUTPUTS` from the records (S, Z, 2, K)."""
    tc = ("time", "ball", "race")
    data = {}
    for name, (slot, size, convert) in CONTACT_OUTPUTS.items():
        if size == 1:
            values, dims = records[..., slot], tc
        else:
            values, dims = records[..., slot : slot + size], tc + ("axis",)
        data[name] = (dims, convert(values) if convert is not None else values.copy())
    # heat generated in each contact: rolling resistance + sliding + spin
    heat = records[..., L.K_POWER_ROLLING] + records[..., L.K_POWER_SLIDING]
    data["contact_heat"] = (tc, heat + records[..., L.K_POWER_SPIN])
    return data


def loss_outputs(records: np.ndarray, balls: np.ndarray, bearing: np.ndarray) -> dict:
    """Power losses by source per ball and in total, friction torque and drive power."""
    per_ball = np.stack(
        [
            records[..., L.K_POWER_ROLLING].sum(axis=-1),
            records[..., L.K_POWER_SLIDING].sum(axis=-1),
            records[..., L.K_POWER_SPIN].sum(axis=-1),
            balls[..., L.BO_DRAG_POWER],
            balls[..., L.BO_POCKET_POWER],
        ],
        axis=-1,
    )
    cage = bearing[:, [L.RO_LAND_POWER, L.RO_CAGE_DRAG_POWER]]  # order of LOSS_SOURCES
    total = np.concatenate((per_ball.sum(axis=1), cage), axis=-1)
    return {
        "ball_power_loss": (("time", "ball", "ball_loss_source"), per_ball),
        "power_loss": (("time", "loss_source"), total),
        "total_power_loss": (("time",), total.sum(axis=-1)),
        "friction_torque": (("time",), bearing[:, L.RO_FRICTION_TORQUE].copy()),
        "drive_power": (("time",), bearing[:, L.RO_DRIVE_POWER].copy()),
    }


def kinetic_energy(states: np.ndarray, par) -> np.ndarray:
    """Kinetic energy [J] of every moving body of the model at each stored state (S, n) -> (S,).

    Balls: translation and rotation (a sphere: one inertia about every axis). Cage (when
    modelled): translation, rotation about its axis and tilts (polar and diametral inertia).
    Inner ring: translations when they are degrees of freedom, tilts when they are free. The
    rings' rotations are imposed at constant speed: their kinetic energy does not change and is
    left out. Inertial frame, velocities in m/s and rad/s.
    """
    z = int(par.ball_count)
    energy = np.zeros(states.shape[0])
    for j in range(z):
        base = L.ball_base(j)
        vel = states[:, base + L.B_VEL : base + L.B_VEL + 3]
        omega = states[:, base + L.B_OMEGA : base + L.B_OMEGA + 3]
        energy += 0.5 * par.ball_mass * np.sum(vel**2, axis=1)
        energy += 0.5 * par.ball_inertia * np.sum(omega**2, axis=1)
    if par.cage:
        cb = L.cage_base(z)
        vel = states[:, cb + L.C_VEL : cb + L.C_VEL + 3]
        tilt_rate = states[:, cb + L.C_TILT_RATE : cb + L.C_TILT_RATE + 2]
        energy += 0.5 * par.cage_mass * np.sum(vel**2, axis=1)
        energy += 0.5 * par.cage_polar_inertia * states[:, cb + L.C_SPEED] ** 2
        energy += 0.5 * par.cage_diametral_inertia * np.sum(tilt_rate**2, axis=1)
    rb = L.ring_base(z)
    if par.ring_free:
        vel = states[:, rb + L.R_VEL : rb + L.R_VEL + 3]
        energy += 0.5 * par.ring_mass * np.sum(vel**2, axis=1)
    if par.tilt_mode == L.TILT_FREE:
        tilt_rate = states[:, rb + L.R_TILT_RATE : rb + L.R_TILT_RATE + 2]
        energy += 0.5 * par.ring_diametral_inertia * np.sum(tilt_rate**2, axis=1)
    return energy


def truncation_margins(geometry, angle: np.ndarray, semi_major: np.ndarray) -> np.ndarray:
    """Margin [degree] between the ellipse edge and the loaded shoulder, per race
    (solver.physics.hertz.truncation_margin); NaN where the case gives no shoulder
    (results-schema.md). ``angle`` [rad] and ``semi_major`` [m] have a last axis
    race = (inner, outer)."""
    out = np.empty(angle.shape)
    for k, race in enumerate(("inner", "outer")):
        try:
            out[..., k] = truncation_margin(geometry, angle[..., k], semi_major[..., k], race)
        except ValueError:  # shoulder not on the groove arc: no margin can be stated
            out[..., k] = np.nan
    return out


def build_dataset(
    inputs,
    options,
    history,
    par,
    quad,
    times,
    states,
    period,
    complete,
    stop_reason,
    stats,
    start=None,
):
    """Dataset of the dynamic run under the operating history ``history``
    (:class:`solver.history.HistoryRecord`) from the stored states (S, n) at ``times`` (S,), with
    the trajectory metrics and the settling window of :mod:`solver.results.summary` stored in it,
    and the quasi-static solution ``start`` (a :class:`QuasiStaticSolution`, None when there is
    none) as its ``quasistatic_*`` variables."""
    ds, imposed, summary_point = time_series(
        inputs,
        options,
        history,
        par,
        quad,
        times,
        states,
        period,
        complete,
        stop_reason,
        stats,
        start,
    )
    metrics = trajectory_summary(ds, options.analysis_skip_fraction)
    ds = ds.assign(metrics.data_vars).assign_coords(frame=metrics["frame"])
    ds = with_inputs_over_time(ds, history, imposed)
    ds = ds.assign(skidding_variables(ds))  # at each sample's ring speeds
    ds.attrs["analysed_window"] = metrics.attrs["analysed_window"]
    if inputs.history is not None:  # the phases between the history's events (results-schema.md)
        ds.attrs.update(phase_attributes(inputs.history, float(times[-1])))
    balance = energy_balance(ds, float(metrics["analysis_start_time"]))
    spec = variable("energy_balance_residual")
    ds["energy_balance_residual"] = ((), np.float64(balance.residual), spec.attrs())
    return with_estimates(ds, inputs, summary_point)  # the final phase, as the summary


def chunk_dataset(
    inputs, options, history, par, quad, times, states, period, stats, channels, start=None
):
    """The per-sample part of :func:`build_dataset`: every variable over ``time`` and the
    ``quasistatic_*`` variables of ``start``, without what is summed up over a whole run (the
    trajectory metrics, the analysed window, the energy-balance residual, the friction
    estimates); the inputs of ``channels`` (channel constants) as data variables over ``time``.
    ``complete`` = 0, ``stop_reason`` = "live" (a chunk of a live simulation)."""
    ds, imposed, _ = time_series(
        inputs, options, history, par, quad, times, states, period, False, "live", stats, start
    )
    ds = with_inputs_over_time(ds, history, imposed, channels)
    return with_data_variables(ds, skidding_variables(ds))


def time_series(
    inputs,
    options,
    history,
    par,
    quad,
    times,
    states,
    period,
    complete,
    stop_reason,
    stats,
    start=None,
):
    """(the Dataset of every per-sample variable of the run and the ``quasistatic_*`` variables
    of ``start`` when given, the imposed inputs of :func:`imposed_inputs`, the operating point
    of its coordinates)."""
    z = int(par.ball_count)
    s_count = states.shape[0]
    records = np.zeros((s_count, z, 2, L.N_CONTACT_RECORD))
    balls_out = np.zeros((s_count, z, L.N_BALL_OUTPUT))
    bearing_out = np.zeros((s_count, L.N_BEARING_OUTPUT))
    observe(states, times, history, par, quad, records, balls_out, bearing_out)
    imposed = imposed_inputs(history, times, states[:, L.ring_base(z) + L.R_PHI_INNER])
    pocket = balls_out[..., L.BO_POCKET_FORCE]
    balls = np.stack(
        [states[:, L.ball_base(j) : L.ball_base(j) + L.BALL_STRIDE] for j in range(z)], axis=1
    )
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
    relative = imposed[CH_INNER_SPEED] - imposed[CH_OUTER_SPEED]
    sgn = np.where(relative >= 0.0, -1.0, 1.0)[:, None]
    attitude = np.degrees(np.arctan2(-sgn * w_r, sgn * w_x))
    angle = records[..., L.K_ANGLE]
    semi_major = records[..., L.K_SEMI_MAJOR]
    tilt = states[:, rb + L.R_TILT : rb + L.R_TILT + 2].copy()
    if par.tilt_mode == L.TILT_TURNING_WITH_RING:
        # tilt turning with the ring: R = R_x(phi) R(g) = R(R_x(phi) g) R_x(phi), so the tilt
        # vector relative to the outer ring (inertial axes) is g turned by the ring angle phi
        phi = states[:, rb + L.R_PHI_INNER]
        gy, gz = tilt[:, 0].copy(), tilt[:, 1].copy()
        tilt[:, 0] = gy * np.cos(phi) - gz * np.sin(phi)
        tilt[:, 1] = gy * np.sin(phi) + gz * np.cos(phi)
    tc = ("time", "ball", "race")
    tb = ("time", "ball")
    data = contact_outputs(records) | loss_outputs(records, balls_out, bearing_out)
    data |= {
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
        "kinetic_energy": (("time",), kinetic_energy(states, par)),
        "elastic_energy": (("time",), bearing_out[:, L.RO_ELASTIC_ENERGY].copy()),
        "load_work": (("time",), load_work(states, times, history, par)),
    }
    attrs = {
        "stop_reason": stop_reason,
        "gravity": f"{options.gravity:g} m/s^2 along -z of the inertial frame",
        "traction_model": (
            f"ellipse-integrated, {TRACTION_LAW_NAMES[par.traction_law]}; rolling resistance "
            "(EHL inlet + hysteresis) and oil-air drag on the balls and cage"
        )
        if options.traction
        else "off (frictionless: no traction, rolling resistance or drag)",
        "damping_ratio": float(options.damping_ratio),
        "cage_model": "6 DOF (translations, rotation, tilts)" if options.cage else "off",
        "lubricant": inputs.lubricant.description,
        "integrator": _integrator_note(options),
        "steps": stats.steps,
        "rejected_steps": stats.rejected,
        "rhs_evaluations": stats.rhs_evaluations,
        "wall_time_s": float(stats.wall_time),
        "shaft_period_s": float(period),
    }
    if start is not None:
        data.update(start_variables(start))
    # the summary reads the operating point from the coordinates: along a history, that of the
    # end of the run (its final phase, where the settling test puts the analysed window when the
    # final phase holds its inputs); the inputs that vary then become data variables over time
    summary_point = (
        inputs.operating if inputs.history is None else operating_at(inputs, float(times[-1]))
    )
    ds = build_result(
        "dynamic",
        data,
        inputs.geometry,
        summary_point,
        case=inputs.case_text,
        times=times,
        complete=complete,
        attrs=attrs,
    )
    return ds, imposed, summary_point


def load_work(states: np.ndarray, times: np.ndarray, history, par) -> np.ndarray:
    """Work [J] done since t = 0 by the applied loads of the operating history ``history`` and
    gravity at each stored state (S, n) at ``times`` (S,) [s]: the Stieltjes sum of F . dx over the
    inner ring's displacement (where its translations are free) and M . d(tilt) (free tilt), F and M
    at the middle of each piece, the pieces being the sample intervals cut at the history's event
    times (a load step does its work on the side of the jump it acts on; the position at an event is
    interpolated linearly), plus -m g dz of every moving body. Not F . v sampled: the ring's contact
    vibration, far faster than the output samples, would alias into it."""
    z = int(par.ball_count)
    rb = L.ring_base(z)
    cb = L.cage_base(z)
    events = event_times(history, float(times[0]), float(times[-1]))
    work = np.zeros(times.size)
    applied_load_work(states, times, history, par, events, work)
    ring = states[:, rb + L.R_POS : rb + L.R_POS + 3]
    heights = np.zeros(times.size)
    for j in range(z):
        heights += par.ball_mass * states[:, L.ball_base(j) + L.B_POS + 2]
    if par.ring_free:
        heights += par.ring_mass * ring[:, 2]
    if par.cage:
        heights += par.cage_mass * states[:, cb + L.C_POS + 2]
    return work - par.gravity * (heights - heights[0])


def imposed_inputs(history, times: np.ndarray, inner_angle: np.ndarray) -> np.ndarray:
    """(N_CHANNELS, S) every channel of ``history`` at ``times`` [s] (SI, rad); the radial load's
    azimuth in space (a load turning with the inner ring: its angle in the ring plus the ring's
    spin angle ``inner_angle`` (S,) [rad])."""
    values = np.empty((N_CHANNELS, times.size))
    channel_series(history, np.ascontiguousarray(times, dtype=np.float64), values)
    if history.radial_load_frame == FRAME_INNER_RING:
        values[CH_RADIAL_LOAD_ANGLE] += inner_angle
    return values


def varying_channels(history) -> list[int]:
    """The channels of ``history`` that vary in time (a table of several values, a sine or a
    rate; the radial load's azimuth when it turns with the inner ring). Under a free tilt the
    misalignment channels, under an imposed tilt the moment channels, are not inputs."""
    unused = (
        (CH_MISALIGNMENT, CH_MISALIGNMENT_AXIS)
        if history.tilt_free
        else (CH_TILTING_MOMENT, CH_MOMENT_AXIS)
    )
    out = []
    for c in range(N_CHANNELS):
        if c in unused:
            continue
        n = int(history.counts[c])
        values = history.values[c, :n]
        varies = bool(np.any(values != values[0])) or history.amplitude[c] != 0.0
        varies = varies or history.rate[c] != 0.0
        if c == CH_RADIAL_LOAD_ANGLE and history.radial_load_frame == FRAME_INNER_RING:
            varies = True
        if varies:
            out.append(c)
    return out


def with_inputs_over_time(ds, history, imposed: np.ndarray, channels=None):
    """``ds`` with every operating input that varies in ``history`` (or of ``channels``, channel
    constants) as a data variable over ``time`` in place of its scalar coordinate (same name,
    units and meaning; angles in degree): ``imposed`` from :func:`imposed_inputs`."""
    if channels is None:
        channels = varying_channels(history)
    if not channels:
        return ds
    names = [CHANNEL_NAMES[c] for c in channels]
    added = {}
    for c, name in zip(channels, names, strict=True):
        values = imposed[c]
        if name in ANGLE_CHANNELS:
            values = np.degrees(values)
        added[name] = xr.Variable(("time",), values, COORDINATES[name].attrs())
    return with_data_variables(ds, added, dropped=names)


def _integrator_note(options) -> str:
    """Method, step control and tolerance of the run, for the Dataset attrs."""
    return f"{stepper(options.method).note}, tolerance {options.tolerance:g}"
