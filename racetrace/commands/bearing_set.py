"""What ``racetrace check`` and ``racetrace solve`` print for a bearing set (a case with a
``[set]`` table): the set as described, and its quasi-static result per bearing."""

from __future__ import annotations

import math

import numpy as np


def _num(value: float, digits: int = 4) -> str:
    value = float(value)
    return f"{0.0 if abs(value) < 1e-12 else value:.{digits}g}"


def describe_set(case) -> list[str]:
    """Lines describing the set of ``case`` (its arrangement, bearings, preload and loads)."""
    s = case.bearing_set
    force = ", ".join(_num(v) for v in s.load_force_N)
    moment = ", ".join(_num(v) for v in s.load_moment_Nm)
    lines = [
        f"set:       {s.describe()}",
        f"           loads on the shaft at {_num(s.load_position_mm)} mm: force [{force}] N, "
        f"moment [{moment}] N m",
    ]
    for b in s.bearings:
        geometry = b.case.bearing
        lines.append(
            f"           {b.name}: at {_num(b.position_mm)} mm, carries thrust towards "
            f"{b.direction}; {geometry.designation or 'bearing'} ({b.source}), "
            f"{geometry.ball_count} balls of {_num(geometry.ball_diameter_mm)} mm"
        )
    return lines


def set_table(ds) -> str:
    """The set's quasi-static result as a readable table (units in the headers)."""
    lines = [
        f"{ds.attrs.get('title', '')}",
        f"{ds.attrs.get('bearing_set', '')}; ball speeds: {ds.attrs.get('kinematics', '')}",
        "",
        f"{'bearing':>12} {'pos mm':>8} {'dir':>4} {'Fa N':>10} {'Fr N':>10} "
        f"{'Qi max N':>10} {'a_i deg':>8} {'a_o deg':>8} {'loaded':>7} {'p max GPa':>10}",
    ]
    for index, name in enumerate(ds["bearing"].values):
        one = ds.isel(bearing=index)
        count = int(one["ball_count"])
        load = one["contact_load"].values[:count]
        angle = one["contact_angle"].values[:count]
        loaded = load[:, 0] > 0.0
        heavy = int(np.argmax(load[:, 0]))
        lines.append(
            f"{name!s:>12} {float(one['bearing_position']) * 1e3:8.1f} "
            f"{one['bearing_direction'].item():>4} {float(one['bearing_axial_load']):10.1f} "
            f"{float(one['bearing_radial_load']):10.1f} {load[:, 0].max():10.2f} "
            f"{angle[heavy, 0]:8.2f} {angle[heavy, 1]:8.2f} {int(loaded.sum()):3d}/{count:<3d} "
            f"{np.nanmax(one['max_pressure'].values[:count]) * 1e-9:10.3f}"
        )
    offset = ds["shaft_offset"].values * 1e6
    tilt = ds["shaft_tilt"].values
    lines += [
        "",
        f"shaft at the load point: offset [{', '.join(f'{v:.3f}' for v in offset)}] um, tilt "
        f"[{', '.join(f'{v:.5f}' for v in tilt)}] deg",
        f"preload offset {float(ds['preload_offset']) * 1e6:.3f} um; "
        f"spring shift {float(ds['spring_shift']) * 1e6:.3f} um",
        f"set stiffness at the load point: axial {float(ds['axial_stiffness']) * 1e-6:.2f} N/um, "
        f"radial {float(ds['radial_stiffness']) * 1e-6:.2f} N/um, tilt "
        f"{float(ds['tilt_stiffness']) * math.pi / 180:.1f} N m/deg",
    ]
    for name in ("axial_load_share", "radial_load_share"):
        if name in ds:
            shares = ", ".join(
                f"{b!s} {v:.3f}" for b, v in zip(ds["bearing"].values, ds[name].values, strict=True)
            )
            lines.append(f"{name.replace('_', ' ')}: {shares}")
    return "\n".join(lines)


