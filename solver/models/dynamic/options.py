"""Run options of the dynamic model: overrides of the case's ``[simulation]`` values, and the
numerical knobs that are not case keys.

Tests and the command line switch parts of the physics off through these; every override left at
None takes the case's value (:class:`solver.inputs.SimulationInputs`, filled from the case schema).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace

from solver.case.schema import field as schema_field
from solver.case.validate import check_value
from solver.errors import CaseError, Problem
from solver.physics.traction import LAW_RHEOLOGY, LAW_SLIP_CURVE
from solver.results.summary import UNSETTLED_SKIP_FRACTION

from .integrate import registry as integrate_registry

#: Options that override a ``[simulation]`` case key: option -> (SimulationInputs field, case key).
CASE_OVERRIDES = {
    "traction": ("traction", "simulation.ball_race_traction"),
    "damping_ratio": ("damping_ratio", "simulation.contact_damping_ratio"),
    "gravity": ("gravity", "simulation.gravity_m_s2"),
    "cage": ("cage", "simulation.model_cage"),
    "tolerance": ("tolerance", "simulation.tolerance"),
    "shaft_revolutions": ("shaft_revolutions", "simulation.shaft_revolutions"),
    "samples_per_revolution": ("samples_per_revolution", "simulation.samples_per_revolution"),
}

#: Default ellipse quadrature of the product rule (points along the rolling direction, strips
#: across the groove) per traction law (option ``quadrature`` = None). Slip curve: the local
#: traction depends on the slip only, which varies linearly along the rolling direction, and two
#: points there give the results of four within 0.015 of the accuracy contract's allowances
#: (docs/numerics.md) at half the cost.
DEFAULT_QUADRATURE = {LAW_SLIP_CURVE: (2, 8), LAW_RHEOLOGY: (4, 8)}

#: Ellipse rules (option ``ellipse_rule``): "product", the fixed product rule of
#: solver.physics.traction.ellipse_quadrature; "split", the rule of
#: solver.physics.traction.split_ellipse_rule, whose strips are placed per contact on the pieces of
#: the major axis between the lines of zero rolling slip (where the rheology's saturated stress
#: changes sign).
ELLIPSE_RULES = ("product", "split")

#: Default ellipse rule per traction law (option ``ellipse_rule`` = None and no ``quadrature``).
#: Rheology: its stress saturates within a few mm/s of slip, so across the groove it jumps where
#: the rolling slip changes sign; the split rule with 3 x 3 nodes per piece (at most 27) is closer
#: to the converged integral than the product rule's 4 x 8 and 12 % cheaper (docs/numerics.md).
DEFAULT_ELLIPSE_RULE = {LAW_SLIP_CURVE: "product", LAW_RHEOLOGY: "split"}

#: Default (points along the rolling direction, strips per piece) of the split rule.
DEFAULT_SPLIT_COUNTS = (3, 3)

#: Integration methods of the dynamic model (option ``method``): the keys of the steppers'
#: registry, solver.models.dynamic.integrate.registry.
METHODS = integrate_registry.METHODS
INTEGRATION_METHODS = METHODS


@dataclass(frozen=True)
class SimulationOptions:
    """Options of :func:`solver.models.dynamic.simulate` (SI units).

    The first seven override the case's ``[simulation]`` values (:data:`CASE_OVERRIDES`; None, the
    default: the case's value; the bounds are those of the case keys, docs/case-format.md).

    - ``traction``: ellipse-integrated EHL traction at the ball-race contacts (False: frictionless).
    - ``damping_ratio``: critical-damping ratio zeta of the ball-race normal contacts (physics.md
      §2.6.6; 0 = undamped).
    - ``gravity``: gravitational acceleration [m/s^2], acting along -z of the inertial frame.
    - ``cage``: model the cage (pockets and guiding land). False: balls are free to bunch.
    - ``ring_free``: inner-ring translations are degrees of freedom under the applied loads (False:
      the ring is held at its initial, quasi-static position).
    - ``tolerance``: local error tolerance of the adaptive integrator, relative to the
      characteristic scales of each state component (deflection, contact velocity, ...).
    - ``shaft_revolutions`` / ``samples_per_revolution``: override the case's ``[simulation]``
      values.
    - ``chunk_samples``: output samples per integration chunk (progress/cancel granularity).
    - ``analysis_skip_fraction``: fraction of the run skipped before the trajectory metrics when
      the run does not settle (a settled run is analysed from its settling time on;
      solver.results.summary).
    - ``quadrature``: (points along the rolling direction, strips across the groove) of the ellipse
      traction rule; with ``ellipse_rule`` = "split", (points along the rolling direction, strips
      on each piece between the lines of zero rolling slip). None: :data:`DEFAULT_QUADRATURE` of
      the case's traction law (product rule) or :data:`DEFAULT_SPLIT_COUNTS` (split rule).
    - ``ellipse_rule``: "product" or "split" (:data:`ELLIPSE_RULES`); None: "product" when
      ``quadrature`` is given, else :data:`DEFAULT_ELLIPSE_RULE` of the case's traction law.
    - ``pocket_stiffness`` [N/m], ``pocket_damping_ratio``: linear ball-pocket contact law (None:
      solver.physics.cage_contact.pocket_stiffness_estimate for a glass-filled polyamide cage).
    - ``land_stiffness`` [N/m]: cage-land metal contact (None: land_contact_stiffness_estimate).
    - ``friction_regularisation`` [m/s]: slip speed below which friction laws are smoothed.
    - ``heathcote``: evaluate the slip on the curved deformed surface (differential slip).
    - ``inner_ring_mass`` [kg]: None = estimated from the ring cross-section (width 2 D).
    - ``max_steps_per_chunk``: safety bound on the integrator steps in one chunk.
    - ``method``: integration method (:data:`METHODS`). "dopri5": explicit Dormand–Prince 5(4)
      (solver.models.dynamic.integrate.dopri5); "imex": additive Runge–Kutta ARK4(3)6L[2]SA with
      the cage's guiding-land film implicit (solver.models.dynamic.integrate.imex), whose step is
      not limited by the film's squeeze damping on a cage running near its land; "auto"
      (default): Dormand–Prince steps, and the additive steps only where that film would limit
      the explicit step. docs/numerics.md compares them.
    - ``start``: "quasistatic" (the project's Jones–Harris solution, solver.models.quasistatic;
      falls back to "equilibrium" if it finds no solution) or "equilibrium" (the model's own
      force balance without gyroscopic moment, see ``initial.initial_state``).
    """

    traction: bool | None = None
    damping_ratio: float | None = None
    gravity: float | None = None
    cage: bool | None = None
    ring_free: bool = True
    tolerance: float | None = None
    shaft_revolutions: float | None = None
    samples_per_revolution: int | None = None
    chunk_samples: int = 60
    analysis_skip_fraction: float = UNSETTLED_SKIP_FRACTION
    quadrature: tuple[int, int] | None = None
    ellipse_rule: str | None = None
    pocket_stiffness: float | None = None
    pocket_damping_ratio: float = 0.1
    land_stiffness: float | None = None
    friction_regularisation: float = 1.0e-3
    heathcote: bool = True
    inner_ring_mass: float | None = None
    max_steps_per_chunk: int = 2_000_000
    method: str = "auto"
    start: str = "quasistatic"

    def resolved(self, simulation) -> SimulationOptions:
        """Copy with every case override filled: the option where given, else the value of
        ``simulation`` (:class:`solver.inputs.SimulationInputs`)."""
        changes = {
            name: getattr(simulation, attribute)
            for name, (attribute, _) in CASE_OVERRIDES.items()
            if getattr(self, name) is None
        }
        return replace(self, **changes)

    def validated(self) -> SimulationOptions:
        """Return self after checking every value; raise CaseError naming the option otherwise."""
        problems = []
        for name, (_, case_key) in CASE_OVERRIDES.items():
            value = getattr(self, name)
            if value is not None:  # the bounds of the case key it overrides
                check_value(schema_field(case_key), f"simulation option {name}", value, problems)
        positive = ("pocket_stiffness", "land_stiffness", "friction_regularisation")
        for f in fields(self):
            v = getattr(self, f.name)
            key = f"simulation option {f.name}"
            if f.name in CASE_OVERRIDES:
                continue
            if isinstance(v, float) and not math.isfinite(v):
                problems.append(Problem(f.name, f"{key} = {v!r}: must be a finite number"))
            elif f.name in positive and v is not None and not v > 0:
                problems.append(Problem(f.name, f"{key} = {v!r}: must be greater than 0"))
        if self.pocket_damping_ratio < 0:
            problems.append(
                Problem(
                    "pocket_damping_ratio",
                    f"simulation option pocket_damping_ratio = {self.pocket_damping_ratio!r}: "
                    "must be >= 0",
                )
            )
        if not 0.0 <= self.analysis_skip_fraction < 1.0:
            problems.append(
                Problem(
                    "analysis_skip_fraction",
                    f"simulation option analysis_skip_fraction = {self.analysis_skip_fraction!r}: "
                    "must lie in [0, 1)",
                )
            )
        if self.chunk_samples < 1:
            problems.append(
                Problem(
                    "chunk_samples",
                    f"simulation option chunk_samples = {self.chunk_samples}: must be >= 1",
                )
            )
        if self.method not in METHODS:
            problems.append(
                Problem(
                    "method",
                    f"simulation option method = {self.method!r}: must be one of "
                    + ", ".join(repr(m) for m in METHODS),
                )
            )
        if self.ellipse_rule is not None and self.ellipse_rule not in ELLIPSE_RULES:
            problems.append(
                Problem(
                    "ellipse_rule",
                    f"simulation option ellipse_rule = {self.ellipse_rule!r}: must be one of "
                    + ", ".join(repr(m) for m in ELLIPSE_RULES),
                )
            )
        if self.start not in ("quasistatic", "equilibrium"):
            problems.append(
                Problem(
                    "start",
                    f"simulation option start = {self.start!r}: must be "
                    "'quasistatic' or 'equilibrium'",
                )
            )
        if problems:
            raise CaseError(problems)
        return self
