"""The Dataset of a dynamic run of a bearing set (results-schema.md, "Dynamic results of a bearing
set").

Every single-bearing dynamic variable (:func:`.output.build_dataset` on the bearing's slice of the
states, its own frame) is stacked along a ``bearing`` dimension as in the quasi-static set's
Dataset (:func:`solver.models.quasistatic.set_result.stack_bearings`). The shaft's variables are
in the shaft frame. ``energy_balance_residual`` is the whole set's (a bearing's own balance lacks
the work the shaft does on its inner ring): the bearings' drive power, losses, kinetic and elastic
energies and gravity's work summed, plus the work of the external load on the shaft; under a spring
preload also the floating outer rings' kinetic energy, the kinetic energy the spring side's bodies
have from their frame's motion (their states are relative to their outer ring,
:mod:`.set_kernels`), and the spring's work on the outer rings.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import xarray as xr

from solver.models.quasistatic.set_result import stack_bearings
from solver.results.energy import energy_balance
from solver.results.estimates import with_estimates
from solver.results.life import rating_life
from solver.results.variables import Variable, variable

from . import layout as L
from .kernels import rhs_into, rhs_work
from .output import build_dataset

_SET = ("dynamic",)

#: The dynamic set's own variables (shaft frame), by name: dims (time last), units, meaning.
SET_DYNAMIC_VARIABLES: dict[str, Variable] = {
    "shaft_offset": Variable(
        ("axis",),
        "m",
        "shaft displacement",
        "displacement of the shaft at the load point (set.load.position_mm), shaft frame",
        _SET,
    ),
    "shaft_tilt": Variable(
        ("tilt_axis",),
        "degree",
        "shaft tilt",
        "tilt of the shaft about y and z (small rotation vector), shaft frame",
        _SET,
    ),
    "bearing_force": Variable(
        ("bearing", "axis"),
        "N",
        "force of the bearing on the shaft",
        "force of the bearing's balls (and an inner-ring-guided cage's land) on its inner ring, "
        "shaft frame",
        _SET,
    ),
    "bearing_moment": Variable(
        ("bearing", "tilt_axis"),
        "N m",
        "moment of the bearing on the shaft",
        "moment (about y, z) of the bearing's balls on its inner ring about the ring's centre on "
        "its ball-centre plane, shaft frame",
        _SET,
    ),
    "bearing_axial_load": Variable(
        ("bearing",),
        "N",
        "axial load of the bearing",
        "axial load the bearing carries along its own direction (positive: pushed onto its "
        "contact line)",
        _SET,
    ),
    "bearing_radial_load": Variable(
        ("bearing",),
        "N",
        "radial load of the bearing",
        "radial force between the bearing's balls and its inner ring",
        _SET,
    ),
    "shaft_net_force": Variable(
        ("axis",),
        "N",
        "net force on the shaft",
        "sum of the external force and the bearings' forces on the shaft (gravity and inertia "
        "excluded), shaft frame",
        _SET,
    ),
    "spring_shift": Variable(
        (),
        "m",
        "spring side outer ring shift",
        "axial shift w of the spring side's floating outer rings, along those bearings' own "
        "direction: their inner rings' approach is w plus the shaft's displacement in their own "
        "frame, as the quasi-static set's spring_shift (the outer rings move by -w); present "
        "with a spring preload",
        _SET,
    ),
    "spring_force": Variable(
        (),
        "N",
        "spring force",
        "constant force of the spring on the floating outer rings of the spring side, pushing "
        "them onto their balls; present with a spring preload",
        _SET,
    ),
}


def _var(name: str, dims: tuple, values) -> xr.Variable:
    spec = SET_DYNAMIC_VARIABLES[name]
    return xr.Variable(dims, np.asarray(values, dtype=float), spec.attrs())


def ring_loads(member, states: np.ndarray, times: np.ndarray) -> np.ndarray:
    """(S, 6) force [N] and moment [N m] of a bearing's balls on its inner ring (own frame, about
    the ring's centre) at each stored state of the bearing's slice ``states`` (S, n)."""
    par = member.par
    z = int(par.ball_count)
    work = rhs_work(z)
    rec_i = np.zeros((z, L.N_CONTACT_RECORD))
    rec_o = np.zeros((z, L.N_CONTACT_RECORD))
    pocket = np.zeros(z)
    dydt = np.zeros(states.shape[1])
    out = np.empty((states.shape[0], 6))
    for k in range(states.shape[0]):
        y = np.ascontiguousarray(states[k])
        rhs_into(
            y,
            float(times[k]),
            member.history,
            par,
            member.quad,
            dydt,
            rec_i,
            rec_o,
            pocket,
            work,
            True,
        )
        out[k] = work.ring_load
    return out


def rated_at_carried_load(ds: xr.Dataset, inputs, loads: np.ndarray) -> xr.Dataset:
    """A bearing's Dataset ``ds`` (its own frame) with its operating loads those its balls carry,
    as in the quasi-static set: ``axial_load``, ``radial_load`` and ``radial_load_angle`` are the
    means over the analysed window of the load on its inner ring (``loads`` (S, 6), the balls'
    force and moment on the ring, own frame, from :func:`ring_loads`), and the life metrics and
    friction estimates that read them are computed at those loads. The bearing's own inputs hold
    no applied load (the set's loads act on the shaft)."""
    times = np.asarray(ds["time"].values, dtype=float)
    first = int(np.searchsorted(times, float(ds["analysis_start_time"]), side="left"))
    carried = -np.asarray(loads[first:, :3], dtype=float)  # the load the ring puts on the balls
    axial = float(np.mean(carried[:, 0]))
    radial = float(np.mean(np.hypot(carried[:, 1], carried[:, 2])))
    direction = carried[:, 1:3].mean(axis=0)
    angle = float(np.arctan2(direction[1], direction[0])) if np.any(direction) else 0.0
    note = (
        "a bearing of a set: the mean over the analysed window of the load its balls carry "
        "(the set's loads act on the shaft)"
    )
    coords = {}
    for name, value in (
        ("axial_load", axial),
        ("radial_load", radial),
        ("radial_load_angle", float(np.degrees(angle))),
    ):
        coords[name] = xr.Variable((), np.float64(value), ds[name].attrs | {"note": note})
    ds = ds.assign_coords(coords)
    operating = dataclasses.replace(
        inputs.operating, axial_load=axial, radial_load=radial, radial_load_angle=angle
    )
    ds = ds.assign(rating_life(ds, first).data_vars)
    return with_estimates(ds, inputs, operating)


def to_shaft(sign: float, loads: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(force (S, 3), moment about y, z (S, 2)) in the shaft frame from a bearing's own-frame
    ring loads ``loads`` (S, 6)."""
    force = loads[:, :3] * np.array([sign, 1.0, 1.0])
    moment = sign * loads[:, 4:6]
    return force, moment


def floating_energy(members, states: np.ndarray, shaft) -> tuple[np.ndarray, np.ndarray]:
    """(kinetic energy [J] the bearings' series lack, work of the spring [J] since the first
    sample) of the floating outer rings of a spring preload at the stored set states (S, n);
    zeros without one. A floating bearing's bodies (balls, cage, inner ring) have their velocities
    stored relative to its outer ring, which moves at -w' along x: each body k of mass m_k and
    stored axial velocity v_k has (v_k - w')^2 m_k / 2 of kinetic energy instead of v_k^2 m_k / 2;
    the outer rings (mass M_o) have M_o w'^2 / 2; the spring force F_s, on the rings along -x of
    their frame, does F_s (w - w_0)."""
    size = states.shape[0]
    if shaft.spring_slot < 0:
        return np.zeros(size), np.zeros(size)
    w = states[:, shaft.spring_slot]
    rate = states[:, shaft.spring_slot + 1]
    kinetic = 0.5 * rate**2 / shaft.spring_mass_inverse
    for m in members:
        if not m.floating:
            continue
        par = m.par
        z = int(par.ball_count)
        sub = states[:, m.start : m.stop]
        rb = L.ring_base(z)
        mass = z * par.ball_mass + par.ring_mass
        momentum = par.ring_mass * sub[:, rb + L.R_VEL]
        for j in range(z):
            momentum = momentum + par.ball_mass * sub[:, L.ball_base(j) + L.B_VEL]
        if par.cage:
            mass += par.cage_mass
            momentum = momentum + par.cage_mass * sub[:, L.cage_base(z) + L.C_VEL]
        kinetic = kinetic - rate * momentum + 0.5 * mass * rate**2
    return kinetic, shaft.spring_force * (w - w[0])


def set_energy_balance(
    datasets, applied, shaft_states, times, period, start_time, floating=(0.0, 0.0)
):
    """:func:`solver.results.energy.energy_balance` of the whole set: the bearings' series summed
    (their kinetic energies hold the rings', i.e. the shaft's), plus the work of the constant
    external load ``applied`` (Fx, Fy, Fz, My, Mz) over the shaft's displacement, plus
    ``floating`` (:func:`floating_energy`: kinetic energy and work of a spring preload's floating
    outer rings, (S,) each)."""
    total = {
        name: sum(np.asarray(ds[name].values, dtype=float) for ds in datasets)
        for name in (
            "drive_power",
            "total_power_loss",
            "kinetic_energy",
            "elastic_energy",
            "load_work",
        )
    }
    u = np.concatenate(
        (
            shaft_states[:, L.R_POS : L.R_POS + 3],
            shaft_states[:, L.R_TILT : L.R_TILT + 2],
        ),
        axis=1,
    )
    total["load_work"] = total["load_work"] + (u - u[0]) @ applied + floating[1]
    total["kinetic_energy"] = total["kinetic_energy"] + floating[0]
    ds = xr.Dataset(
        {name: (("time",), values) for name, values in total.items()},
        coords={"time": times},
        attrs={"shaft_period_s": float(period)},
    )
    return energy_balance(ds, start_time)


def set_dynamic_dataset(
    given, qs, members, shaft, options, times, states, period, complete, stop_reason, stats
) -> xr.Dataset:
    """The set run's Dataset from the stored set states (S, n) at ``times`` (S,); ``shaft`` the
    run's :class:`.set_kernels.SetShaft`."""
    datasets, ring_load_series = [], []
    for m in members:
        sub = np.ascontiguousarray(states[:, m.start : m.stop])
        loads = ring_loads(m, sub, times)
        ring_load_series.append(loads)
        own = build_dataset(
            m.inputs,
            options,
            m.history,
            m.par,
            m.quad,
            times,
            sub,
            period,
            complete,
            stop_reason,
            stats,
            m.quasistatic,
        )
        datasets.append(rated_at_carried_load(own, m.inputs, loads))
    shaft_states = states[:, members[-1].stop : members[-1].stop + L.RING_SIZE]
    forces, moments, axial, radial = [], [], [], []
    for m, loads in zip(members, ring_load_series, strict=True):
        force, moment = to_shaft(m.sign, loads)
        # the bearing's force on the shaft is that of its balls on its ring
        forces.append(force)
        moments.append(moment)
        axial.append(-m.sign * force[:, 0])
        radial.append(np.hypot(force[:, 1], force[:, 2]))
    applied = np.asarray(given.applied, dtype=float)
    net = sum(forces) + applied[:3]
    bearing_set = given.bearing_set
    coords = {
        "bearing": xr.Variable(
            "bearing", [m.name for m in members], {"long_name": "bearing of the set"}
        ),
        "bearing_position": xr.Variable(
            "bearing",
            [e.entry.position_mm * 1e-3 for e in qs.members],
            {"units": "m", "long_name": "axial position of the bearing's ball-centre plane"},
        ),
        "bearing_direction": xr.Variable(
            "bearing",
            [e.entry.direction for e in qs.members],
            {"long_name": "axial direction of the shaft thrust the bearing carries"},
        ),
        "load_position": xr.Variable(
            (),
            bearing_set.load_position_mm * 1e-3,
            {"units": "m", "long_name": "axial position of the external loads on the shaft"},
        ),
    }
    data = {
        "shaft_offset": _var("shaft_offset", ("time", "axis"), shaft_states[:, L.R_POS : 3]),
        "shaft_tilt": _var(
            "shaft_tilt",
            ("time", "tilt_axis"),
            np.degrees(shaft_states[:, L.R_TILT : L.R_TILT + 2]),
        ),
        "bearing_force": _var("bearing_force", ("bearing", "time", "axis"), np.stack(forces)),
        "bearing_moment": _var(
            "bearing_moment", ("bearing", "time", "tilt_axis"), np.stack(moments)
        ),
        "bearing_axial_load": _var("bearing_axial_load", ("bearing", "time"), np.stack(axial)),
        "bearing_radial_load": _var("bearing_radial_load", ("bearing", "time"), np.stack(radial)),
        "shaft_net_force": _var("shaft_net_force", ("time", "axis"), net),
    }
    spring = shaft.spring_slot >= 0
    if spring:
        data["spring_shift"] = _var("spring_shift", ("time",), states[:, shaft.spring_slot])
        data["spring_force"] = _var("spring_force", (), shaft.spring_force)
    ds = stack_bearings(datasets, coords, data)
    start_time = max(float(d["analysis_start_time"]) for d in datasets)
    balance = set_energy_balance(
        datasets,
        applied,
        shaft_states,
        times,
        period,
        start_time,
        floating_energy(members, states, shaft),
    )
    residual = np.nan if balance is None else balance.residual
    spec = variable("energy_balance_residual")
    attrs = spec.attrs() | {
        "description": spec.description + " (the whole set: every bearing and the shaft)"
    }
    ds["energy_balance_residual"] = xr.Variable((), np.float64(residual), attrs)
    freedom = (
        "free in x, y, z, tilt_y, tilt_z"
        if bearing_set.misalignment_deg is None
        else "free in x, y, z, its tilt held at set.misalignment_deg"
    )
    rings = "outer rings fixed"
    if spring:
        floating = ", ".join(m.name for m in members if m.floating)
        rings = (
            f"the outer rings of {floating} floating axially as one body of "
            f"{1.0 / shaft.spring_mass_inverse:.4g} kg (estimated) under the spring force, "
            "the other outer rings fixed"
        )
    ds.attrs.update(
        {
            "model": "dynamic",
            "bearing_set": bearing_set.describe(),
            "case": given.inputs.case_text,
            "stop_reason": stop_reason,
            "complete": int(complete),
            "set_model": (
                f"rigid shaft {freedom} at the load point, spinning at the inner-ring speed; its "
                f"mass and inertia those of the inner rings; {rings}; each bearing's "
                "balls and cage as the single-bearing model"
            ),
            "preload_offset_m": float(qs.offset),
        }
    )
    return ds
