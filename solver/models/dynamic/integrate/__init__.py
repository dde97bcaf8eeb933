"""Integrators of the dynamic model, one module per method (``dopri5``, ``imex``), their shared
step control (``control``), the model's face towards them (``model``) and the table of methods
(``registry``): ``stepper(method)`` and ``METHODS``. docs/extending.md walks through adding a
method. This package imports no numba kernel until a stepper is asked for.
"""

from .registry import METHODS, Stepper, stepper

__all__ = ["METHODS", "Stepper", "stepper", "run"]


def run(method, history, par, quad, y, times, outputs, control, h, t=0.0):
    """One call of the stepper of ``method`` on the bearing model ``history`` (the operating
    history, :class:`solver.history.HistoryRecord`), ``par``, ``quad`` from time
    ``t`` with first step ``h`` [s] (``y`` updated in place, ``outputs`` filled; ``control``:
    :class:`.control.StepControl`); returns the progress record (:data:`.control.PROGRESS`)."""
    from .model import bearing_model

    chosen = stepper(method)
    model = bearing_model(history, par, quad)
    work = chosen.workspace(model, y.shape[0], t, h)
    chosen.advance(y, times, outputs, control, work, model)
    return work.progress[0]
