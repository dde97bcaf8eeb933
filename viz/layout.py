"""Where the marks of the scene lie on the two raceways, shared by the parts that draw them.

Each raceway's groove (:mod:`viz.raceway`, ring frame, m) and its cells between the shoulder edges
(:class:`viz.tracks.TrackGrid`, rad); the outer ring's cut-away sector and its shift along the
axis (drawn apart); and the across-groove display: deviations of the contact angle from the run's
mean (the reference, rad) scaled by the exaggeration and clipped at the shoulders.
"""

from __future__ import annotations

import math

import numpy as np

from .meshes import ring_profile
from .raceway import INNER, OUTER, exaggerate, groove_half_angle, grooves
from .tracks import TrackGrid

MARK_LIFT = 0.004  # fraction of the groove radius that marks are lifted off the raceway
ELLIPSE_POINTS = 24  # outline points of a contact ellipse (and around a close-up dome)


class RacewayLayout:
    """The grooves, grids and display rules of one bearing (``geometry``) under ``options``
    (:class:`viz.options.SceneOptions`, read when used: the exaggeration may change)."""

    def __init__(self, geometry, options):
        g = geometry
        self.options = options
        self.grooves = grooves(g)
        self.shoulder_radii = (g.inner_shoulder_diameter / 2, g.outer_shoulder_diameter / 2)
        self.profiles = tuple(
            ring_profile(self.grooves[race], g.ball_diameter, self.shoulder_radii[race])
            for race in (INNER, OUTER)
        )
        self.grids = tuple(
            TrackGrid(-theta, theta)
            for theta in (
                groove_half_angle(self.grooves[race], g.ball_diameter, self.shoulder_radii[race])
                for race in (INNER, OUTER)
            )
        )
        self.outer_shift = float(options.explode) * g.ball_diameter  # m along x
        # about which the across-groove deviation is exaggerated (rad); the run's mean once shown
        self.reference = [g.free_contact_angle] * 2

    def display_alpha(self, race: int, alpha):
        """Exaggerated groove latitude (rad), clipped at the shoulder edges."""
        grid = self.grids[race]
        shown = exaggerate(alpha, self.reference[race], self.options.exaggeration)
        return np.clip(shown, grid.alpha_lo, grid.alpha_hi)

    def in_cutaway(self, race: int, phi) -> np.ndarray:
        """True where a mark on ``race`` at ring azimuth ``phi`` (rad) lies in the removed sector.

        Outer-raceway marks there would float in front of the balls, so they are not drawn.
        """
        if race != OUTER:
            return np.zeros(np.shape(phi), bool)
        lo, hi = self.options.outer_cutaway
        return np.mod(np.asarray(phi) - lo, 2 * math.pi) < (hi - lo)

    def kept_phi_cells(self, race: int) -> np.ndarray:
        """Phi cells of ``race`` that are drawn: all but the outer ring's cut-away sector."""
        grid = self.grids[race]
        centres = (np.arange(grid.n_phi) + 0.5) * grid.d_phi
        return np.flatnonzero(~self.in_cutaway(race, centres))

    def ring_span(self, race: int) -> tuple[float, float]:
        """(first, last) azimuth (rad) of the ring mesh of ``race``: the whole turn for the inner
        ring, the half shell left by the cut-away for the outer one."""
        if race == INNER:
            return 0.0, 2 * math.pi
        lo, hi = self.options.outer_cutaway
        return hi, lo + 2 * math.pi
