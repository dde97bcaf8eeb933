"""Load (or, on a fresh clone, compile once) the numba kernels most tests use, before the test
workers start: the quasi-static model and a few hundredths of a revolution of the dynamic model of
the default catalogue case, and of a catalogue bearing set."""

from __future__ import annotations

import time


def warm_kernels() -> str:
    """Solve and briefly simulate a single bearing and a bearing set; returns what it did, in
    words (the seconds taken). A case that fails here fails again in its own test, which reports
    it: nothing is raised."""
    import solver
    from solver.models.dynamic import SimulationOptions

    start = time.perf_counter()
    names = ("spindle-combined-load", "spindle-pair-db-light-preload")
    done = []
    for name in names:
        try:
            case = solver.catalogue().get(name).load()
            solver.solve(case)
            solver.simulate(case, options=SimulationOptions(shaft_revolutions=0.02))
            done.append(name)
        except Exception as error:  # noqa: BLE001 - reported by the case's own tests
            done.append(f"{name} (failed: {type(error).__name__})")
    seconds = time.perf_counter() - start
    return f"numba kernels warmed in {seconds:.0f} s: {', '.join(done)}"
