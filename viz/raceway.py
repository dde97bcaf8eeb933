"""Points on the raceway grooves (torus surfaces) in each ring's own frame, physics.md §2.8.1.

Pure numpy, no rendering. A raceway point is given by its circumferential coordinate ``phi`` (rad,
azimuth in the ring frame, from +y towards +z) and its groove latitude ``alpha`` (rad, the contact
angle). Races are indexed ``INNER = 0`` and ``OUTER = 1`` like the ``race`` dimension of a result.

    P^r(phi, alpha) = (x_c -+ r sin(alpha),
                       (rho_c -+ r cos(alpha)) cos(phi),
                       (rho_c -+ r cos(alpha)) sin(phi))

upper signs for the inner groove, lower signs for the outer one. Lengths in m.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

INNER, OUTER = 0, 1
RACES = ("inner", "outer")


@dataclass(frozen=True)
class Groove:
    """One groove: curvature-centre circle (radius ``rho_c``, axial position ``x_c``, m), groove
    radius ``r`` (m) and ``sign`` = +1 for the inner groove, -1 for the outer one."""

    rho_c: float
    x_c: float
    r: float
    sign: float

    def point(self, phi, alpha, lift: float = 0.0) -> np.ndarray:
        """Surface points, shape ``broadcast(phi, alpha).shape + (3,)``, m, ring frame.

        ``lift`` (m) moves the point off the surface towards the curvature centre, i.e. into the
        space of the ball, so that marks drawn on the raceway are not hidden by the ring surface.
        """
        phi, alpha = np.asarray(phi, float), np.asarray(alpha, float)
        if phi.shape != alpha.shape:
            phi, alpha = np.broadcast_arrays(phi, alpha)
        r = self.r - lift
        radius = self.rho_c - self.sign * r * np.cos(alpha)
        out = np.empty(phi.shape + (3,))
        out[..., 0] = self.x_c - self.sign * r * np.sin(alpha)
        out[..., 1] = radius * np.cos(phi)
        out[..., 2] = radius * np.sin(phi)
        return out

    def contact_radius(self, alpha) -> np.ndarray:
        """Distance of the raceway point from the bearing axis, m: rho_c -+ r cos(alpha)."""
        return self.rho_c - self.sign * self.r * np.cos(np.asarray(alpha, float))


def groove_half_angle(groove: Groove, ball_diameter: float, shoulder_radius: float) -> float:
    """Groove latitude theta (rad) of the shoulder edges, which are drawn at +-theta.

    cos(theta) = |rho_c - shoulder_radius| / r; when no usable shoulder is given the shoulder
    height is 0.2 D (a typical spindle-bearing value, drawing only).
    """
    D, r = ball_diameter, groove.r
    s = groove.sign  # +1 inner (material below the groove), -1 outer (material above)
    depth = (
        s * (shoulder_radius - (groove.rho_c - s * r)) if np.isfinite(shoulder_radius) else np.nan
    )
    if not (np.isfinite(depth) and 0.05 * D < depth < 0.9 * r):
        depth = 0.2 * D
    return math.acos(1.0 - depth / r)


def grooves(geometry) -> tuple[Groove, Groove]:
    """(inner, outer) grooves of a :class:`solver.geometry.BearingGeometry` (unloaded reference)."""
    inner = Groove(
        rho_c=geometry.inner_curvature_center_radius,
        x_c=geometry.inner_curvature_center_axial,
        r=geometry.inner_groove_radius,
        sign=1.0,
    )
    outer = Groove(
        rho_c=geometry.outer_curvature_center_radius,
        x_c=geometry.outer_curvature_center_axial,
        r=geometry.outer_groove_radius,
        sign=-1.0,
    )
    return inner, outer


def exaggerate(alpha, reference: float, factor: float):
    """Scale the across-groove deviation of ``alpha`` from ``reference`` by ``factor`` (rad).

    factor 1 returns ``alpha`` unchanged; real deviations are often a fraction of a degree, so the
    3-D view offers factors up to ~20.
    """
    return reference + factor * (np.asarray(alpha, float) - reference)


def ellipse_angles(groove: Groove, phi, alpha, semi_major, semi_minor, n: int = 24):
    """The groove angles (rad) of contact ellipses wrapped on the groove (physics.md §2.8.3):
    (phi(tau), alpha(tau)), each of shape (..., n), at ``n`` angles tau over a turn from 0.

    ``phi``, ``alpha`` (rad) are the ellipse centres; ``semi_major`` (m) lies across the groove,
    ``semi_minor`` (m) along the rolling direction. alpha(tau) = alpha + (a/r) cos(tau),
    phi(tau) = phi + (b / rho_contact) sin(tau).
    """
    cos_tau, sin_tau = _unit_circle(n)
    phi = np.asarray(phi, float)[..., None]
    alpha = np.asarray(alpha, float)[..., None]
    a = np.asarray(semi_major, float)[..., None]
    b = np.asarray(semi_minor, float)[..., None]
    rho = groove.contact_radius(alpha)
    return phi + b / rho * sin_tau, alpha + a / groove.r * cos_tau


def ellipse_outline(groove: Groove, phi, alpha, semi_major, semi_minor, n: int = 24, lift=0.0):
    """Contact ellipses wrapped on the groove (:func:`ellipse_angles`), points shape (..., n, 3),
    m; ``lift`` as :meth:`Groove.point`."""
    return groove.point(*ellipse_angles(groove, phi, alpha, semi_major, semi_minor, n), lift=lift)


@functools.cache
def _unit_circle(n: int) -> tuple[np.ndarray, np.ndarray]:
    """cos and sin of ``n`` angles tau evenly spaced over a turn from 0 (read-only arrays)."""
    tau = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
    out = np.cos(tau), np.sin(tau)
    for values in out:
        values.flags.writeable = False
    return out


def shoulder_angles(geometry) -> tuple[float, float]:
    """(inner, outer) groove latitude theta (rad) of the shoulder edges drawn at +-theta."""
    inner, outer = grooves(geometry)
    return (
        groove_half_angle(inner, geometry.ball_diameter, geometry.inner_shoulder_diameter / 2),
        groove_half_angle(outer, geometry.ball_diameter, geometry.outer_shoulder_diameter / 2),
    )
