"""``racetrace quasistatic CASE [--output result.nc] [--json]`` (also ``racetrace solve``): the
Jones–Harris quasi-static solution.

The answer is :func:`solver.quasistatic_answer`: for a misalignment turning with the inner ring,
the solutions over one revolution (a ``ring_angle`` dimension), whose metrics span every ring
angle and ball; the per-ball rows are then those at ring angle 0. For a case with a time history,
``--at-time T`` solves under its operating point at T seconds (default t = 0) and
``--along-history [N]`` solves along the history (:func:`solver.quasistatic_along_history`),
printing one row per time.

Default output is a readable table with units, followed by the trajectory metrics
(:mod:`racetrace.metrics`); ``--json`` prints a machine-parseable summary instead (the metrics
under ``trajectory``); ``--output`` writes the full results Dataset (NetCDF, results-schema.md).
Case warnings and result warnings (:func:`solver.results.checks.result_warnings`: the result leaves
the model's validity) go to stderr as ``warning: ...`` lines and leave the exit code alone. Exit
codes: 0 success, 2 invalid input (including an ``--output`` that cannot be written: checked before
solving), 3 no solution (the message says why and what to try) — mapped by racetrace.cli — and 5
when the result could not be written to ``--output`` (it is then written to a file in the
temporary folder, named on stderr).
"""

from __future__ import annotations

import json
import math
import os
import sys
from pathlib import Path

import numpy as np

from ._output import output_problem, save_result

RACES = ("inner", "outer")
#: What ``--along-history`` without a count solves (solver.quasistatic_along_history's default).
ALONG_HISTORY_DEFAULT_TEXT = "41 equally spaced times and every knot time of the history"
#: The result could not be written to --output: it went to the temporary folder, or nowhere.
EXIT_NOT_WRITTEN = 5


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "quasistatic",
        aliases=["solve"],
        help="solve the quasi-static (Jones-Harris) model of a case",
        description="Solve the quasi-static Jones-Harris model of a case (file or catalogue name) "
        "and print the load distribution; optionally save the results Dataset as NetCDF.",
    )
    parser.add_argument("case", metavar="CASE", help="case file (.toml) or catalogue name")
    parser.add_argument(
        "--output", "-o", metavar="FILE.nc", help="write the results Dataset (NetCDF)"
    )
    parser.add_argument(
        "--json", action="store_true", help="print a JSON summary instead of a table"
    )
    when = parser.add_mutually_exclusive_group()
    when.add_argument(
        "--at-time",
        type=float,
        metavar="SECONDS",
        help="of a case with a time history: solve under its operating point at this time "
        "(default: t = 0)",
    )
    when.add_argument(
        "--along-history",
        type=int,
        nargs="?",
        const=0,
        metavar="N",
        help="of a case with a time history: solve at N equally spaced times over its duration "
        f"(without N: {ALONG_HISTORY_DEFAULT_TEXT}) and print one row per time",
    )
    parser.set_defaults(func=run)


def _pressure_unit(p_max: float) -> tuple[str, float]:
    return ("GPa", 1e-9) if p_max >= 1e9 else ("MPa", 1e-6)


def _ring_angles(ds) -> int:
    """Ring angles of a solution over one revolution; 0 for a snapshot."""
    return int(ds.sizes.get("ring_angle", 0))


def _at_start(ds):
    """The snapshot at ring angle 0 of a solution over one revolution; a snapshot as it is."""
    return ds.isel(ring_angle=0, drop=True) if "ring_angle" in ds.dims else ds


def _revolution_text(ds) -> str:
    """The line saying that the answer spans one revolution ('' for a snapshot)."""
    count = _ring_angles(ds)
    if not count:
        return ""
    return (
        f"misalignment turning with the inner ring: solved at {count} inner-ring angles over one "
        "revolution; the metrics span them all, the rows below are at ring angle 0"
    )


