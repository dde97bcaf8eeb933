"""The rheology's traction of one contact against its entrainment speed: the table of
docs/numerics.md, "Low entrainment speed".

    python benchmarks/experiments/low_entrainment.py

A contact of the 209 case's oil (the schema's default oil at its inlet temperature) under 500 N
(semi-axes 1.5 mm x 0.2 mm, R_x 5 mm, split rule 3 x 3), pure rolling slip along the rolling
direction. For each entrainment speed u_e the central film (solver.physics.rheology
.film_and_rolling_force, inlet heating included) and the traction force of
solver.physics.traction.ellipse_traction_law with the transit time b / u_e: the slope at a slip of
0.1 um/s, the slip at which the force reaches half its largest value over slips from 1 nm/s to
10 m/s, and that largest value over the load. This is the law the dynamic model freezes below
u_min (solver.physics.rheology.ENTRAINMENT_FLOOR).
"""

from __future__ import annotations

import math

import numpy as np

from solver.catalogue import resolve_case
from solver.inputs import to_inputs
from solver.physics import traction as tr
from solver.physics.rheology import film_and_rolling_force

LOAD = 500.0  # N
SEMI_MAJOR, SEMI_MINOR, R_X = 1.5e-3, 0.2e-3, 5e-3  # m
SPEEDS = (1e-4, 1e-2, 0.1, 1.0, 10.0, 20.0)  # m/s


def main() -> None:
    inputs = to_inputs(resolve_case("209-radial"))
    rheology = inputs.lubricant.rheology_array()
    eprime = inputs.geometry.effective_modulus
    p_max = 1.5 * LOAD / (math.pi * SEMI_MAJOR * SEMI_MINOR)
    nodes = tr.split_ellipse_rule(3, 3)
    curve = tr.constant_traction_parameters(0.0)  # not read by the rheology law

    def force(entrainment: float, slip: float) -> tuple[float, float]:
        film, _, _ = film_and_rolling_force(
            entrainment,
            slip / entrainment,
            LOAD,
            R_X,
            SEMI_MAJOR / SEMI_MINOR,
            p_max,
            eprime,
            rheology,
        )
        contact = np.zeros(tr.CONTACT_SIZE)
        contact[tr.CT_NORMAL + 2] = 1.0
        contact[tr.CT_ROLLING] = 1.0
        contact[tr.CT_SEMI_MAJOR] = SEMI_MAJOR
        contact[tr.CT_SEMI_MINOR] = SEMI_MINOR
        contact[tr.CT_LOAD] = LOAD
        kinematics = np.zeros(tr.KIN_SIZE)
        kinematics[tr.KIN_BALL_VELOCITY] = slip
        out = np.zeros(tr.TRACTION_OUT_SIZE)
        transit = SEMI_MINOR / entrainment
        tr.ellipse_traction_law(
            contact, kinematics, tr.LAW_RHEOLOGY, curve, rheology, film, transit, 0.0, nodes, out
        )
        return -out[tr.TR_FORCE], film

    print("| u_e [m/s] | h_c [nm] | slope [N s/m] | slip at half the limit [mm/s] | F_max / Q |")
    print("|---|---|---|---|---|")
    slips = np.logspace(-9, 1, 400)
    for u in SPEEDS:
        small, film = force(u, 1e-7)
        values = np.array([force(u, s)[0] for s in slips])
        half = slips[np.argmax(values > 0.5 * values.max())]
        print(
            f"| {u:g} | {film * 1e9:.3g} | {small / 1e-7:.2g} | {half * 1e3:.2g} | "
            f"{values.max() / LOAD:.3f} |"
        )


if __name__ == "__main__":
    main()
