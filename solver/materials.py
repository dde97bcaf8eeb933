"""Elastic and inertial material data (SI units), and the built-in materials table.

A case file names its materials (``bearing_steel``, ``silicon_nitride``) or defines its own under
``[materials]``; this module is the one place where the built-in values live.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Material:
    """An isotropic elastic material.

    Attributes are SI: ``youngs_modulus`` in Pa, ``poisson_ratio`` dimensionless, ``density`` in
    kg/m^3. ``hysteresis_loss``: fraction of the elastic strain energy lost per rolling cycle
    (elastic hysteresis, Tabor; about 0.5-2 % for hardened bearing steel, physics.md §2.6.5 [M/E]);
    materials defined in a case file get the default.
    """

    name: str
    youngs_modulus: float
    poisson_ratio: float
    density: float
    hysteresis_loss: float = 0.01

    @property
    def compliance(self) -> float:
        """(1 - nu^2) / E in 1/Pa: this body's share of the Hertz elastic constant eta."""
        return (1.0 - self.poisson_ratio**2) / self.youngs_modulus


BUILTIN_MATERIALS: dict[str, Material] = {
    # AISI 52100 through-hardened bearing steel.
    "bearing_steel": Material("bearing_steel", 208.0e9, 0.3, 7800.0, hysteresis_loss=0.01),
    # Hot-isostatically-pressed silicon nitride (hybrid-bearing balls).
    # Ceramics dissipate less than steel under cyclic contact stress [E].
    "silicon_nitride": Material("silicon_nitride", 310.0e9, 0.26, 3200.0, hysteresis_loss=0.005),
}


def effective_modulus(body_1: Material, body_2: Material) -> float:
    """Hertz effective modulus E' = 2 / eta, with eta = sum of (1 - nu^2)/E, in Pa."""
    return 2.0 / (body_1.compliance + body_2.compliance)
