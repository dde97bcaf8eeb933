"""The public door's entry points that take a case by any name: a :class:`~solver.case.Case`, a
path to a case file, or a catalogue name (the only place that resolves catalogue names; the models
take a Case or SI Inputs).

Each function resolves its ``case`` argument (:func:`solver.catalogue.resolve_case`, CaseError when
it is neither a file nor a catalogue name) and calls the model of the same name.
"""

from __future__ import annotations

import os

from solver.catalogue import resolve_case


def _resolved(case):
    """A Case for a path or a catalogue name; a Case or SI Inputs as given."""
    if isinstance(case, str | os.PathLike):
        return resolve_case(case)
    return case


def solve_quasistatic(case, at_time: float | None = None):
    """The quasi-static (Jones-Harris) solution of ``case`` as a results Dataset
    (:func:`solver.models.quasistatic.solve_quasistatic`); ``at_time`` [s]: of a case with a time
    history, under its operating point at that time."""
    from solver.models.quasistatic import solve_quasistatic as model

    return model(_resolved(case), at_time=at_time)


def quasistatic_along_history(case, times=None):
    """The quasi-static reference along a case's time history, stacked along ``time``
    (:func:`solver.models.quasistatic.quasistatic_along_history`; ``times`` None, a count or
    the times [s])."""
    from solver.models.quasistatic import quasistatic_along_history as model

    return model(_resolved(case), times)


def solve(case):
    """The quasi-static answer of ``case``: for a bearing set (a case with a ``[set]`` table) the
    set's Dataset with a ``bearing`` dimension
    (:func:`solver.models.quasistatic.bearing_set.solve_set`), for one bearing
    :func:`quasistatic_answer`."""
    case = _resolved(case)
    if getattr(case, "bearing_set", None) is not None:
        from solver.models.quasistatic.bearing_set import solve_set

        return solve_set(case)
    return quasistatic_answer(case)


def solve_over_revolution(case, angles: int | None = None):
    """The quasi-static steady state at ``angles`` inner-ring angles over one shaft revolution
    (:func:`solver.models.quasistatic.solve_over_revolution`; None: its default,
    ``REVOLUTION_RING_ANGLES``)."""
    from solver.models.quasistatic import REVOLUTION_RING_ANGLES
    from solver.models.quasistatic import solve_over_revolution as model

    return model(_resolved(case), angles=REVOLUTION_RING_ANGLES if angles is None else angles)


def quasistatic_answer(case):
    """The quasi-static answer the CLI, studies, app and report quote: the solutions over one
    revolution for a misalignment turning with the inner ring, else the snapshot
    (:func:`solver.models.quasistatic.quasistatic_answer`)."""
    from solver.models.quasistatic import quasistatic_answer as model

    return model(_resolved(case))


def quasistatic_speed_sweep(case, speeds_rpm):
    """Quasi-static solutions of ``case`` at each inner-ring speed in ``speeds_rpm`` (rpm)
    (:func:`solver.models.quasistatic.quasistatic_speed_sweep`)."""
    from solver.models.quasistatic import quasistatic_speed_sweep as model

    return model(_resolved(case), speeds_rpm)


def simulate(case, progress=None, cancel=None, options=None):
    """The dynamic model's run of ``case`` (:func:`solver.models.dynamic.simulate`); for a
    bearing set (a case with a ``[set]`` table) the set's run with a ``bearing`` dimension
    (:func:`solver.models.dynamic.set_simulate.simulate_set`)."""
    case = _resolved(case)
    if getattr(case, "bearing_set", None) is not None:
        from solver.models.dynamic.set_simulate import simulate_set

        return simulate_set(case, progress=progress, cancel=cancel, options=options)
    from solver.models.dynamic import simulate as model

    return model(case, progress=progress, cancel=cancel, options=options)


def preload() -> None:
    """Import the modules that a solve, a result view and a study read (no kernel is compiled):
    for a process that forks workers or sessions after it, so that they share these imports."""
    import solver.case  # noqa: F401
    import solver.models.quasistatic  # noqa: F401
    import solver.results.checks  # noqa: F401
    import solver.results.dataset  # noqa: F401
    import solver.results.io  # noqa: F401
    import solver.results.summary  # noqa: F401
