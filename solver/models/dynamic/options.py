"""Run options of the dynamic model that are not (yet) case-file keys.

Tests switch parts of the physics off through these; the defaults are the full model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from types import MappingProxyType

from solver.errors import CaseError, Problem
from solver.results.summary import UNSETTLED_SKIP_FRACTION


@dataclass(frozen=True)
class SimulationOptions:
    """Options of :func:`solver.models.dynamic.simulate` (SI units).

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
      traction rule.
    - ``pocket_stiffness`` [N/m], ``pocket_damping_ratio``: linear ball-pocket contact law (None:
      solver.physics.cage_contact.pocket_stiffness_estimate for a glass-filled polyamide cage).
    - ``land_stiffness`` [N/m]: cage-land metal contact (None: land_contact_stiffness_estimate).
    - ``friction_regularisation`` [m/s]: slip speed below which friction laws are smoothed.
    - ``heathcote``: evaluate the slip on the curved deformed surface (differential slip).
    - ``inner_ring_mass`` [kg]: None = estimated from the ring cross-section (width 2 D).
    - ``max_steps_per_chunk``: safety bound on the integrator steps in one chunk.
    - ``start``: "quasistatic" (the project's Jones–Harris solution, solver.models.quasistatic;
      falls back to "equilibrium" if it finds no solution) or "equilibrium" (the model's own
      force balance without gyroscopic moment, see ``initial.initial_state``).
    """

    traction: bool = True
    damping_ratio: float = 0.05
    gravity: float = 9.81
    cage: bool = True
    ring_free: bool = True
    tolerance: float = 1e-4
    shaft_revolutions: float | None = None
    samples_per_revolution: int | None = None
    chunk_samples: int = 60
    analysis_skip_fraction: float = UNSETTLED_SKIP_FRACTION
    quadrature: tuple[int, int] = (4, 8)
    pocket_stiffness: float | None = None
    pocket_damping_ratio: float = 0.1
    land_stiffness: float | None = None
    friction_regularisation: float = 1.0e-3
    heathcote: bool = True
    inner_ring_mass: float | None = None
    max_steps_per_chunk: int = 2_000_000
    start: str = "quasistatic"

    def validated(self) -> SimulationOptions:
        """Return self after checking every value; raise CaseError naming the option otherwise."""
        problems = []
        positive = ("tolerance", "pocket_stiffness", "land_stiffness", "friction_regularisation")
        for f in fields(self):
            v = getattr(self, f.name)
            key = f"simulation option {f.name}"
            if isinstance(v, float) and not math.isfinite(v):
                problems.append(Problem(f.name, f"{key} = {v!r}: must be a finite number"))
            elif f.name in positive and v is not None and not v > 0:
                problems.append(Problem(f.name, f"{key} = {v!r}: must be greater than 0"))
        for name in ("damping_ratio", "gravity", "pocket_damping_ratio"):
            if getattr(self, name) < 0:
                problems.append(
                    Problem(
                        name, f"simulation option {name} = {getattr(self, name)!r}: must be >= 0"
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
        if self.shaft_revolutions is not None and not self.shaft_revolutions > 0:
            problems.append(
                Problem(
                    "shaft_revolutions",
                    f"simulation option shaft_revolutions = {self.shaft_revolutions!r}: "
                    "must be > 0",
                )
            )
        if self.samples_per_revolution is not None and not self.samples_per_revolution >= 4:
            problems.append(
                Problem(
                    "samples_per_revolution",
                    f"simulation option samples_per_revolution = {self.samples_per_revolution!r}: "
                    "must be >= 4",
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


#: [simulation] case keys (optional; when the case schema has them) -> SimulationOptions fields.
CASE_KEYS = MappingProxyType(
    {
        "ball_race_traction": "traction",
        "contact_damping_ratio": "damping_ratio",
        "gravity_m_s2": "gravity",
        "tolerance": "tolerance",
        "model_cage": "cage",
    }
)


def options_from_case(case, base: SimulationOptions | None = None) -> SimulationOptions:
    """``base`` (default options) updated with the optional [simulation] keys of ``case``
    (``CASE_KEYS``); keys the case does not define keep their defaults."""
    from dataclasses import replace

    base = base or SimulationOptions()
    sim = getattr(case, "simulation", None)
    changes = {}
    for key, name in CASE_KEYS.items():
        value = getattr(sim, key, None) if sim is not None else None
        if value is not None:
            changes[name] = value
    return replace(base, **changes)
