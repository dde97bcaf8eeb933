"""Validation (2) of the dynamic model (the others are in test_dynamic_validation.py): with
traction and damping off it conserves mechanical energy, and its right-hand side satisfies the
momentum balance."""

from __future__ import annotations

import math

import numpy as np

from solver.models.dynamic import layout as L
from solver.models.dynamic.kernels import (
    TRACTION_WORK_SIZE,
    ball_drag,
    cage_land,
    mechanical_energy,
)
from solver.models.dynamic.params import drive_at_start
from tests.helpers.cases import spindle_inputs
from tests.helpers.dyn_helpers import evaluate, integrate_states, start

#: integrator tolerance of the conservation runs. Undamped (no traction, zero contact damping),
#: the balls' normal-contact vibrations gain energy from the integration error at looser
#: tolerances: the total energy drifts by 2e-6 (1e-4), 1.4e-2 (5e-4) and 7.5e-2 (1e-3, the
#: default) of the mean elastic energy over these 3 revolutions. Any contact damping removes it
#: (test_default_tolerance_tracks_the_energy_with_light_damping; docs/numerics.md).
CONSERVATION_TOLERANCE = 1e-4


def _energies(states, history, par, quad):
    z = int(par.ball_count)
    ri = np.zeros((z, L.N_CONTACT_RECORD))
    ro = np.zeros((z, L.N_CONTACT_RECORD))
    energy, elastic = [], []
    for s in states:
        energy.append(mechanical_energy(s, 0.0, history, par, quad, ri, ro))
        elastic.append(
            0.4
            * sum((r[:, L.K_ELASTIC] * np.maximum(r[:, L.K_DEFLECTION], 0)).sum() for r in (ri, ro))
        )
    return np.array(energy), np.array(elastic)


def test_energy_is_conserved_without_traction_and_damping():
    """3 shaft revolutions at 20 000 rpm under 500 N axial + 300 N radial, gravity on, inner ring
    free: balls run through the load zone, exchanging kinetic and elastic energy. Tolerance: the
    total energy may change by at most 1e-4 of the mean elastic (Hertz) energy, the part of the
    energy that the contact dynamics exchange (the balls' orbital kinetic energy is ~100x larger),
    at tolerance 1e-4 (``CONSERVATION_TOLERANCE``)."""
    history, par, quad, y0 = start(
        spindle_inputs(radial=300.0), traction=False, damping_ratio=0.0, cage=False
    )
    period = 2 * math.pi / drive_at_start(history).inner_speed
    times = np.linspace(0.0, 3 * period, 181)
    states, _ = integrate_states(history, par, quad, y0, times, tolerance=CONSERVATION_TOLERANCE)
    energy, elastic = _energies(states, history, par, quad)
    drift = np.abs(energy - energy[0]).max()
    assert drift < 1e-4 * elastic.mean()
    # the elastic energy really varies (the test exercises the exchange)
    ring = states[:, L.ring_base(18) : L.ring_base(18) + 3]
    assert np.ptp(ring[:, 1]) > 1e-9 or np.ptp(elastic) > 1e-3 * elastic.mean()


def test_default_tolerance_tracks_the_energy_with_light_damping():
    """With a light contact damping (zeta = 0.01, a fifth of the default) and no traction, the
    energy history at the default integrator tolerance follows a run at 1e-5 within 1e-4 of the
    mean elastic energy (measured 2.5e-5 over this revolution; undamped, 1.0e-2): the drift of
    the undamped runs is a marginal instability of exactly undamped vibrations, which any damping
    removes."""
    from solver.case.schema import field

    default = field("simulation.tolerance").default
    history, par, quad, y0 = start(
        spindle_inputs(radial=300.0), traction=False, damping_ratio=0.01, cage=False
    )
    times = np.linspace(0.0, 2 * math.pi / drive_at_start(history).inner_speed, 61)
    tight, _ = integrate_states(history, par, quad, y0, times, tolerance=1e-5)
    loose, _ = integrate_states(history, par, quad, y0, times, tolerance=default)
    e_tight, elastic = _energies(tight, history, par, quad)
    e_loose, _ = _energies(loose, history, par, quad)
    assert np.abs(e_loose - e_tight).max() < 1e-4 * elastic.mean()


def test_damping_dissipates_energy():
    """The same run with contact damping on must lose energy (sign check of the damping law)."""
    history, par, quad, y0 = start(
        spindle_inputs(radial=300.0), traction=False, damping_ratio=0.2, cage=False
    )
    # kick the balls radially so the contacts vibrate
    for j in range(18):
        b = L.ball_base(j)
        y0[b + L.B_VEL] += 0.05
    period = 2 * math.pi / drive_at_start(history).inner_speed
    times = np.linspace(0.0, 0.5 * period, 31)
    states, _ = integrate_states(history, par, quad, y0, times, tolerance=CONSERVATION_TOLERANCE)
    energy, elastic = _energies(states, history, par, quad)
    kick = 18 * 0.5 * par.ball_mass * 0.05**2
    # zeta = 0.2 at the ~70 kHz contact mode removes most of the kick within 0.5 rev
    assert energy[0] - energy[-1] > 0.25 * kick
    assert np.all(np.diff(energy) <= 1e-4 * elastic.mean())  # the conservation tolerance above


def test_linear_momentum_balance_of_the_rhs():
    """Sum of m a over balls, inner ring and cage equals the external forces: applied load on the
    ring, outer-ring contact forces on the balls, cage-land force, drag of the oil-air mixture on
    the balls and gravity (all internal
    ball-ring and ball-cage forces cancel), with traction, damping and cage on."""
    history, par, quad, y0 = start(spindle_inputs(radial=300.0))
    rng = np.random.default_rng(7)
    y = y0.copy()
    z = 18
    cb = L.cage_base(z)
    y[cb + 1 : cb + 3] += 0.9 * par.land_clearance * np.array([0.6, 0.8])  # cage against its land
    for j in range(z):
        b = L.ball_base(j)
        y[b + L.B_VEL : b + L.B_VEL + 3] += rng.normal(size=3) * 0.3
        y[b + 1 : b + 3] += rng.normal(size=2) * 5e-5  # some balls touch their pockets
    dydt, ri, ro, pocket = evaluate(y, history, par, quad)
    assert pocket.max() > 0.0
    rb = L.ring_base(z)
    total = np.zeros(3)
    for j in range(z):
        b = L.ball_base(j)
        total += par.ball_mass * dydt[b + L.B_VEL : b + L.B_VEL + 3]
    total += par.ring_mass * dydt[rb + L.R_VEL : rb + L.R_VEL + 3]
    total += par.cage_mass * dydt[cb + L.C_VEL : cb + L.C_VEL + 3]
    land = np.zeros(5)
    speeds = drive_at_start(history)[:2]
    cage_land(
        y, cb, y[rb : rb + 3], y[rb + 3 : rb + 6], *speeds, par, np.zeros(TRACTION_WORK_SIZE), land
    )
    external = ro[:, L.K_F_BALL : L.K_F_BALL + 3].sum(axis=0)
    external += np.array(drive_at_start(history)[4:7])
    assert abs(land[1]) + abs(land[2]) > 0.0  # the land force is exercised
    external += land[:3]
    drag = np.array([ball_drag(y, L.ball_base(j), par)[0] for j in range(z)])
    assert np.abs(drag).sum() > 0.0  # the oil-air drag is exercised
    external += drag.sum(axis=0)
    external[2] -= par.gravity * (z * par.ball_mass + par.cage_mass + par.ring_mass)
    np.testing.assert_allclose(total, external, atol=1e-9 * ri[:, L.K_LOAD].sum())
