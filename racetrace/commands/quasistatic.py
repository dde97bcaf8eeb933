"""``racetrace quasistatic CASE [--output result.nc] [--json]`` (also ``racetrace solve``): the
Jones–Harris quasi-static solution.

The answer is :func:`solver.quasistatic_answer`: for a misalignment turning with the inner ring,
the solutions over one revolution (a ``ring_angle`` dimension), whose metrics span every ring
angle and ball; the per-ball rows are then those at ring angle 0.

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
    op = case.operating
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
    from solver import CaseError, Problem, printable, quasistatic_answer, resolve_case

    case = resolve_case(args.case)
    for warning in case.warnings():
        print(f"warning: {warning.message}", file=sys.stderr)
    if args.output:
        problem = output_problem(Path(args.output))
        if problem:
            raise CaseError(Problem("output", problem))
    if case.bearing_set is not None:
        return _run_set(args, case)
    ds = quasistatic_answer(case)
    print_result_warnings(ds)
    written = save_result(ds, Path(args.output)) if args.output else None
    if args.json:
        out = summary(ds)
        if args.output:
            out["output"] = None if written is None else str(written)
        text = json.dumps(out, indent=2, allow_nan=False)
    else:
        text = printable(table(ds, case), keep_newlines=True)  # the title is the user's text
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
