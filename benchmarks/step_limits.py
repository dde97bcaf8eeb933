"""What sets the explicit step on a running bearing: which state component's error the step
control sees, step by step.

    python benchmarks/step_limits.py [--cases spindle heavy] [--traction-model rheology]
                                     [--revolutions 1] [--tolerance 1e-4]

The case runs from its quasi-static start with a Python copy of the Dormand–Prince 5(4) loop of
``solver.models.dynamic.integrate.dopri5`` (same tableau, error norm and PI control; the right-hand
side is the compiled model's). For every step the state component with the largest scaled error is
attributed to a part of the state (ball centre position or velocity, ball quaternion, ball angular
velocity, inner ring, cage speed and angle, rest of the cage); printed: steps per shaft revolution,
rejected steps, and the share of accepted and rejected steps each part set, with the median step.
Slow (Python loop, about 10x the compiled run): use a revolution or less.
"""

from __future__ import annotations

import argparse
import math
import sys
from collections import Counter
from dataclasses import replace

import numpy as np

sys.path.insert(0, str(__import__("pathlib").Path(__file__).resolve().parents[1]))

from solver.catalogue import resolve_case
from solver.inputs import to_inputs
from solver.models.dynamic import SimulationOptions
from solver.models.dynamic import layout as L
from solver.models.dynamic.initial import initial_state_from_quasistatic, quasistatic_solution
from solver.models.dynamic.integrate import dopri5 as dp
from solver.models.dynamic.kernels import post_step, rhs_into, rhs_work
from solver.models.dynamic.params import build_params, build_quadrature
from solver.models.dynamic.simulate import state_scales

CASES = {"spindle": "spindle-combined-load", "heavy": "218-heavy-combined"}

_A = (
    (),
    (dp._A21,),
    (dp._A31, dp._A32),
    (dp._A41, dp._A42, dp._A43),
    (dp._A51, dp._A52, dp._A53, dp._A54),
    (dp._A61, dp._A62, dp._A63, dp._A64, dp._A65),
    (dp._A71, 0.0, dp._A73, dp._A74, dp._A75, dp._A76),
)
_E = (dp._E1, 0.0, dp._E3, dp._E4, dp._E5, dp._E6, dp._E7)


def part_names(z):
    """Name of the part of the state each slot belongs to."""
    names = []
    for _ in range(z):
        names += ["ball position"] * 3 + ["ball velocity"] * 3
        names += ["ball quaternion"] * 4 + ["ball angular velocity"] * 3
    names += ["inner ring"] * L.RING_SIZE
    cage = ["cage position"] * 3 + ["cage velocity"] * 3 + ["cage angle", "cage speed"]
    cage += ["cage tilt"] * 2 + ["cage tilt rate"] * 2
    return names + cage


def run(label, traction_model, revolutions, tolerance):
    inputs = to_inputs(resolve_case(CASES[label]))
    if traction_model is not None:
        inputs = replace(inputs, lubricant=replace(inputs.lubricant, traction_model=traction_model))
    options = SimulationOptions(shaft_revolutions=revolutions)
    par = build_params(inputs, options)
    quad = build_quadrature(options, par)
    y = initial_state_from_quasistatic(par, quasistatic_solution(inputs))
    scale = state_scales(par, y)
    tol = tolerance if tolerance is not None else options.resolved(inputs.simulation).tolerance
    op = inputs.operating
    period = 2.0 * math.pi / abs(op.inner_ring_speed - op.outer_ring_speed)
    z = int(par.ball_count)
    names = part_names(z)
    n = y.shape[0]
    rec_i = np.zeros((z, L.N_CONTACT_RECORD))
    rec_o = np.zeros((z, L.N_CONTACT_RECORD))
    pocket = np.zeros(z)
    work = rhs_work(z)
    k = np.empty((7, n))

    def f(state, out):
        rhs_into(state, par, quad, out, rec_i, rec_o, pocket, work)

    f(y, k[0])
    h = 0.05 * scale[L.B_POS] / scale[L.B_VEL]
    t, t_end = 0.0, revolutions * period
    err_old = 1e-4
    accepted, rejected = Counter(), Counter()
    steps_taken = []
    while t < t_end:
        hs = min(h, t_end - t)
        for s in range(1, 7):
            yt = y + hs * sum(a * k[j] for j, a in enumerate(_A[s]) if a != 0.0)
            f(yt, k[s])
        e = hs * sum(c * k[j] for j, c in enumerate(_E) if c != 0.0)
        r = np.abs(e) / (tol * scale)
        worst = int(np.argmax(r))
        err = float(r[worst])
        if err <= 1.0:
            accepted[names[worst]] += 1
            steps_taken.append(hs)
            fac = 0.9 * err ** (-0.17) * err_old**0.04 if err > 0.0 else 5.0
            fac = min(5.0, max(0.2, fac))
            err_old = max(err, 1e-4)
            t += hs
            y = yt
            post_step(y, par, rec_i, rec_o)
            k[0] = k[6]
            h = hs * fac
        else:
            rejected[names[worst]] += 1
            h = hs * max(0.2, 0.9 * err ** (-0.2))
    n_acc = sum(accepted.values())
    print(
        f"\n== {label}, traction {inputs.lubricant.traction_model}, tolerance {tol:g}, "
        f"{revolutions:g} revolutions from the quasi-static start"
    )
    print(
        f"   {n_acc / revolutions:.0f} steps per revolution, {sum(rejected.values())} rejected, "
        f"median step {np.median(steps_taken) * 1e6:.2f} us"
    )
    print(f"   {'part with the largest scaled error':36s} {'accepted':>9s} {'rejected':>9s}")
    for name in dict.fromkeys(names):
        if accepted[name] or rejected[name]:
            print(f"   {name:36s} {accepted[name] / n_acc:9.1%} {rejected[name]:9d}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES))
    parser.add_argument("--traction-model", choices=("slip_curve", "rheology"), default=None)
    parser.add_argument("--revolutions", type=float, default=1.0)
    parser.add_argument("--tolerance", type=float, default=None)
    args = parser.parse_args(argv)
    for label in args.cases:
        run(label, args.traction_model, args.revolutions, args.tolerance)
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