def set_summary(ds) -> dict:
    """The set's result as plain JSON values (SI units, angles in degree)."""
    bearings = []
    for index, name in enumerate(ds["bearing"].values):
        one = ds.isel(bearing=index)
        count = int(one["ball_count"])
        load = one["contact_load"].values[:count]
        bearings.append(
            {
                "name": str(name),
                "position_m": float(one["bearing_position"]),
                "direction": str(one["bearing_direction"].item()),
                "axial_load_N": float(one["bearing_axial_load"]),
                "radial_load_N": float(one["bearing_radial_load"]),
                "max_inner_contact_load_N": float(load[:, 0].max()),
                "loaded_balls": int((load[:, 0] > 0.0).sum()),
                "ball_count": count,
                "force_on_shaft_N": [float(v) for v in one["bearing_force"].values],
                "moment_on_shaft_Nm": [float(v) for v in one["bearing_moment"].values],
                "stiffness": one["bearing_stiffness"].values.tolist(),
            }
        )
    out = {
        "title": ds.attrs.get("title", ""),
        "bearing_set": ds.attrs.get("bearing_set", ""),
        "ball_speeds": ds.attrs.get("kinematics", ""),
        "bearings": bearings,
        "shaft_offset_m": [float(v) for v in ds["shaft_offset"].values],
        "shaft_tilt_deg": [float(v) for v in ds["shaft_tilt"].values],
        "preload_offset_m": float(ds["preload_offset"]),
        "spring_shift_m": float(ds["spring_shift"]),
        "set_stiffness": ds["set_stiffness"].values.tolist(),
        "axial_stiffness_N_m": float(ds["axial_stiffness"]),
        "radial_stiffness_N_m": float(ds["radial_stiffness"]),
        "tilt_stiffness_Nm_rad": float(ds["tilt_stiffness"]),
    }
    for name in ("axial_load_share", "radial_load_share"):
        if name in ds:
            out[name] = [float(v) for v in ds[name].values]
    return out


def _dynamic_bearing(ds, index: int) -> dict:
    """Bearing ``index`` of a dynamic set's Dataset: its single-bearing result (``one``) and its
    loads on the shaft averaged over its analysed window (N)."""
    from solver import bearing_result

    one = bearing_result(ds, index)
    start = float(one.racetrace.metric("analysis_start_time"))
    window = ds.isel(bearing=index).sel(time=slice(start, None))
    return {
        "one": one,
        "axial_load_N": float(window["bearing_axial_load"].mean("time")),
        "radial_load_N": float(window["bearing_radial_load"].mean("time")),
    }


def _dynamic_values(one) -> dict:
    """A bearing's cage slip (fractions) and mean power loss [W] (NaN where not available)."""
    metric = one.racetrace.metric
    return {
        "cage_slip": float(metric("cage_slip")),
        "mean_instantaneous_cage_slip": float(metric("mean_instantaneous_cage_slip")),
        "cage_skids": bool(float(metric("cage_skids")) == 1.0),
        "mean_total_power_loss_W": float(metric("mean_total_power_loss")),
    }


def _reference_life(one) -> dict:
    """A bearing's reference rating life L10r (ISO/TS 16281, from its contact loads: million
    revolutions, hours) and the lives' notes. ISO 281's L10, computed at the window means of
    the loads the bearing carries, stays in the result file."""
    from racetrace.metrics import life_headline

    lives = life_headline(one)
    return {key: lives[key] for key in ("L10r_million_revolutions", "L10r_hours", "notes")}