def summary(ds) -> dict:
    """JSON-serialisable summary of a quasi-static answer (SI units, angles in degree): metrics
    over the whole answer (every ring angle of a solution over one revolution), the state and the
    balls at ring angle 0 (``ring_angles``: how many were solved, 0 for a snapshot)."""

    def floats(values):
        return [float(v) for v in np.asarray(values).ravel()]

    from racetrace.metrics import finite_or_none, life_json, metrics_json, torque_json
    from solver import RPM, ring_speeds

    answer, ds = ds, _at_start(ds)
    load = ds.contact_load.values
    inner_speed, outer_speed = ring_speeds(ds)
    largest_load, peak_pressure = (
        answer.racetrace.metric(n) for n in ("largest_load", "peak_pressure")
    )
    return {
        "model": "quasistatic",
        "ring_angles": _ring_angles(answer),
        "units": {
            "angle": "degree",
            "load": "N",
            "length": "m",
            "pressure": "Pa",
            "speed": "rad/s",
            "moment": "N m",
        },
        "inner_ring_speed_rpm": inner_speed / RPM,
        "outer_ring_speed_rpm": outer_speed / RPM,
        "inner_ring_offset_m": floats(ds.inner_ring_offset.values),
        "inner_ring_tilt_deg": floats(ds.inner_ring_tilt.values),
        "inner_ring_moment_Nm": floats(ds.inner_ring_moment.values),
        "cage_speed_rad_s": float(ds.cage_speed.values),
        "cage_to_shaft_speed_ratio": finite_or_none(
            float(ds.cage_speed.values) / inner_speed if inner_speed else math.nan
        ),  # null for a shaft at rest (or so slow that the ratio overflows)
        "max_contact_load_N": {r: float(largest_load.sel(race=r)) for r in RACES},
        "max_pressure_Pa": {r: float(peak_pressure.sel(race=r)) for r in RACES},
        "solver": {
            "iterations": int(ds.attrs.get("solver_iterations", 0)),
            "residual": float(ds.attrs.get("solver_residual", 0.0)),
            "race_control_note": ds.attrs.get("race_control_note", ""),
        },
        "trajectory": metrics_json(answer),
        "life": life_json(answer),
        "friction_torque": torque_json(answer),
        "balls": [
            {
                "azimuth_deg": float(ds.ball_azimuth.values[j]),
                "contact_angle_deg": {
                    "inner": float(ds.contact_angle.values[j, 0]),
                    "outer": float(ds.contact_angle.values[j, 1]),
                },
                "contact_load_N": {"inner": float(load[j, 0]), "outer": float(load[j, 1])},
                "semi_major_m": {
                    "inner": float(ds.ellipse_semi_major.values[j, 0]),
                    "outer": float(ds.ellipse_semi_major.values[j, 1]),
                },
                "semi_minor_m": {
                    "inner": float(ds.ellipse_semi_minor.values[j, 0]),
                    "outer": float(ds.ellipse_semi_minor.values[j, 1]),
                },
                "max_pressure_Pa": {
                    "inner": float(ds.max_pressure.values[j, 0]),
                    "outer": float(ds.max_pressure.values[j, 1]),
                },
                "race_control": str(ds.race_control.values[j]),
            }
            for j in range(ds.sizes["ball"])
        ],
    }


def table(ds, case) -> str:
    """Readable table: header (bearing, speed, loads, ring displacement, cage speed, peak pressure)
    and one row per ball."""
    from racetrace.metrics import life_text, metrics_text, torque_text
    from solver import ring_speeds

    answer, ds = ds, _at_start(ds)
    op = _operating_text_values(ds, case)
    b = case.bearing
    inner_speed = ring_speeds(ds)[0]
    peak = answer.racetrace.metric("peak_pressure")
    unit, factor = _pressure_unit(float(peak.max()))
    offset = ds.inner_ring_offset.values * 1e6
    tilt = ds.inner_ring_tilt.values
    moment = ds.inner_ring_moment.values
    cage_ratio = float(ds.cage_speed) / inner_speed if inner_speed else math.nan
    ratio = f" ({cage_ratio:.4f} x shaft)" if math.isfinite(cage_ratio) else ""
    lines = [
        f"case:    {case.title or '(no title)'}",
        f"bearing: {b.designation or '(no designation)'}, {b.ball_count} balls of "
        f"{b.ball_diameter_mm:g} mm, pitch diameter {b.pitch_diameter_mm:g} mm",
        f"speed:   inner ring {op.inner_ring_speed_rpm:g} rpm, outer ring "
        f"{(op.outer_ring_speed_rpm or 0.0):g} rpm",
        f"loads:   axial {(op.axial_load_N or 0.0):g} N, radial {(op.radial_load_N or 0.0):g} N at "
        f"{(op.radial_load_angle_deg or 0.0):g} deg",
        f"inner ring offset: x {offset[0]:.3f} um, y {offset[1]:.3f} um, z {offset[2]:.3f} um; "
        f"tilt y {tilt[0]:.4f} deg, z {tilt[1]:.4f} deg",
        f"moment on the inner ring: y {_clean(moment[0]):.4g} N m, z {_clean(moment[1]):.4g} N m"
        + (
            " (applied)"
            if op.tilting_moment_Nm is not None
            else " (what the shaft must apply to hold the imposed alignment)"
        ),
        f"cage speed: {float(ds.cage_speed):.2f} rad/s{ratio}",
        f"max pressure: inner {float(peak.sel(race='inner')) * factor:.3f} {unit}, "
        f"outer {float(peak.sel(race='outer')) * factor:.3f} {unit}",
    ]
    if "history_time" in ds.attrs:
        lines.append(f"time:    t = {float(ds.attrs['history_time']):g} s along the case's history")
    note = ds.attrs.get("race_control_note", "")
    if note and "settled" not in note:
        lines.append(f"note: {note}")
    if _revolution_text(answer):
        lines.append(f"note: {_revolution_text(answer)}")
    lines.append("")
    head = (
        f"{'ball':>4} {'psi':>7} {'alpha_i':>7} {'alpha_o':>7} {'Q_i':>9} {'Q_o':>9} {'a_i':>7} "
        f"{'b_i':>7} {'a_o':>7} {'b_o':>7} {'p_i':>7} {'p_o':>7}  control"
    )
    units = (
        f"{'':>4} {'deg':>7} {'deg':>7} {'deg':>7} {'N':>9} {'N':>9} {'mm':>7} {'mm':>7} "
        f"{'mm':>7} {'mm':>7} {unit:>7} {unit:>7}"
    )
    lines += [head, units]
    for j in range(ds.sizes["ball"]):
        a = ds.ellipse_semi_major.values[j] * 1e3
        bb = ds.ellipse_semi_minor.values[j] * 1e3
        p = ds.max_pressure.values[j] * factor
        q = ds.contact_load.values[j]
        angle = ds.contact_angle.values[j]
        lines.append(
            f"{j:>4d} {float(ds.ball_azimuth.values[j]):7.2f} {angle[0]:7.3f} {angle[1]:7.3f} "
            f"{q[0]:9.2f} {q[1]:9.2f} {a[0]:7.4f} {bb[0]:7.4f} {a[1]:7.4f} {bb[1]:7.4f} "
            f"{p[0]:7.3f} {p[1]:7.3f}  {ds.race_control.values[j]}"
        )
    lines.append(
        "alpha: contact angle; Q: contact load; a, b: contact-ellipse semi-axes (across the"
    )
    lines.append("groove, rolling direction); p: peak Hertz pressure; control: controlling race")
    lines += ["", metrics_text(answer), life_text(answer), torque_text(answer)]
    return "\n".join(lines)


