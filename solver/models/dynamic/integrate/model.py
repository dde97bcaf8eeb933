"""The bearing model as the steppers see it: one record and the two kernels they call.

The steppers call the model only through :func:`evaluate` (the right-hand side at a state and a
time: the model's operating history ``history`` is read at that time) and
:func:`after_step` (run after every accepted step: the dynamic model renormalises its quaternions
there and reports a ball that left the raceways). numba compiles a function passed as an argument
anew in every process, so the kernels are bound here by import rather than passed in; a model of
several bearings on one shaft changes this module and its record, not the steppers.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from .. import layout as L
from ..kernels import post_step, rhs_into, rhs_work
from ..unliteral import runtime_bool


class BearingModel(NamedTuple):
    """What the right-hand side reads besides the state, and the records it writes."""

    history: tuple  # solver.history.HistoryRecord: the imposed inputs against time
    par: tuple  # solver.models.dynamic.params.ModelParams
    quad: np.ndarray  # ellipse quadrature nodes (params.build_quadrature)
    rec_inner: np.ndarray  # (Z, layout.N_CONTACT_RECORD) inner contact records, written
    rec_outer: np.ndarray  # (Z, layout.N_CONTACT_RECORD) outer contact records, written
    pocket: np.ndarray  # (Z,) pocket normal forces [N], written


def bearing_model(history, par, quad) -> BearingModel:
    """A :class:`BearingModel` with fresh contact records."""
    z = int(par.ball_count)
    return BearingModel(
        history,
        par,
        quad,
        np.zeros((z, L.N_CONTACT_RECORD)),
        np.zeros((z, L.N_CONTACT_RECORD)),
        np.zeros(z),
    )


def scratch(model: BearingModel):
    """The scratch record of one right-hand-side evaluation (``Workspace.rhs``)."""
    return rhs_work(int(model.par.ball_count))


@njit(cache=True)
def evaluate(y, t, model, out, rhs):
    """``out`` <- dy/dt at ``y`` and time ``t`` [s], with the scratch record ``rhs``
    (:func:`scratch`)."""
    rhs_into(
        y,
        t,
        model.history,
        model.par,
        model.quad,
        out,
        model.rec_inner,
        model.rec_outer,
        model.pocket,
        rhs,
        runtime_bool(False),
    )


@njit(cache=True)
def after_step(y, model):
    """Projection after an accepted step; False when the state left the model's domain."""
    return post_step(y, model.par, model.rec_inner, model.rec_outer)