def dynamic_set_text(ds) -> str:
    """The dynamic run of a set in readable lines: per bearing its loads, trajectory metrics,
    cage slip, power loss, mean friction torque and reference rating life; then a spring
    preload's force and the floating outer rings' shift; then the set's energy balance. The
    empirical torque estimates and ISO 281's L10 (at the window means of the loads each bearing
    carries) stay in the result file."""
    from racetrace.metrics import energy_text, metrics_text
    from solver import set_spring_preload

    lines = [f"{ds.attrs.get('bearing_set', 'bearing set')}"]
    for index, name in enumerate(ds["bearing"].values):
        bearing = _dynamic_bearing(ds, index)
        one = bearing["one"]
        values = _dynamic_values(one)
        lines += [
            "",
            f"{name!s} (at {float(ds['bearing_position'][index]) * 1e3:g} mm, carries "
            f"thrust towards {ds['bearing_direction'].values[index]}): axial load "
            f"{bearing['axial_load_N']:.1f} N, radial load {bearing['radial_load_N']:.1f} N "
            "(mean over its analysed window)",
        ]
        # the energy balance is the set's, printed once below
        lines += [line for line in metrics_text(one).splitlines() if not line.startswith("energy")]
        skids = " (the cage skids)" if values["cage_skids"] else ""
        lines.append(
            f"cage slip: {100.0 * values['cage_slip']:.3f} % of the epicyclic speed; "
            f"{100.0 * values['mean_instantaneous_cage_slip']:.3f} % of the rolling speed{skids}"
        )
        torque = float(one.racetrace.metric("mean_friction_torque"))
        lines.append(
            f"power loss: {values['mean_total_power_loss_W']:.4g} W, friction torque "
            f"{torque * 1e3:.4g} N mm (means over the analysed window)"
        )
        life = _reference_life(one)
        lines.append(
            f"L10r (ISO/TS 16281, contact loads): {life['L10r_million_revolutions']:.5g} million "
            f"revolutions = {life['L10r_hours']:.5g} h"
        )
        lines += [f"  note: {note}" for note in life["notes"]]
    spring = set_spring_preload(ds)
    if spring is not None:
        lines += [
            "",
            f"spring preload: {spring['spring_force_N']:g} N on the spring side's outer rings; "
            f"their shift {spring['spring_shift_m'] * 1e6:.3f} um (mean over the set's analysed "
            f"window, {spring['spring_shift_span_m'] * 1e6:.3f} um peak to peak)",
        ]
    lines += ["", f"the set: {energy_text(float(ds['energy_balance_residual']))}"]
    return "\n".join(lines)


def dynamic_set_summary(ds) -> dict:
    """The dynamic run of a set as plain JSON values (SI units, angles in degree; NaN as null):
    per bearing its loads, trajectory metrics, cage slip, power loss, mean friction torque and
    reference rating life (as :func:`dynamic_set_text`); the set's energy-balance residual; with
    a spring preload ``spring_force_N``, ``spring_shift_m`` and ``spring_shift_span_m``."""
    from racetrace.metrics import finite_or_none, metrics_json
    from solver import set_spring_preload

    bearings = []
    for index, name in enumerate(ds["bearing"].values):
        bearing = _dynamic_bearing(ds, index)
        one = bearing["one"]
        trajectory = metrics_json(one)
        trajectory.pop("energy_balance_residual", None)  # the set's, given once
        values = _dynamic_values(one)
        bearings.append(
            {
                "name": str(name),
                "position_m": float(ds["bearing_position"][index]),
                "direction": str(ds["bearing_direction"].values[index]),
                "axial_load_N": bearing["axial_load_N"],
                "radial_load_N": bearing["radial_load_N"],
                "trajectory": trajectory,
                "cage_slip": finite_or_none(values["cage_slip"]),
                "mean_instantaneous_cage_slip": finite_or_none(
                    values["mean_instantaneous_cage_slip"]
                ),
                "cage_skids": values["cage_skids"],
                "mean_total_power_loss_W": finite_or_none(values["mean_total_power_loss_W"]),
                "mean_friction_torque_N_m": finite_or_none(
                    float(one.racetrace.metric("mean_friction_torque"))
                ),
                "life": {
                    key: finite_or_none(value) if key != "notes" else value
                    for key, value in _reference_life(one).items()
                },
            }
        )
    out = {
        "bearing_set": ds.attrs.get("bearing_set", ""),
        "bearings": bearings,
        "energy_balance_residual": finite_or_none(float(ds["energy_balance_residual"])),
    }
    spring = set_spring_preload(ds)
    if spring is not None:
        out |= spring
    return out
