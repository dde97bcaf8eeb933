"""Gupta-style dynamic model of an angular contact ball bearing (physics.md §2.6-2.8).

Public API: :func:`simulate` (returns an ``xarray.Dataset``, results-schema.md) and
:class:`SimulationOptions`. The model reads :class:`solver.inputs.Inputs` (SI), built once from the
case. Internals: ``layout`` (state/parameter slots), ``kernels`` (numba contact laws and
right-hand side), ``integrate`` (the integration methods: Dormand-Prince 5(4), additive
Runge-Kutta with the cage's land film implicit, and the default switching method; their shared
step control), ``initial`` (quasi-static start), ``observe``/``output`` (Dataset).
"""

from .options import SimulationOptions
from .simulate import simulate

__all__ = ["simulate", "SimulationOptions"]
