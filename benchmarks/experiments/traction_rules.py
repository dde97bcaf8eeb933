"""Accuracy and cost of the ellipse traction rules with the rheology law, on running contact states.

    python benchmarks/traction_rules.py [--cases spindle heavy] [--states 0.1 0.35 0.6]
                                        [--rules product:4x8 split:3x3 ...]

For each catalogue case (benchmarks/dynamic.py: ``spindle``, ``heavy``) with the ``rheology``
traction model, the dynamic model is advanced from its start to a few running states (shaft
revolutions ``--states``). At each state one right-hand side is evaluated with every rule and with
a converged reference (the product rule with 48 x 96 nodes); printed per rule: the largest error of
the contact force and of the moment on the ball over all contacts and states, relative to the
largest tangential contact force and moment of the state (max and rms over the contacts), and the
CPU time of one right-hand-side evaluation at the last state (best of 7 batches). Rules:
``product:NxM`` (solver.physics.traction.ellipse_quadrature, N points along the rolling direction,
M strips) and ``split:NxK`` (solver.physics.traction.split_ellipse_rule, N points along the rolling
direction, K strips on each piece between the lines of zero rolling slip).
"""

from __future__ import annotations

import argparse
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from dynamic import CASES, running_state  # noqa: E402

from solver.catalogue import resolve_case  # noqa: E402
from solver.inputs import to_inputs  # noqa: E402
from solver.models.dynamic import SimulationOptions  # noqa: E402
from solver.models.dynamic import layout as L  # noqa: E402
from solver.models.dynamic.kernels import rhs  # noqa: E402
from solver.models.dynamic.params import build_params, model_history  # noqa: E402
from solver.physics import traction as tr  # noqa: E402

DEFAULT_RULES = (
    "product:2x8",
    "product:4x8",
    "product:4x16",
    "split:2x3",
    "split:3x2",
    "split:3x3",
    "split:4x3",
    "split:4x4",
)
REFERENCE = "product:48x96"


def node_table(spec: str) -> np.ndarray:
    """Node table of a rule written ``product:NxM`` or ``split:NxK``."""
    kind, counts = spec.split(":")
    n, m = (int(c) for c in counts.split("x"))
    table = tr.split_ellipse_rule(n, m) if kind == "split" else tr.ellipse_quadrature(n, m)
    return np.ascontiguousarray(table)


def evaluate(history, par, y, nodes):
    """Contact records (inner then outer) of one right-hand side with the node table ``nodes``."""
    z = int(par.ball_count)
    rec_i = np.zeros((z, L.N_CONTACT_RECORD))
    rec_o = np.zeros((z, L.N_CONTACT_RECORD))
    rhs(y, 0.0, history, par, nodes, np.zeros_like(y), rec_i, rec_o, np.zeros(z))
    return np.concatenate([rec_i, rec_o])


def evaluation_cost(history, par, y, nodes, repeats=300):
    """CPU seconds of one right-hand side (best of 7 batches)."""
    z = int(par.ball_count)
    rec_i = np.zeros((z, L.N_CONTACT_RECORD))
    rec_o = np.zeros((z, L.N_CONTACT_RECORD))
    dydt, pocket = np.zeros_like(y), np.zeros(z)
    rhs(y, 0.0, history, par, nodes, dydt, rec_i, rec_o, pocket)
    best = float("inf")
    for _ in range(7):
        start = time.process_time()
        for _ in range(repeats):
            rhs(y, 0.0, history, par, nodes, dydt, rec_i, rec_o, pocket)
        best = min(best, (time.process_time() - start) / repeats)
    return best


def run_case(label, states, rules):
    inputs = to_inputs(resolve_case(CASES[label]))
    inputs = replace(inputs, lubricant=replace(inputs.lubricant, traction_model="rheology"))
    options = SimulationOptions()
    par = build_params(inputs, options)
    history = model_history(inputs)
    tables = {spec: node_table(spec) for spec in rules}
    errors = {spec: [] for spec in rules}
    y = None
    for revolutions in states:
        y = running_state(inputs, options, revolutions)
        ref = evaluate(history, par, y, node_table(REFERENCE))
        n = ref[:, L.K_NORMAL : L.K_NORMAL + 3]
        force = ref[:, L.K_F_BALL : L.K_F_BALL + 3]
        moment = ref[:, L.K_M_BALL : L.K_M_BALL + 3]
        tangential = force - np.sum(force * n, axis=1)[:, None] * n
        f_scale = np.max(np.linalg.norm(tangential, axis=1))
        m_scale = np.max(np.linalg.norm(moment, axis=1))
        for spec, table in tables.items():
            rec = evaluate(history, par, y, table)
            df = np.linalg.norm(rec[:, L.K_F_BALL : L.K_F_BALL + 3] - force, axis=1) / f_scale
            dm = np.linalg.norm(rec[:, L.K_M_BALL : L.K_M_BALL + 3] - moment, axis=1) / m_scale
            errors[spec].append(
                (df.max(), np.sqrt(np.mean(df**2)), dm.max(), np.sqrt(np.mean(dm**2)))
            )
    print(f"\n== {label} (rheology), states at {', '.join(f'{s:g}' for s in states)} revolutions")
    print(f"   errors against {REFERENCE}, relative to the largest tangential force / moment")
    print(
        f"   {'rule':14s} {'force max':>10s} {'rms':>8s} {'moment max':>11s} {'rms':>8s}  one RHS"
    )
    for spec, table in tables.items():
        e = np.max(np.array(errors[spec]), axis=0)
        cost = evaluation_cost(history, par, y, table)
        print(
            f"   {spec:14s} {e[0]:10.4f} {e[1]:8.4f} {e[2]:11.4f} {e[3]:8.4f}  {cost * 1e6:6.1f} us"
        )


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES))
    parser.add_argument("--states", nargs="+", type=float, default=[0.1, 0.35, 0.6])
    parser.add_argument("--rules", nargs="+", default=list(DEFAULT_RULES))
    args = parser.parse_args(argv)
    for label in args.cases:
        run_case(label, args.states, args.rules)


if __name__ == "__main__":
    main()
