"""Benchmark of the dynamic model on a light and a heavy catalogue case.

    python benchmarks/dynamic.py [--revolutions N] [--cases spindle heavy]
                                 [--methods auto dopri5] [--memory-revolutions 100]
                                 [--compile-time] [--traction-model case|rheology|slip_curve]
                                 [--compare-traction [REPEATS]]
                                 [--tolerance 1e-4]

- spindle: catalogue case ``spindle-combined-load`` (7008C-class hybrid, 18 balls, 20 000 rpm,
  500 N axial + 300 N radial, cage on);
- heavy: ``218-heavy-combined`` (218, 16 balls, 10 000 rpm, 17.8 kN + 8.9 kN, cage on).

For each case and integration method (option ``method``, docs/numerics.md) prints wall and CPU
time per shaft revolution of a run timed without tracemalloc (after a warm-up run that loads or
compiles the numba kernels), steps per revolution, accepted and rejected steps, right-hand-side
evaluations per step and the cost of one evaluation (CPU, as the integrator makes it: timed from a
compiled loop at a running state, best of 15 batches), peak memory of a separate pass of
``--memory-revolutions`` revolutions under tracemalloc (Python/numpy allocations; ru_maxrss for
the process), and a
breakdown of where the time goes: the cost of one right-hand-side evaluation measured with parts of
the physics switched off (numba code cannot be profiled by cProfile, so the parts are timed by
difference), times the number of evaluations, plus the integrator overhead and the output stage.
Last, each case's figures against the targets of issue 13 (spindle <= 0.1 s, 218 heavy <= 0.06 s
per revolution, <= 1 GB for 100 revolutions). ``--compile-time`` also times the first run in a
fresh process with an empty numba cache (compilation of every kernel).

``--compare-traction`` instead times the two traction models of the ball-race contacts against
each other (issue 12: the rheology may make a shaft revolution at most 25 % slower than the slip
curve): for each case and method, runs with the slip curve and with the rheology alternate
(interleaved, so that the load of the shared machine falls on both alike), REPEATS times each
(default 3), and prints the median wall and CPU seconds per shaft revolution, the steps per
revolution and the cost of one right-hand-side evaluation of each, and their ratios.
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
import tracemalloc
from dataclasses import replace

import numpy as np
from numba import njit

# run as a script, sys.path[0] is benchmarks/; put the repository first so that the ``assets``
# package resolves to the repository's directory (the catalogue reads its files)
sys.path.insert(0, str(__import__("pathlib").Path(__file__).resolve().parents[1]))

from solver.catalogue import resolve_case
from solver.inputs import to_inputs
from solver.models.dynamic import SimulationOptions, simulate
from solver.models.dynamic import layout as L
from solver.models.dynamic.initial import initial_state
from solver.models.dynamic.integrate import METHODS, run
from solver.models.dynamic.integrate.control import step_control
from solver.models.dynamic.kernels import rhs_into, rhs_work
from solver.models.dynamic.params import build_params, build_quadrature, model_history
from solver.models.dynamic.simulate import state_scales

CASES = {"spindle": "spindle-combined-load", "heavy": "218-heavy-combined"}
TARGETS = {"spindle": 0.1, "heavy": 0.06}  # s wall per shaft revolution (issue 13)
MEMORY_TARGET = 1e9  # bytes for 100 revolutions


def running_state(inputs, options, revolutions=0.1):
    """A state of the running bearing: the initial state advanced by ``revolutions``."""
    par = build_params(inputs, options)
    history = model_history(inputs)
    quad = build_quadrature(options, par)
    y = initial_state(history, par, quad)
    scale = state_scales(history, par, y)
    op = inputs.operating
    t_end = revolutions * 2.0 * np.pi / abs(op.inner_ring_speed - op.outer_ring_speed)
    out = np.empty((1, y.shape[0]))
    h = 0.05 * scale[L.B_POS] / scale[L.B_VEL]
    tolerance = options.resolved(inputs.simulation).tolerance
    control = step_control(tolerance, scale, 1e-6 * h, 10_000_000)
    run("dopri5", history, par, quad, y, np.array([t_end]), out, control, h)
    return y


@njit
def _evaluations(n, y, history, par, quad, dydt, rec_i, rec_o, pocket, scratch):
    """``n`` right-hand-side evaluations as the integrator makes them (scratch record, records
    not observed), from compiled code: no Python call per evaluation."""
    for _ in range(n):
        rhs_into(y, 0.0, history, par, quad, dydt, rec_i, rec_o, pocket, scratch, False)


def rhs_cost(inputs, options, y, repeats=400, batches=15):
    """CPU seconds per right-hand-side evaluation at state ``y`` as the integrator makes them
    (best of ``batches`` batches of ``repeats``: the machine is shared)."""
    par = build_params(inputs, options)
    history = model_history(inputs)
    quad = build_quadrature(options, par)
    z = int(par.ball_count)
    rec_i = np.zeros((z, L.N_CONTACT_RECORD))
    rec_o = np.zeros((z, L.N_CONTACT_RECORD))
    pocket = np.zeros(z)
    dydt = np.zeros_like(y)
    scratch = rhs_work(int(par.ball_count))
    _evaluations(1, y, history, par, quad, dydt, rec_i, rec_o, pocket, scratch)
    best = float("inf")
    for _ in range(batches):
        start = time.process_time()
        _evaluations(repeats, y, history, par, quad, dydt, rec_i, rec_o, pocket, scratch)
        best = min(best, (time.process_time() - start) / repeats)
    return best


def run_case(label, revolutions, method, memory_revolutions, traction_model="case", tolerance=None):
    case = resolve_case(CASES[label])
    inputs = to_inputs(case)
    if traction_model != "case":
        inputs = replace(inputs, lubricant=replace(inputs.lubricant, traction_model=traction_model))
    options = SimulationOptions(shaft_revolutions=revolutions, method=method, tolerance=tolerance)
    first = time.perf_counter()
    simulate(inputs, options=replace(options, shaft_revolutions=0.05))  # load / compile kernels
    first = time.perf_counter() - first
    start = time.perf_counter()
    cpu_start = time.process_time()
    ds = simulate(inputs, options=options)
    cpu = time.process_time() - cpu_start
    total = time.perf_counter() - start
    # memory in a separate pass: tracemalloc slows numpy-heavy code down
    tracemalloc.start()
    simulate(inputs, options=replace(options, shaft_revolutions=memory_revolutions))
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1e3
    integ = ds.attrs["wall_time_s"]
    steps, rejected, evals = (
        ds.attrs["steps"],
        ds.attrs["rejected_steps"],
        ds.attrs["rhs_evaluations"],
    )
    y_run = running_state(inputs, options)
    full = rhs_cost(inputs, options, y_run)
    no_traction = rhs_cost(inputs, replace(options, traction=False), y_run)
    no_cage = rhs_cost(inputs, replace(options, cage=False), y_run)
    normal_only = rhs_cost(inputs, replace(options, traction=False, cage=False), y_run)
    per_rev = integ / revolutions
    tol = options.resolved(inputs.simulation).tolerance
    print(f"\n== {label}, method {method}, tolerance {tol:g}: {case.title}")
    print(
        f"   {revolutions:g} shaft revolutions, {ds.sizes['time']} samples, complete = "
        f"{ds.attrs['complete']}, traction model {inputs.lubricant.traction_model}"
    )
    print(
        f"   wall time: integration {integ:.2f} s = {per_rev:.3f} s per shaft revolution; "
        f"whole simulate() incl. start and output {total:.2f} s"
    )
    print(
        f"   CPU time of simulate() {cpu:.2f} s ({cpu / revolutions:.3f} s per revolution incl. "
        "start and output; wall > CPU means the shared machine was busy)"
    )
    print(
        f"   steps {steps / revolutions:.0f} per revolution ({steps} accepted, {rejected} "
        f"rejected, mean step {ds.attrs['shaft_period_s'] * revolutions / max(steps, 1) * 1e6:.2f}"
        f" us); RHS evaluations {evals} = {evals / max(steps + rejected, 1):.2f} per step; "
        f"one evaluation {full * 1e6:.1f} us"
    )
    print(f"   first run in this process (kernels from the cache or compiled) {first:.1f} s")
    print(
        f"   memory ({memory_revolutions:g}-revolution pass): tracemalloc peak {peak / 1e6:.1f} MB,"
        f" process max RSS {rss / 1e6:.0f} MB"
    )
    rhs_total = evals * full
    print("   where the time goes (RHS cost by difference at a running state x evaluations; the")
    print("   machine is shared, so the parts are indicative):")
    print(f"     normal contacts only: {normal_only * 1e6:.1f} us per evaluation")
    parts = {
        "Hertz geometry + normal forces + ball/ring bookkeeping": evals * normal_only,
        "traction, rolling resistance and drag": evals * (full - no_traction),
        "cage pockets and land": evals * (full - no_cage),
    }
    for name, seconds in parts.items():
        print(f"     {name:55s} {seconds:7.2f} s  ({100 * seconds / integ:5.1f} %)")
    print(
        f"     {'rest: integrator, linear algebra, waiting for the CPU':55s} "
        f"{integ - rhs_total:7.2f} s  ({100 * (integ - rhs_total) / integ:5.1f} %)"
    )
    print(f"     {'initial state + output Dataset':55s} {total - integ:7.2f} s")
    # the process's resident set plus the traced allocations scaled to 100 revolutions
    return per_rev, rss + peak * max(100.0 / memory_revolutions - 1.0, 0.0)


TRACTION_MODELS = ("slip_curve", "rheology")


def compare_traction(label, revolutions, method, repeats):
    """Interleaved runs with each traction model; prints medians and the rheology / slip-curve
    ratios. Returns the ratio of the median wall seconds per shaft revolution."""
    case = resolve_case(CASES[label])
    base = to_inputs(case)
    inputs = {
        m: replace(base, lubricant=replace(base.lubricant, traction_model=m))
        for m in TRACTION_MODELS
    }
    options = SimulationOptions(shaft_revolutions=revolutions, method=method)
    for m in TRACTION_MODELS:  # load / compile the kernels of both
        simulate(inputs[m], options=replace(options, shaft_revolutions=0.05))
    wall = {m: [] for m in TRACTION_MODELS}
    cpu = {m: [] for m in TRACTION_MODELS}
    steps = {}
    for _ in range(repeats):
        for m in TRACTION_MODELS:
            cpu_start = time.process_time()
            ds = simulate(inputs[m], options=options)
            cpu[m].append((time.process_time() - cpu_start) / revolutions)
            wall[m].append(ds.attrs["wall_time_s"] / revolutions)
            steps[m] = (ds.attrs["steps"] + ds.attrs["rejected_steps"]) / revolutions
    y_run = running_state(inputs["slip_curve"], options)
    evaluation = {}
    for _ in range(2):
        for m in TRACTION_MODELS:
            cost = rhs_cost(inputs[m], options, y_run, repeats=200)
            evaluation[m] = min(evaluation.get(m, float("inf")), cost)
    med = {m: float(np.median(wall[m])) for m in TRACTION_MODELS}
    med_cpu = {m: float(np.median(cpu[m])) for m in TRACTION_MODELS}
    print(f"\n== {label}, method {method}: {case.title}; {revolutions:g} revolutions x {repeats}")
    for m in TRACTION_MODELS:
        print(
            f"   {m:10s} integration {med[m]:.3f} s/rev wall (median; runs "
            f"{', '.join(f'{w:.3f}' for w in wall[m])}), simulate() CPU {med_cpu[m]:.3f} s/rev, "
            f"{steps[m]:.0f} steps/rev (incl. rejected), "
            f"one evaluation {evaluation[m] * 1e6:.1f} us"
        )
    ratio = med["rheology"] / med["slip_curve"]
    print(
        f"   rheology / slip curve: wall {ratio:.2f}, CPU "
        f"{med_cpu['rheology'] / med_cpu['slip_curve']:.2f}, steps "
        f"{steps['rheology'] / steps['slip_curve']:.2f}, one evaluation (same state) "
        f"{evaluation['rheology'] / evaluation['slip_curve']:.2f}"
    )
    return ratio


def compile_time():
    """(wall, CPU) seconds of a first tiny run in a fresh process with an empty numba cache."""
    code = (
        "import time; t = time.perf_counter()\n"
        "from solver.models.dynamic import SimulationOptions, simulate\n"
        "simulate('spindle-combined-load', options=SimulationOptions(shaft_revolutions=0.01))\n"
        "print(time.perf_counter() - t)\n"
    )
    cpu = resource.getrusage(resource.RUSAGE_CHILDREN)
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        out = subprocess.run(
            [sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True
        )
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime + after.ru_stime - cpu.ru_utime - cpu.ru_stime
    return float(out.stdout.strip().splitlines()[-1]), cpu


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--revolutions", type=float, default=3.0)
    parser.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES))
    parser.add_argument("--methods", nargs="+", default=["auto", "dopri5"], choices=list(METHODS))
    parser.add_argument(
        "--memory-revolutions",
        type=float,
        default=100.0,
        help="length of the separate memory pass (peak scaled to 100 revolutions if shorter)",
    )
    parser.add_argument("--compile-time", action="store_true")
    parser.add_argument(
        "--tolerance", type=float, default=None, help="integrator tolerance (default: the case's)"
    )
    parser.add_argument(
        "--traction-model",
        default="case",
        choices=("case", "rheology", "slip_curve"),
        help="traction law of the ball-race contacts (default: the case's)",
    )
    parser.add_argument(
        "--compare-traction",
        type=int,
        nargs="?",
        const=3,
        default=0,
        metavar="REPEATS",
        help="time the rheology against the slip curve (interleaved runs, medians)",
    )
    args = parser.parse_args(argv)
    if args.compare_traction:
        ratios = {
            (label, method): compare_traction(
                label, args.revolutions, method, args.compare_traction
            )
            for label in args.cases
            for method in args.methods
        }
        print("\nrheology / slip curve, wall s per shaft revolution (issue 12 allows 1.25):")
        for (label, method), ratio in ratios.items():
            verdict = "within" if ratio <= 1.25 else "over"
            print(f"  {label:8s} {method:10s} {ratio:.2f}: {verdict} 1.25")
        return 0
    results = {
        (label, method): run_case(
            label,
            args.revolutions,
            method,
            args.memory_revolutions,
            args.traction_model,
            args.tolerance,
        )
        for label in args.cases
        for method in args.methods
    }
    print("\nagainst the targets (wall s per shaft revolution on this machine; memory for 100")
    print("revolutions, scaled from the memory pass when it was shorter):")
    for (label, method), (per_rev, memory) in results.items():
        verdict = "meets" if per_rev <= TARGETS[label] else "misses"
        mem = "meets" if memory <= MEMORY_TARGET else "misses"
        print(
            f"  {label:8s} {method:10s} {per_rev:.3f} s/rev: {verdict} {TARGETS[label]} s; "
            f"memory <= {memory / 1e6:.0f} MB: {mem} 1 GB"
        )
    if args.compile_time:
        wall, cpu = compile_time()
        print(
            f"\nfirst run with an empty numba cache (compile everything): {wall:.1f} s wall, "
            f"{cpu:.1f} s CPU"
        )
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
