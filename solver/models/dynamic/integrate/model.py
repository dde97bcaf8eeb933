"""The bearing model as the steppers see it: one record and the two kernels they call.

The steppers call the model only through :func:`evaluate` (the right-hand side at a state and a
time: the model's operating history ``history`` is read at that time) and
:func:`after_step` (run after every accepted step: the dynamic model renormalises its quaternions
there and reports a ball that left the raceways). numba compiles a function passed as an argument
anew in every process, so the kernels are bound here by import rather than passed in. Two models
share the steppers: one bearing (:class:`BearingModel`) and a set of bearings on one rigid shaft
(:class:`SetModel`, :mod:`..set_kernels`); :func:`evaluate` and :func:`after_step` pick the
kernels by the record's type when numba compiles them.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit, types
from numba.extending import overload

from .. import layout as L
from ..kernels import post_step, rhs_into, rhs_work
from ..set_kernels import SetWork, set_post_step, set_rhs_into
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


class SetModel(NamedTuple):
    """A bearing set on one rigid shaft (:mod:`..set_kernels`)."""

    bearings: tuple  # one BearingModel per bearing, own frame
    shaft: tuple  # set_kernels.SetShaft


def scratch(model):
    """The scratch record of one right-hand-side evaluation (``Workspace.rhs``)."""
    if isinstance(model, SetModel):
        return SetWork(
            tuple(rhs_work(int(m.par.ball_count)) for m in model.bearings),
            np.zeros(5),
            np.zeros(5),
            np.zeros(5),
        )
    return rhs_work(int(model.par.ball_count))


def _is_set_model(model) -> bool:
    return isinstance(model, types.NamedTuple) and model.instance_class is SetModel


def _model_rhs(y, t, model, out, rhs):
    """The right-hand side of ``model`` (compiled by type, :func:`_model_rhs_of`)."""
    raise NotImplementedError("_model_rhs runs only in compiled code")


def _model_post_step(y, model):
    """The projection of ``model`` (compiled by type, :func:`_model_post_step_of`)."""
    raise NotImplementedError("_model_post_step runs only in compiled code")


@overload(_model_rhs)
def _model_rhs_of(y, t, model, out, rhs):
    if _is_set_model(model):

        def set_rhs(y, t, model, out, rhs):
            set_rhs_into(y, t, model.bearings, model.shaft, out, rhs, runtime_bool(False))

        return set_rhs

    def bearing_rhs(y, t, model, out, rhs):
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

    return bearing_rhs


@overload(_model_post_step)
def _model_post_step_of(y, model):
    if _is_set_model(model):

        def set_projection(y, model):
            return set_post_step(y, model.bearings, model.shaft)

        return set_projection

    def bearing_projection(y, model):
        return post_step(y, model.par, model.rec_inner, model.rec_outer)

    return bearing_projection


@njit(cache=True)
def evaluate(y, t, model, out, rhs):
    """``out`` <- dy/dt at ``y`` and time ``t`` [s], with the scratch record ``rhs``
    (:func:`scratch`)."""
    _model_rhs(y, t, model, out, rhs)


@njit(cache=True)
def after_step(y, model):
    """Projection after an accepted step; False when the state left the model's domain."""
    return _model_post_step(y, model)
