"""Steps and evaluations per shaft revolution of an IMEX additive Runge–Kutta method that treats the
cage's translational velocity implicitly (a Python prototype for docs/numerics.md).

    python benchmarks/imex_steps.py --case heavy --traction-model rheology [--revolutions 1]
                                    [--tolerance 1e-4] [--implicit cage|none] [--pair ark4|ark3]

The 218 heavy case's explicit step is limited by the cage running in its guiding land's thin film:
the squeeze-film damping on the cage's radial velocity is an overdamped mode of about -1.5e6 1/s
(docs/numerics.md). Here f = f_E + f_I with f_I(Y) = A (Y - y_n) on the cage's three velocity
components, A their 3 x 3 block of the whole right-hand side's Jacobian (forward differences at the
step's start, evaluations not counted; solver.models.dynamic.integrate.imex, the compiled method,
differences the land kernel alone), and a pair of Kennedy & Carpenter (Appl. Numer. Math. 44, 2003,
139–181): ARK4(3)6L[2]SA (default; order 4(3), six evaluations per step) or ARK3(2)4L[2]SA (order
3(2), four). ``--implicit none`` runs the pair's explicit part alone; ``--implicit cage+rotation``
adds every ball's angular velocity to the implicit slots (the traction slope on the balls' rotation;
A the dense block of those slots, the best case of a per-ball treatment). Same error norm as the
solver's integrators, PI step control. Python loop: slow, use a revolution or less."""

from __future__ import annotations

import argparse
import math
import sys
from dataclasses import replace

import numpy as np

sys.path.insert(0, str(__import__("pathlib").Path(__file__).resolve().parents[2]))

from solver.catalogue import resolve_case
from solver.inputs import to_inputs
from solver.models.dynamic import SimulationOptions
from solver.models.dynamic import layout as L
from solver.models.dynamic.initial import initial_state_from_quasistatic, quasistatic_solution
from solver.models.dynamic.integrate.imex import ark436l2sa
from solver.models.dynamic.kernels import post_step, rhs_into, rhs_work
from solver.models.dynamic.params import build_params, build_quadrature, model_history
from solver.models.dynamic.simulate import state_scales

CASES = {"spindle": "spindle-combined-load", "heavy": "218-heavy-combined"}


def _ark3():
    """ARK3(2)4L[2]SA: (explicit A, implicit A, b, embedded b, order)."""
    g = 1767732205903.0 / 4055673282236.0
    ae = np.zeros((4, 4))
    ae[1, 0] = 1767732205903.0 / 2027836641118.0
    ae[2, :2] = (5535828885825.0 / 10492691773637.0, 788022342437.0 / 10882634858940.0)
    ae[3, :3] = (
        6485989280629.0 / 16251701735622.0,
        -4246266847089.0 / 9704473918619.0,
        10755448449292.0 / 10357097424841.0,
    )
    ai = np.zeros((4, 4))
    ai[1, :2] = (g, g)
    ai[2, :3] = (2746238789719.0 / 10658868560708.0, -640167445237.0 / 6845629431997.0, g)
    ai[3, :] = (
        1471266399579.0 / 7840856788654.0,
        -4482444167858.0 / 7529755066697.0,
        11266239266428.0 / 11593286722821.0,
        g,
    )
    b_hat = (
        2756255671327.0 / 12835298489170.0,
        -10771552573575.0 / 22201958757719.0,
        9247589265047.0 / 10645013368117.0,
        2193209047091.0 / 5459859503100.0,
    )
    return ae, ai, ai[3].copy(), np.array(b_hat), 3


def _ark4():
    """ARK4(3)6L[2]SA, the compiled method's tableau: (explicit A, implicit A, b, embedded b,
    order)."""
    t = ark436l2sa()
    return t.explicit, t.implicit, t.b, t.b - t.e, t.order


PAIRS = {"ark3": _ark3, "ark4": _ark4}


def run(label, traction_model, revolutions, tolerance, implicit, pair="ark4"):
    a_explicit, a_implicit, b, b_embedded, order = PAIRS[pair]()
    gamma = a_implicit[1, 1]
    stages = b.shape[0]
    inputs = to_inputs(resolve_case(CASES[label]))
    if traction_model is not None:
        inputs = replace(inputs, lubricant=replace(inputs.lubricant, traction_model=traction_model))
    options = SimulationOptions(shaft_revolutions=revolutions)
    par = build_params(inputs, options)
    history = model_history(inputs)
    quad = build_quadrature(options, par)
    y = initial_state_from_quasistatic(par, quasistatic_solution(inputs))
    scale = state_scales(history, par, y)
    z, n = int(par.ball_count), y.shape[0]
    cb = L.cage_base(z)
    idx = [cb + L.C_VEL + i for i in range(3)] if implicit != "none" else []
    if implicit == "cage+rotation":  # and every ball's angular velocity (dense block, best case)
        idx += [L.ball_base(j) + L.B_OMEGA + i for j in range(z) for i in range(3)]
    m = len(idx)
    rec_i = np.zeros((z, L.N_CONTACT_RECORD))
    rec_o = np.zeros((z, L.N_CONTACT_RECORD))
    pocket = np.zeros(z)
    work = rhs_work(z)
    count = [0]

    def f(state, counted=True):
        out = np.empty(n)
        rhs_into(state, 0.0, history, par, quad, out, rec_i, rec_o, pocket, work, True)
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
        matrix = np.eye(m) - hs * gamma * jac
        fe = np.zeros((stages, n))
        fi = np.zeros((stages, n))
        for i in range(stages):
            if i == 0:
                yi, fy = y, f0
            else:
                yi = y + hs * (a_explicit[i, :i] @ fe[:i] + a_implicit[i, :i] @ fi[:i])
                if m:
                    yi[idx] = y[idx] + np.linalg.solve(matrix, yi[idx] - y[idx])
                fy = f(yi)
            if m:
                fi[i, idx] = jac @ (yi[idx] - y[idx])
            fe[i] = fy - fi[i]
        total = fe + fi
        err = float(np.max(np.abs(hs * ((b - b_embedded) @ total)) / (tolerance * scale)))
        if err <= 1.0:
            fac = 0.9 * err ** (-0.7 / order) * err_old ** (0.4 / order) if err > 0.0 else 5.0
            err_old = max(err, 1e-4)
            t += hs
            y = y + hs * (b @ total)
            post_step(y, par, rec_i, rec_o)
            f0 = f(y)
            steps += 1
            h = hs * min(5.0, max(0.2, fac))
        else:
            rejected += 1
            h = hs * max(0.2, 0.9 * err ** (-1.0 / order))
    print(
        f"{label} traction {inputs.lubricant.traction_model} {pair} tolerance {tolerance:g} "
        f"implicit {implicit}: {steps / revolutions:.0f} steps/rev, {rejected} rejected, "
        f"{count[0] / revolutions:.0f} evaluations/rev ({count[0] / steps:.2f} per step)"
    )


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", default="heavy", choices=list(CASES))
    parser.add_argument("--traction-model", choices=("slip_curve", "rheology"), default=None)
    parser.add_argument("--revolutions", type=float, default=1.0)
    parser.add_argument("--tolerance", type=float, default=1e-4)
    parser.add_argument("--implicit", choices=("cage", "cage+rotation", "none"), default="cage")
    parser.add_argument("--pair", choices=list(PAIRS), default="ark4")
    args = parser.parse_args(argv)
    run(args.case, args.traction_model, args.revolutions, args.tolerance, args.implicit, args.pair)
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
