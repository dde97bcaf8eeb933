"""``racetrace check CASE``: validate a case file (or catalogue name) and print a short summary.

Exit 0 when valid; 2 with every problem listed when not (the CLI maps CaseError to exit 2). A valid
case that one model cannot run (:func:`solver.case.dynamic_problems`) is still valid: each reason is
printed as a ``dynamic model: ...`` line.
"""

from __future__ import annotations

import math

from solver import FIELDS, printable


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "check",
        help="validate a case file and summarise it",
        description="Validate a case file (or a catalogue name) and print a short summary.",
    )
    parser.add_argument("case", metavar="CASE", help="case file (.toml) or catalogue name")
    parser.set_defaults(func=run)


def _num(value: float, digits: int = 4) -> str:
    return f"{value:.{digits}g}"


def history_events(case) -> str:
    """The knot times of a case's histories inside its run, in words ("" for none)."""
    times = sorted(
        {
            t
            for history in case.histories.values()
            for t in history.times
            if 0.0 < t < case.simulation.duration_s
        }
    )
    return ", ".join(f"{t:g} s" for t in times)


def summary(case) -> str:
    """Short human-readable summary of a valid case (units in the text)."""
    b, op = case.bearing, case.operating
    g = case.geometry()
    alpha0 = math.degrees(g.free_contact_angle)
    source = "given" if b.free_contact_angle_deg is not None else "from the diametral clearance"
    lines = [
        f"case:      {case.title or '(no title)'}",
        f"bearing:   {b.designation or '(no designation)'} [provenance: {b.provenance}]",
        f"           {b.ball_count} balls of {_num(b.ball_diameter_mm)} mm on a "
        f"{_num(b.pitch_diameter_mm)} mm pitch circle; groove radius ratios "
        f"f_i = {_num(b.inner_groove_radius_ratio)}, f_o = {_num(b.outer_groove_radius_ratio)}",
        f"           free contact angle {alpha0:.3f} deg ({source}); diametral clearance "
        f"{_num(g.diametral_clearance * 1e3)} mm; free end play {_num(g.free_end_play * 1e3)} mm",
        f"           balls: {case.ball_material.name}, rings: {case.ring_material.name}",
        f"operating: inner ring {_num(op.inner_ring_speed_rpm, 6)} rpm, outer ring "
        f"{_num(op.outer_ring_speed_rpm, 6)} rpm",
        f"           axial load {_num(op.axial_load_N, 6)} N, radial load "
        f"{_num(op.radial_load_N, 6)} N at {_num(op.radial_load_angle_deg)} deg",
    ]
    if op.misalignment_deg is not None:
        lines.append(
            f"           misalignment {_num(op.misalignment_deg)} deg about the axis at "
            f"{_num(op.misalignment_axis_deg)} deg, frame: {op.misalignment_frame}"
        )
    if op.tilting_moment_Nm is not None:
        lines.append(
            f"           tilting moment {_num(op.tilting_moment_Nm)} N m about the axis at "
            f"{_num(op.moment_axis_deg)} deg (tilt solved)"
        )
    sim = case.simulation
    if case.histories:
        by_key = {f.key: f for f in FIELDS}
        lines.append("history:   operating keys that vary in time (values at t = 0 above):")
        for key, history in case.histories.items():
            name = key.split(".", 1)[1]
            lines.append(f"           {name}: {history.describe(by_key[key].unit)}")
        if events := history_events(case):
            lines.append(f"           events (steps and segment ends) at {events}")
        estimated = "simulation.samples_per_second" in case.estimated
        lines.append(
            f"run:       {_num(sim.duration_s, 6)} s, {_num(sim.samples_per_second, 6)} "
            "samples per second" + (" (estimated)" if estimated else "")
        )
    else:
        lines.append(
            f"run:       {_num(sim.shaft_revolutions, 6)} shaft revolutions, "
            f"{sim.samples_per_revolution} samples per revolution"
        )
    if case.estimated:
        names = ", ".join(sorted(k.split(".", 1)[1] for k in case.estimated))
        lines.append(f"estimated: {names} (see docs/case-format.md)")
    if not case.lubricant_given:
        users = "the dynamic model uses"
        if case.simulation.quasistatic_ball_speeds == "traction":
            users = "the dynamic model and the quasi-static traction balance use"
        lines.append(f"lubricant: no [lubricant] section; {users} the default oil")
    lines.append("OK: the case is valid")
    return "\n".join(lines)


def run(args) -> int:
    from solver import dynamic_problems, resolve_case

    case = resolve_case(args.case)
    text = summary(case)
    if case.bearing_set is not None:  # [operating] gives the speeds only; the loads are the set's
        from .bearing_set import describe_set

        kept = [line for line in text.splitlines() if "axial load" not in line]
        kept[-1:-1] = describe_set(case)
        text = "\n".join(kept)
    print(printable(text, keep_newlines=True))  # the title is the user's text
    for problem in dynamic_problems(case):
        print(f"dynamic model: {problem.message}")
    for warning in case.warnings():
        print(f"warning: {warning.message}")
    return 0
