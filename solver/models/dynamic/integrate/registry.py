"""The integration methods of the dynamic model: one line each, naming the stepper module under
``integrate/`` and the variant its ``build`` makes. The method list (option ``method``, the
command line's ``--method`` choices) is this table's keys; :func:`stepper` gives a method's
stepper. This module imports no numba kernel: the stepper modules are imported on first use.
"""

from __future__ import annotations

from collections.abc import Callable
from importlib import import_module
from typing import NamedTuple

#: method -> (stepper module under integrate/, variant given to its ``build``)
REGISTRY = {
    "auto": ("imex", "auto"),
    "dopri5": ("dopri5", "dopri5"),
    "imex": ("imex", "imex"),
}

#: The method names, default first.
METHODS = tuple(REGISTRY)


class Stepper(NamedTuple):
    """A method as the driver uses it."""

    advance: Callable  # numba kernel advance(y, times, outputs, control, work, model), .control
    workspace: Callable  # (model, n, t, h) -> control.Workspace for a state of n components
    note: str  # method and step control, for the Dataset's attrs


def stepper(method: str) -> Stepper:
    """The stepper of ``method`` (one of :data:`METHODS`; KeyError otherwise)."""
    module, variant = REGISTRY[method]
    return import_module(f"{__package__}.{module}").build(variant)
