"""Which modes limit the explicit step: eigenvalues of the dynamic model's Jacobian at a running
state.

    python benchmarks/stiffness.py [--cases spindle heavy] [--revolutions 0.3]
                                   [--traction-model slip_curve|rheology]

For each case the bearing is run for ``--revolutions`` shaft revolutions from its quasi-static
start (explicit Dormand–Prince), then the Jacobian of the right-hand side is formed by central
finite differences (step relative to each state component's characteristic scale) and its
eigenvalues are computed. Each eigenvalue is attributed to the part of the state that carries most
of its eigenvector's weight (eigenvector scaled by the characteristic magnitudes): ball centre
(position/velocity), ball rotation (quaternion/angular velocity), inner ring, cage. Printed: the
largest |lambda| of each part, the Dormand–Prince 5(4) step limit it implies (the stability
region's reach along the eigenvalue's direction), and the same for the per-ball 13 x 13 diagonal
blocks alone (what a per-ball block Jacobian sees). ``--traction-model`` replaces the case's
lubricant traction law (default: the case's own).
"""

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
from solver.models.dynamic.kernels import rhs
from solver.models.dynamic.params import build_params, build_quadrature, model_history
from solver.models.dynamic.simulate import state_scales

CASES = {"spindle": "spindle-combined-load", "heavy": "218-heavy-combined"}

# Dormand–Prince 5(4): stability polynomial of the 5th-order solution (7 stages, FSAL, degree 6)
_DP_POLY = [1.0, 1.0, 1.0 / 2.0, 1.0 / 6.0, 1.0 / 24.0, 1.0 / 120.0, 1.0 / 600.0]


def dp_reach(direction: complex) -> float:
    """Largest r with |R(r e^{i theta})| <= 1 along the unit direction ``direction`` (bisection
    after a scan), for the Dormand–Prince stability polynomial."""

    def stable(r):
        z = r * direction
        return abs(sum(c * z**k for k, c in enumerate(_DP_POLY))) <= 1.0 + 1e-12

    r = 0.01
    while stable(r + 0.01) and r < 10.0:
        r += 0.01
    lo, hi = r, r + 0.01
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if stable(mid) else (lo, mid)
    return lo


def jacobian(history, par, quad, y, scale):
    """Central-difference Jacobian of the right-hand side at ``y``."""
    n = y.shape[0]
    z = int(par.ball_count)
    rec_i = np.zeros((z, L.N_CONTACT_RECORD))
    rec_o = np.zeros((z, L.N_CONTACT_RECORD))
    pocket = np.zeros(z)
    fp = np.empty(n)
    fm = np.empty(n)
    jac = np.empty((n, n))
    for k in range(n):
        e = 1e-4 * scale[k]
        yp = y.copy()
        yp[k] += e
        ym = y.copy()
        ym[k] -= e
        rhs(yp, 0.0, history, par, quad, fp, rec_i, rec_o, pocket)
        rhs(ym, 0.0, history, par, quad, fm, rec_i, rec_o, pocket)
        jac[:, k] = (fp - fm) / (2.0 * e)
    return jac


def parts(z):
    """State slots of each part: {name: index array}."""
    n = L.state_size(z)
    centre, rotation = [], []
    for j in range(z):
        b = L.ball_base(j)
        centre += list(range(b + L.B_POS, b + L.B_POS + 6))
        rotation += list(range(b + L.B_QUAT, b + L.B_QUAT + 7))
    rb, cb = L.ring_base(z), L.cage_base(z)
    return {
        "ball centre (normal contact)": np.array(centre),
        "ball rotation (traction)": np.array(rotation),
        "inner ring": np.arange(rb, rb + L.RING_SIZE),
        "cage": np.arange(cb, min(cb + L.CAGE_SIZE, n)),
    }


def slot_name(z, i):
    """Name of state slot ``i`` (its body and quantity)."""
    ball = {L.B_POS: "position", L.B_VEL: "velocity", L.B_QUAT: "quaternion", L.B_OMEGA: "omega"}
    cage = {L.C_POS: "position", L.C_VEL: "velocity", L.C_ANGLE: "angle", L.C_SPEED: "speed"}
    cage |= {L.C_TILT: "tilt", L.C_TILT_RATE: "tilt rate"}
    axes = "xyz"
    if i < L.ring_base(z):
        j, o = divmod(i, L.BALL_STRIDE)
        start = max(k for k in ball if k <= o)
        return f"ball {j} {ball[start]}[{o - start}]"
    if i < L.cage_base(z):
        return f"inner ring slot {i - L.ring_base(z)}"
    o = i - L.cage_base(z)
    start = max(k for k in cage if k <= o)
    suffix = f" {axes[o - start]}" if cage[start] in ("position", "velocity") else ""
    return f"cage {cage[start]}{suffix}"