def _operating_text_values(ds, case):
    """The operating point the header lines print, case units: the case's; for a solution at a
    time along a history (attribute ``history_time``), the one it was solved under."""
    from types import SimpleNamespace

    from solver import RPM, operating_from_result

    if "history_time" not in ds.attrs:
        return case.operating
    op = operating_from_result(ds)
    return SimpleNamespace(
        inner_ring_speed_rpm=op.inner_ring_speed / RPM,
        outer_ring_speed_rpm=op.outer_ring_speed / RPM,
        axial_load_N=op.axial_load,
        radial_load_N=op.radial_load,
        radial_load_angle_deg=math.degrees(op.radial_load_angle),
        tilting_moment_Nm=op.tilting_moment,
    )


def _along_value(ds, name: str, i: int) -> float:
    """Operating input ``name`` at time index ``i`` (a data variable over time where it varies,
    a scalar coordinate where not)."""
    values = np.asarray(ds[name].values, dtype=float)
    return float(values[i] if values.ndim else values)


def along_rows(ds) -> list[dict]:
    """One row per time of a sweep along the history: the operating inputs (case units) and the
    largest contact load, the contact-angle range and the cage speed there."""
    from solver import RPM

    rows = []
    for i, t in enumerate(np.asarray(ds.time.values, dtype=float)):
        load = ds.contact_load.isel(time=i).values
        angle = ds.contact_angle.isel(time=i).values
        inner = _along_value(ds, "inner_ring_speed", i)
        rows.append(
            {
                "time_s": float(t),
                "inner_ring_speed_rpm": inner / RPM,
                "outer_ring_speed_rpm": _along_value(ds, "outer_ring_speed", i) / RPM,
                "axial_load_N": _along_value(ds, "axial_load", i),
                "radial_load_N": _along_value(ds, "radial_load", i),
                "radial_load_angle_deg": _along_value(ds, "radial_load_angle", i),
                "max_contact_load_N": {r: float(load[:, k].max()) for k, r in enumerate(RACES)},
                "contact_angle_deg": {
                    r: [float(angle[:, k].min()), float(angle[:, k].max())]
                    for k, r in enumerate(RACES)
                },
                "cage_speed_rad_s": float(ds.cage_speed.isel(time=i)),
            }
        )
    return rows


