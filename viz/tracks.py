"""Painted contact tracks: where the contact ellipses ran on each raceway, as a field on the groove.

Pure numpy/numba, no rendering. Each raceway is divided into a grid of cells in that ring's own
frame: ``n_phi`` cells around (ring azimuth ``phi``, rad, from +y towards +z) by ``n_alpha`` cells
across the groove (groove latitude ``alpha``, rad, the contact-angle coordinate of
:mod:`viz.raceway`) between the two shoulder edges. Every loaded contact sample of a
:class:`viz.frames.FrameSource` covers the cells its ellipse sweeps on the way to the next sample:
across the groove ``alpha +- a / r`` (semi-major axis ``a``, groove radius ``r``), around the ring
from its centre to the next sample's centre, widened by the semi-minor axis ``b`` each way.

Two fields are accumulated per race, both indexed ``[phi cell, alpha cell]``:

* **dwell** (s): how long a point of the raceway spent inside a contact ellipse, averaged over the
  cell. A sample of time step ``dt`` contributes ``dt * 2 b`` (s m) along the raceway, spread evenly
  over the cells it covers, so a pass of an ellipse moving at ``v`` leaves ``2 b / v``.
* **peak pressure** (Pa): the highest Hertz pressure seen at the cell,
  ``p0 sqrt(1 - (d / a)^2)`` at the across-groove distance ``d`` of the cell centre from the ellipse
  centre (the largest pressure along the rolling direction at that distance).

The footprints of all samples are computed once (:class:`TrackPainter`); the fields then grow frame
by frame (:meth:`TrackPainter.accumulate`), so playing costs only the new frames. Display options:
the across-groove deviation of the ellipse centres from the run's mean contact angle is scaled by
``exaggeration`` and clipped at the shoulders (the track never leaves the groove); ellipse sizes are
scaled by ``ellipse_scale``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from solver import loaded_mask  # importing solver configures numba's cache folder first

from .frames import FrameSource
from .raceway import INNER, OUTER, Groove

QUANTITIES = ("dwell", "peak_pressure")
QUANTITY_LABELS = {"dwell": "dwell,\nms", "peak_pressure": "peak pressure,\nGPa"}
QUANTITY_SCALE = {"dwell": 1e3, "peak_pressure": 1e-9}  # SI -> the units of the colour bar
N_PHI = 240  # cells around each raceway (1.5 degree)
N_ALPHA = 64  # cells across each groove, shoulder to shoulder


@dataclass(frozen=True)
class TrackGrid:
    """Cells of one raceway: ``n_phi`` around x ``n_alpha`` across, latitudes in rad."""

    alpha_lo: float  # shoulder edge on the -alpha side (rad)
    alpha_hi: float  # shoulder edge on the +alpha side (rad)
    n_phi: int = N_PHI
    n_alpha: int = N_ALPHA

    @property
    def d_phi(self) -> float:
        return 2.0 * math.pi / self.n_phi

    @property
    def d_alpha(self) -> float:
        return (self.alpha_hi - self.alpha_lo) / self.n_alpha

    def phi_edges(self) -> np.ndarray:
        return np.linspace(0.0, 2.0 * math.pi, self.n_phi + 1)


@dataclass(frozen=True)
class Footprints:
    """Per-sample footprints of one race, frame-major (sample ``k = frame * Z + ball``)."""

    j0: np.ndarray  # first phi cell (may exceed n_phi: taken modulo n_phi)
    nj: np.ndarray  # number of phi cells (0 for an unloaded sample)
    i0: np.ndarray  # first alpha cell
    ni: np.ndarray  # number of alpha cells
    centre: np.ndarray  # displayed centre latitude (rad)
    half_width: np.ndarray  # displayed across-groove half-width (rad)
    weight: np.ndarray  # dwell added to each covered cell (s)
    p0: np.ndarray  # peak Hertz pressure of the sample (Pa)


@njit(cache=True)
def _paint(dwell, peak, j0, nj, i0, ni, centre, half_width, weight, p0, alpha_lo, d_alpha, n_phi):
    """Add samples to the fields (see the module docstring); ``peak`` keeps the maximum."""
    for k in range(j0.shape[0]):
        for dj in range(nj[k]):
            j = (j0[k] + dj) % n_phi
            for di in range(ni[k]):
                i = i0[k] + di
                dwell[j, i] += weight[k]
                u = (alpha_lo + (i + 0.5) * d_alpha - centre[k]) / half_width[k]
                p = p0[k] * math.sqrt(max(0.0, 1.0 - u * u))
                if p > peak[j, i]:
                    peak[j, i] = p


@njit(cache=True)
def _first_painted(first, j0, nj, i0, ni, weight, ball_count, n_phi):
    """Lower ``first[j, i]`` to the frame of the first sample (``k // ball_count``) that adds
    dwell to cell ``(j, i)`` (the samples in frame order)."""
    for k in range(j0.shape[0]):
        if not weight[k] > 0.0:
            continue
        frame = k // ball_count
        for dj in range(nj[k]):
            j = (j0[k] + dj) % n_phi
            for di in range(ni[k]):
                i = i0[k] + di
                if frame < first[j, i]:
                    first[j, i] = frame


def footprints(
    source: FrameSource,
    race: int,
    groove: Groove,
    grid: TrackGrid,
    reference: float,
    exaggeration: float = 1.0,
    ellipse_scale: float = 1.0,
) -> Footprints:
    """Footprints of every sample of ``race`` (see the module docstring).

    ``reference`` (rad): the latitude about which the deviation is exaggerated (the run's mean
    contact angle on that race).
    """
    c = source.contact
    alpha = c["contact_angle"][:, :, race]  # (N, Z)
    loaded = loaded_mask(c["contact_load"][:, :, race], alpha)
    alpha = np.where(loaded, alpha, reference)
    a = np.where(loaded, np.nan_to_num(c["ellipse_semi_major"][:, :, race]), 0.0) * ellipse_scale
    b = np.where(loaded, np.nan_to_num(c["ellipse_semi_minor"][:, :, race]), 0.0) * ellipse_scale
    p0 = np.where(loaded, np.nan_to_num(c["max_pressure"][:, :, race]), 0.0)
    phi = source.raceway_azimuth[:, :, race]
    n = phi.shape[0]

    # centre across the groove: exaggerated deviation, clipped at the shoulders
    half = np.maximum(a / groove.r, 1e-9)
    centre = reference + float(exaggeration) * (alpha - reference)
    centre = np.clip(centre, grid.alpha_lo, grid.alpha_hi)
    lo = (centre - half - grid.alpha_lo) / grid.d_alpha - 0.5
    hi = (centre + half - grid.alpha_lo) / grid.d_alpha - 0.5
    i_first = np.clip(np.ceil(lo), 0, grid.n_alpha - 1).astype(np.int64)
    i_last = np.clip(np.floor(hi), 0, grid.n_alpha - 1).astype(np.int64)
    narrow = i_last < i_first  # narrower than a cell: paint the cell holding the centre
    i_mid = np.clip(np.floor((centre - grid.alpha_lo) / grid.d_alpha), 0, grid.n_alpha - 1).astype(
        np.int64
    )
    i_first = np.where(narrow, i_mid, i_first)
    i_last = np.where(narrow, i_mid, i_last)

    # around the raceway: from this sample's centre to the next one's, widened by b each way
    if n > 1:
        step = np.empty_like(phi)
        step[:-1] = phi[1:] - phi[:-1]
        step[-1] = step[-2]
    else:
        step = np.zeros_like(phi)
    step = np.where(np.isfinite(step), step, 0.0)
    rho = groove.contact_radius(centre)
    b_phi = b / rho
    start = np.minimum(phi, phi + step) - b_phi
    stop = np.maximum(phi, phi + step) + b_phi
    j_first = np.floor(start / grid.d_phi).astype(np.int64)
    j_last = np.floor(stop / grid.d_phi).astype(np.int64)
    nj = np.minimum(j_last - j_first + 1, grid.n_phi)
    nj = np.where(loaded, nj, 0)
    j_first = np.mod(j_first, grid.n_phi)

    dt = np.diff(source.times)
    dt = np.concatenate([dt, dt[-1:]]) if n > 1 else np.ones(1)
    # the sample's dwell integrated along the raceway, dt * 2 b (s m), spread over its cells
    weight = dt[:, None] * 2.0 * b / (np.maximum(nj, 1) * grid.d_phi * rho)
    weight = np.where(loaded, weight, 0.0)
    return Footprints(
        j0=j_first.ravel(),
        nj=nj.ravel().astype(np.int64),
        i0=i_first.ravel(),
        ni=(i_last - i_first + 1).ravel(),
        centre=centre.ravel(),
        half_width=half.ravel(),
        weight=weight.ravel(),
        p0=p0.ravel(),
    )


class TrackPainter:
    """The dwell and peak-pressure fields of both raceways, grown frame by frame.

    ``grids``: one :class:`TrackGrid` per race; ``references``: (inner, outer) latitudes (rad) about
    which the exaggeration acts.
    """

    def __init__(
        self,
        source: FrameSource,
        grooves,
        grids,
        references,
        exaggeration: float = 1.0,
        ellipse_scale: float = 1.0,
    ):
        self.source = source
        self.grids = tuple(grids)
        self.ball_count = source.ball_count
        self._footprints = [
            footprints(
                source,
                race,
                grooves[race],
                self.grids[race],
                references[race],
                exaggeration,
                ellipse_scale,
            )
            for race in (INNER, OUTER)
        ]
        self._first = [None, None]  # first_painted of each race, computed when first asked
        self.reset()

    def reset(self) -> None:
        """Empty fields (no frame painted)."""
        self.stop = 0
        self._dwell = [np.zeros((g.n_phi, g.n_alpha)) for g in self.grids]
        self._peak = [np.zeros((g.n_phi, g.n_alpha)) for g in self.grids]

    def accumulate(self, stop: int) -> None:
        """Fields of frames ``[0, stop)``: adds the new frames, or starts again when going back."""
        stop = int(min(max(stop, 0), self.source.n_frames))
        if stop < self.stop:
            self.reset()
        if stop == self.stop:
            return
        z = self.ball_count
        sl = slice(self.stop * z, stop * z)
        for race, fp in enumerate(self._footprints):
            g = self.grids[race]
            _paint(
                self._dwell[race], self._peak[race],
                fp.j0[sl], fp.nj[sl], fp.i0[sl], fp.ni[sl], fp.centre[sl], fp.half_width[sl],
                fp.weight[sl], fp.p0[sl], g.alpha_lo, g.d_alpha, g.n_phi,
            )  # fmt: skip
        self.stop = stop

    def first_painted(self, race: int) -> np.ndarray:
        """(n_phi, n_alpha) int64: the frame at which each cell of ``race`` is first painted
        (:meth:`painted` over frames ``[0, stop)`` is ``first_painted < stop``); ``n_frames`` where
        no ellipse of the run comes."""
        if self._first[race] is None:
            g, fp = self.grids[race], self._footprints[race]
            first = np.full((g.n_phi, g.n_alpha), self.source.n_frames, np.int64)
            _first_painted(first, fp.j0, fp.nj, fp.i0, fp.ni, fp.weight, self.ball_count, g.n_phi)
            self._first[race] = first
        return self._first[race]

    def field(self, race: int, quantity: str) -> np.ndarray:
        """(n_phi, n_alpha) field of ``race`` in SI (s or Pa); 0 where no ellipse has been."""
        if quantity not in QUANTITIES:
            raise ValueError(f"unknown track quantity {quantity!r}; use one of {QUANTITIES}")
        return (self._dwell if quantity == "dwell" else self._peak)[race]

    def painted(self, race: int) -> np.ndarray:
        """(n_phi, n_alpha) bool: cells some ellipse has covered."""
        return self._dwell[race] > 0.0

    def value_range(self, quantity: str) -> tuple[float, float]:
        """(min, max) of ``quantity`` over the painted cells of both races; (0, 0) when none."""
        values = [self.field(r, quantity)[self.painted(r)] for r in (INNER, OUTER)]
        values = np.concatenate(values)
        if values.size == 0:
            return 0.0, 0.0
        return float(values.min()), float(values.max())


def groove_surface_arrays(
    groove: Groove, grid: TrackGrid, phis, n_alpha_points: int, lift: float = 0.0
):
    """Quad mesh over the groove, shoulder to shoulder, textured by the track fields.

    Returns (points (n, 3) m in the ring frame, faces (VTK layout), texture coordinates (n, 2)).
    ``phis``: ring azimuths (rad, increasing) of the mesh's rows of points; ``n_alpha_points``:
    points across the groove. The texture coordinates are ``u = phi / 2 pi`` (above 1 past a full
    turn: the texture repeats) and ``v = (alpha - alpha_lo) / (alpha_hi - alpha_lo)``, so that a
    texture of ``n_phi`` x ``n_alpha`` texels (:func:`track_colours`, nearest texel) shows each
    cell of the fields where it lies, however coarse the mesh.
    """
    phis = np.asarray(phis, float)
    alphas = np.linspace(grid.alpha_lo, grid.alpha_hi, int(n_alpha_points))
    na = alphas.size
    points = groove.point(phis[:, None], alphas[None, :], lift=lift).reshape(-1, 3)
    jj, ii = np.meshgrid(np.arange(phis.size - 1), np.arange(na - 1), indexing="ij")
    p00 = (jj * na + ii).ravel()
    faces = np.stack([np.full(p00.shape, 4), p00, p00 + 1, p00 + na + 1, p00 + na], axis=-1)
    u = np.repeat(phis / (2.0 * math.pi), na)
    v = np.tile((alphas - grid.alpha_lo) / (grid.alpha_hi - grid.alpha_lo), phis.size)
    return points, faces.ravel(), np.stack([u, v], axis=1)


def track_colours(field: np.ndarray, painted: np.ndarray, lo: float, hi: float, table, nan_rgba):
    """RGBA texels (n_alpha * n_phi, 4) uint8 of a track field (n_phi, n_alpha), phi fastest.

    ``table``: the colour map (m, 4) uint8 spread linearly over ``[lo, hi]`` (values outside take
    the end colours); cells not ``painted`` take ``nan_rgba``.
    """
    table = np.asarray(table, np.uint8)
    m = table.shape[0]
    span = hi - lo if hi > lo else 1.0
    index = np.clip(((field.T - lo) / span * m).astype(np.int64), 0, m - 1)
    out = table[index]
    out[~painted.T] = np.asarray(nan_rgba, np.uint8)
    return out.reshape(-1, 4)