def report(label, revolutions, traction_model=None):
    case = resolve_case(CASES[label])
    inputs = to_inputs(case)
    if traction_model is not None:
        lubricant = replace(inputs.lubricant, traction_model=traction_model)
        inputs = replace(inputs, lubricant=lubricant)
    options = SimulationOptions(shaft_revolutions=revolutions)
    par = build_params(inputs, options)
    history = model_history(inputs)
    quad = build_quadrature(options, par)
    y0 = initial_state_from_quasistatic(par, quasistatic_solution(inputs))
    scale = state_scales(history, par, y0)
    op = inputs.operating
    period = 2.0 * math.pi / abs(op.inner_ring_speed - op.outer_ring_speed)
    y = _final_state(inputs, options, revolutions * period, y0, history, par, quad, scale)
    z = int(par.ball_count)
    jac = jacobian(history, par, quad, y, scale)
    # similarity scaling by the characteristic magnitudes (same eigenvalues, comparable vectors)
    js = jac * scale[None, :] / scale[:, None]
    lam, vec = np.linalg.eig(js)
    weights = np.abs(vec) ** 2
    groups = parts(z)
    law = inputs.lubricant.traction_model
    print(f"\n== {label}: {case.title}, traction {law}, state after {revolutions:g} revolutions")
    print(f"   shaft period {period * 1e3:.3f} ms; {len(lam)} eigenvalues")
    print(
        f"   {'part':32s} {'max |lambda| 1/s':>16s} {'Re':>11s} {'Im':>11s} {'DP h_max us':>12s}"
        "  largest slot of its mode"
    )
    overall = math.inf
    for name, idx in groups.items():
        share = weights[idx].sum(axis=0)
        mine = [k for k in range(len(lam)) if share[k] >= 0.5]
        if not mine:
            continue
        k = max(mine, key=lambda i: abs(lam[i]))
        lk = lam[k]
        limits = [dp_reach(lam[i] / abs(lam[i])) / abs(lam[i]) for i in mine if abs(lam[i]) > 0]
        hmin = min(limits) if limits else math.inf
        overall = min(overall, hmin)
        slot = slot_name(z, int(np.argmax(weights[:, k])))
        print(
            f"   {name:32s} {abs(lk):16.3e} {lk.real:11.3e} {lk.imag:11.3e} {hmin * 1e6:12.2f}"
            f"  {slot}"
        )
    print(
        f"   explicit Dormand-Prince stability limit: h <= {overall * 1e6:.2f} us = "
        f"{period / overall:.0f} steps per shaft revolution"
    )
    unstable = lam[lam.real > 1e-3 * np.abs(lam).max()]
    print(
        f"   eigenvalues with Re > 0 (growing modes): {len(unstable)}, max Re {lam.real.max():.3e}"
    )
    # per-ball 13 x 13 blocks: what a block-diagonal Jacobian captures
    block_max = 0.0
    for j in range(z):
        b = L.ball_base(j)
        blk = js[b : b + L.BALL_STRIDE, b : b + L.BALL_STRIDE]
        block_max = max(block_max, np.abs(np.linalg.eigvals(blk)).max())
    rest_idx = np.concatenate([groups["inner ring"], groups["cage"]])
    blk = js[np.ix_(rest_idx, rest_idx)]
    ring_cage = np.abs(np.linalg.eigvals(blk)).max()
    print(
        f"   per-ball 13x13 blocks: max |lambda| {block_max:.3e} 1/s (whole Jacobian "
        f"{np.abs(lam).max():.3e}); ring + cage block alone {ring_cage:.3e} 1/s"
    )
    return lam


def _final_state(inputs, options, t_end, y0, history, par, quad, scale):
    """The state at time ``t_end`` of a run from ``y0`` (explicit Dormand–Prince)."""
    from solver.models.dynamic.integrate import run
    from solver.models.dynamic.integrate.control import step_control

    y = y0.copy()
    h = 0.05 * scale[L.B_POS] / scale[L.B_VEL]
    tolerance = options.resolved(inputs.simulation).tolerance
    control = step_control(tolerance, scale, 1e-6 * h, 50_000_000)
    run("dopri5", history, par, quad, y, np.array([t_end]), np.empty((1, y.shape[0])), control, h)
    return y


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES))
    parser.add_argument("--revolutions", type=float, default=0.3)
    parser.add_argument(
        "--traction-model",
        choices=("slip_curve", "rheology"),
        default=None,
        help="lubricant traction law (default: the case's)",
    )
    args = parser.parse_args(argv)
    for label in args.cases:
        report(label, args.revolutions, args.traction_model)
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