def along_table(ds, case) -> str:
    """Readable table of a sweep along the history: one row per time."""
    lines = [
        f"case:    {case.title or '(no title)'}",
        f"quasi-static along the history: {ds.attrs.get('along_history', '')}",
        "",
        f"{'t':>9} {'n_i':>9} {'n_o':>7} {'F_a':>8} {'F_r':>8} {'psi_r':>7} {'Qmax_i':>8} "
        f"{'Qmax_o':>8} {'alpha_i':>13} {'cage':>9}",
        f"{'s':>9} {'rpm':>9} {'rpm':>7} {'N':>8} {'N':>8} {'deg':>7} {'N':>8} {'N':>8} "
        f"{'deg':>13} {'rad/s':>9}",
    ]
    for row in along_rows(ds):
        low, high = row["contact_angle_deg"]["inner"]
        lines.append(
            f"{row['time_s']:9.4g} {row['inner_ring_speed_rpm']:9.1f} "
            f"{row['outer_ring_speed_rpm']:7.1f} {row['axial_load_N']:8.1f} "
            f"{row['radial_load_N']:8.1f} {row['radial_load_angle_deg']:7.1f} "
            f"{row['max_contact_load_N']['inner']:8.1f} {row['max_contact_load_N']['outer']:8.1f} "
            f"{low:6.2f}-{high:6.2f} {row['cage_speed_rad_s']:9.2f}"
        )
    lines.append(
        "n: ring speeds; F_a, F_r, psi_r: axial and radial load and the radial load's azimuth; "
        "Qmax: largest contact load; alpha_i: inner contact angles (lowest-highest); cage: cage "
        "speed"
    )
    return "\n".join(lines)


def _clean(value: float) -> float:
    """Round-off below 1e-9 of the printed magnitude shown as 0 (never '-0' or '-1.7e-15')."""
    return 0.0 if abs(value) < 1e-9 else float(value)


def print_result_warnings(ds, stream=None) -> None:
    """Print where the result leaves the model's validity, as ``warning: ...`` lines (stderr)."""
    from solver import result_warnings

    for message in result_warnings(ds):
        print(f"warning: {message}", file=stream or sys.stderr)


def _run_set(args, case) -> int:
    """``racetrace solve`` of a bearing set: the per-bearing table (or JSON) of solver.solve."""
    from solver import printable, set_result_warnings, solve

    from .bearing_set import set_summary, set_table

    ds = solve(case)
    for message in set_result_warnings(ds):
        print(f"warning: {message}", file=sys.stderr)
    written = save_result(ds, Path(args.output)) if args.output else None
    if args.json:
        out = set_summary(ds)
        if args.output:
            out["output"] = None if written is None else str(written)
        text = json.dumps(out, indent=2, allow_nan=False)
    else:
        text = printable(set_table(ds), keep_newlines=True)
        if written is not None:
            text += f"\n\nresults written to {written}"
    try:
        print(text)
        sys.stdout.flush()
    except BrokenPipeError:
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    if args.output and written != Path(args.output):
        return EXIT_NOT_WRITTEN
    return 0


def run(args) -> int:
    from solver import (
        CaseError,
        Problem,
        printable,
        quasistatic_along_history,
        quasistatic_answer,
        resolve_case,
        solve_quasistatic,
    )

    case = resolve_case(args.case)
    for warning in case.warnings():
        print(f"warning: {warning.message}", file=sys.stderr)
    if args.output:
        problem = output_problem(Path(args.output))
        if problem:
            raise CaseError(Problem("output", problem))
    if case.bearing_set is not None:
        return _run_set(args, case)
    along = getattr(args, "along_history", None)
    at_time = getattr(args, "at_time", None)
    if along is not None and along != 0 and along < 2:
        raise CaseError(
            Problem("--along-history", f"--along-history {along}: give at least 2 times")
        )
    if along is not None:
        ds = quasistatic_along_history(case, None if along == 0 else along)
    elif at_time is not None:
        ds = solve_quasistatic(case, at_time=at_time)
    else:
        ds = quasistatic_answer(case)
    if along is None:
        print_result_warnings(ds)
    written = save_result(ds, Path(args.output)) if args.output else None
    if args.json:
        if along is not None:
            out = {"model": "quasistatic", "along_history": along_rows(ds)}
        else:
            out = summary(ds)
            if at_time is not None:
                out["time_s"] = float(at_time)
        if args.output:
            out["output"] = None if written is None else str(written)
        text = json.dumps(out, indent=2, allow_nan=False)
    else:
        shown = along_table(ds, case) if along is not None else table(ds, case)
        text = printable(shown, keep_newlines=True)  # the title is the user's text
        if written is not None:
            text += f"\n\nresults written to {written}"
    try:
        print(text)
        sys.stdout.flush()
    except BrokenPipeError:  # output piped into e.g. `head`: not an error
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    if args.output and written != Path(args.output):
        return EXIT_NOT_WRITTEN
    return 0
