"""Steps and evaluations per shaft revolution of an IMEX additive Runge–Kutta method that treats the
cage's translational velocity implicitly (a measurement for docs/numerics.md, not a solver method).

    python benchmarks/imex_steps.py --case heavy --traction-model rheology [--revolutions 1]
                                    [--tolerance 1e-4] [--implicit cage|none]

The 218 heavy case's explicit step is limited by the cage running in its guiding land's thin film:
the squeeze-film damping on the cage's radial velocity is an overdamped mode of about -1.5e6 1/s
(docs/numerics.md). Here f = f_E + f_I with f_I(Y) = A (Y - y_n) on the cage's three velocity
components, A their 3 x 3 Jacobian block (forward differences at the step's start; those
evaluations are not counted, a production version would difference the land kernel alone), and
the ARK3(2)4L[2]SA pair of Kennedy & Carpenter (Appl. Numer. Math. 44, 2003, 139–181): explicit
and ESDIRK tableaux sharing b, order 3 with an embedded order 2, four evaluations per step.
``--implicit none`` runs the pair's explicit part alone. Same error norm as the solver's
integrators; step control with exponent 1/3. Python loop: slow, use a revolution or less.
"""

from __future__ import annotations

import argparse
import math
import sys
from dataclasses import replace

import numpy as np

sys.path.insert(0, str(__import__("pathlib").Path(__file__).resolve().parents[1]))

from solver.catalogue import resolve_case
from solver.inputs import to_inputs
from solver.models.dynamic import SimulationOptions
from solver.models.dynamic import layout as L
from solver.models.dynamic.initial import initial_state_from_quasistatic, quasistatic_solution
from solver.models.dynamic.kernels import post_step, rhs_into, rhs_work
from solver.models.dynamic.params import build_params, build_quadrature
from solver.models.dynamic.simulate import state_scales

CASES = {"spindle": "spindle-combined-load", "heavy": "218-heavy-combined"}

GAMMA = 1767732205903.0 / 4055673282236.0
A_EXPLICIT = np.zeros((4, 4))
A_EXPLICIT[1, 0] = 1767732205903.0 / 2027836641118.0
A_EXPLICIT[2, :2] = (5535828885825.0 / 10492691773637.0, 788022342437.0 / 10882634858940.0)
A_EXPLICIT[3, :3] = (
    6485989280629.0 / 16251701735622.0,
    -4246266847089.0 / 9704473918619.0,
    10755448449292.0 / 10357097424841.0,
)
A_IMPLICIT = np.zeros((4, 4))
A_IMPLICIT[1, :2] = (GAMMA, GAMMA)
A_IMPLICIT[2, :3] = (2746238789719.0 / 10658868560708.0, -640167445237.0 / 6845629431997.0, GAMMA)
A_IMPLICIT[3, :] = (
    1471266399579.0 / 7840856788654.0,
    -4482444167858.0 / 7529755066697.0,
    11266239266428.0 / 11593286722821.0,
    GAMMA,
)
B = A_IMPLICIT[3].copy()
B_EMBEDDED = np.array(
    (
        2756255671327.0 / 12835298489170.0,
        -10771552573575.0 / 22201958757719.0,
        9247589265047.0 / 10645013368117.0,
        2193209047091.0 / 5459859503100.0,
    )
)


def run(label, traction_model, revolutions, tolerance, implicit):
    inputs = to_inputs(resolve_case(CASES[label]))
    if traction_model is not None:
        inputs = replace(inputs, lubricant=replace(inputs.lubricant, traction_model=traction_model))
    options = SimulationOptions(shaft_revolutions=revolutions)
    par = build_params(inputs, options)
    quad = build_quadrature(options, par)
    y = initial_state_from_quasistatic(par, quasistatic_solution(inputs))
    scale = state_scales(par, y)
    z, n = int(par.ball_count), y.shape[0]
    cb = L.cage_base(z)
    idx = [cb + L.C_VEL + i for i in range(3)] if implicit == "cage" else []
    m = len(idx)
    rec_i = np.zeros((z, L.N_CONTACT_RECORD))
    rec_o = np.zeros((z, L.N_CONTACT_RECORD))
    pocket = np.zeros(z)
    work = rhs_work()
    count = [0]

    def f(state, counted=True):
        out = np.empty(n)
        rhs_into(state, par, quad, out, rec_i, rec_o, pocket, work)
        count[0] += counted
        return out

    op = inputs.operating
    period = 2.0 * math.pi / abs(op.inner_ring_speed - op.outer_ring_speed)
    t, t_end = 0.0, revolutions * period
    h = 0.05 * scale[L.B_POS] / scale[L.B_VEL]
    f0 = f(y)
    steps = rejected = 0
    err_old = 1e-4
    while t < t_end:
        hs = min(h, t_end - t)
        jac = np.zeros((m, m))
        for c, k in enumerate(idx):
            e = 1e-4 * scale[k]
            yp = y.copy()
            yp[k] += e
            jac[:, c] = (f(yp, counted=False)[idx] - f0[idx]) / e
        matrix = np.eye(m) - hs * GAMMA * jac
        fe = np.zeros((4, n))
        fi = np.zeros((4, n))
        for i in range(4):
            if i == 0:
                yi, fy = y, f0
            else:
                yi = y + hs * (A_EXPLICIT[i, :i] @ fe[:i] + A_IMPLICIT[i, :i] @ fi[:i])
                if m:
                    yi[idx] = y[idx] + np.linalg.solve(matrix, yi[idx] - y[idx])
                fy = f(yi)
            if m:
                fi[i, idx] = jac @ (yi[idx] - y[idx])
            fe[i] = fy - fi[i]
        total = fe + fi
        err = float(np.max(np.abs(hs * ((B - B_EMBEDDED) @ total)) / (tolerance * scale)))
        if err <= 1.0:
            fac = 0.9 * err ** (-1.0 / 3.0) * err_old**0.08 if err > 0.0 else 5.0
            err_old = max(err, 1e-4)
            t += hs
            y = y + hs * (B @ total)
            post_step(y, par, rec_i, rec_o)
            f0 = f(y)
            steps += 1
            h = hs * min(5.0, max(0.2, fac))
        else:
            rejected += 1
            h = hs * max(0.2, 0.9 * err ** (-1.0 / 3.0))
    print(
        f"{label} traction {inputs.lubricant.traction_model} tolerance {tolerance:g} implicit "
        f"{implicit}: {steps / revolutions:.0f} steps/rev, {rejected} rejected, "
        f"{count[0] / revolutions:.0f} evaluations/rev ({count[0] / steps:.2f} per step)"
    )


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", default="heavy", choices=list(CASES))
    parser.add_argument("--traction-model", choices=("slip_curve", "rheology"), default=None)
    parser.add_argument("--revolutions", type=float, default=1.0)
    parser.add_argument("--tolerance", type=float, default=1e-4)
    parser.add_argument("--implicit", choices=("cage", "none"), default="cage")
    args = parser.parse_args(argv)
    run(args.case, args.traction_model, args.revolutions, args.tolerance, args.implicit)
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
