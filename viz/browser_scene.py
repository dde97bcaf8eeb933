"""The bearing scene as data for a browser that renders it itself (vtk.js through trame-vtk).

A :class:`BrowserScene` reads a built :class:`viz.scene.BearingScene` (the same meshes, colours and
layers as the server-rendered view and the exports) and splits it into

* :meth:`BrowserScene.parts` — the static meshes, sent once per result: points (m, each part's own
  frame), cells, per-cell or per-point RGB(A) colours as the server's colour maps give them,
  surface properties, and the ``group`` whose transform moves the part;
* :meth:`BrowserScene.frame_state` — what a played frame sends: one 4x4 matrix per moving group
  (the rings, the cage, each ball), the points of the contact ellipses of the frame and, per
  race, how many cells of the painted track are shown (:meth:`BrowserScene.track_counts`);
* :meth:`BrowserScene.track_cells` — the painted tracks' quads in the order in which the run
  paints them (by the frame at which each cell is first painted), sent once per result and
  painting options: the cells painted over frames ``[0, stop)`` are then the first
  ``track_counts(stop)`` quads, so a frame reveals what the tracks gained with two numbers;
* :meth:`BrowserScene.track_state` — the painted tracks' cell colours (one byte per colour
  channel and quad, in that order) as painted over frames ``[0, stop)``: over the whole run once
  per result and colouring (drawn while playing), and up to a frame chosen by hand.

Arrays are encoded as trame-vtk's typed-array objects (``{"bvals": base64, "dtype": ...}``).
Matrices are in vtk.js's ``userMatrix`` layout (column-major, i.e. the transpose of VTK's row-major
4x4). Lengths in m, inertial frame of case-format.md (x = bearing axis).

Text (the teaching overlay's labels, its legend and the painted tracks' colour bar) is not part
of the 3-D scene: :meth:`BrowserScene.overlay_state` and :meth:`BrowserScene.track_state` give it
as words, colours and numbers for the page to show over the view.
"""

from __future__ import annotations

import base64
import functools

import numpy as np
import pyvista as pv

from .frames import rot_x
from .layout import MARK_LIFT, RacewayLayout
from .marks import ellipse_points
from .overlay import LEGEND
from .painted import SCALAR_BAR
from .raceway import INNER, OUTER
from .tracks import QUANTITY_LABELS, QUANTITY_SCALE, track_colours

INNER_GROUP, OUTER_GROUP, CAGE_GROUP = "inner", "outer", "cage"
SCALAR_MODE_CELL = (2, 4)  # VTK_SCALAR_MODE_USE_CELL_DATA, VTK_SCALAR_MODE_USE_CELL_FIELD_DATA


def typed_array(values, dtype) -> dict:
    """``values`` as a trame-vtk typed-array object (base64 of the raw little-endian bytes)."""
    a = np.ascontiguousarray(values, dtype=dtype)
    return {"bvals": base64.b64encode(a.tobytes()).decode("ascii"), "dtype": _dtype_name(a.dtype)}


@functools.cache
def _dtype_name(dtype: np.dtype) -> str:
    """``dtype.name`` (a property that costs microseconds each time: read once per type)."""
    return dtype.name


def ball_group(j: int) -> str:
    """Name of the transform group of ball ``j``."""
    return f"ball_{j}"


def _cells(cell_array) -> dict | None:
    """A VTK cell array in the legacy layout (count, ids, count, ids, ...) as int32, or None."""
    if cell_array is None or cell_array.GetNumberOfCells() == 0:
        return None
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkCommonCore import vtkIdTypeArray

    legacy = vtkIdTypeArray()
    cell_array.ExportLegacyFormat(legacy)
    return typed_array(vtk_to_numpy(legacy), np.int32)


def _hex(colour) -> list[float]:
    return [float(c) for c in pv.Color(colour).float_rgb]


class BrowserScene:
    """The browser's view of ``scene`` (:class:`viz.scene.BearingScene`, source shown)."""

    def __init__(self, scene):
        self.scene = scene
        self.layout: RacewayLayout = scene.layout
        self._track_cells = [self._track_grid_cells(race) for race in (INNER, OUTER)]
        # per race: quads in painting order (indices into the grid's quads) and their first frames
        self._track_order = [np.arange(cells[2].size) for cells in self._track_cells]
        self._track_first = [np.zeros(cells[2].size, np.int64) for cells in self._track_cells]
        self._names: tuple[str, ...] = ()  # the transform groups of frame_matrices, by ball count

    # ---- static parts ---------------------------------------------------------------------------
    def _groups(self) -> dict:
        """id(actor) -> transform group of every moving actor."""
        s = self.scene
        groups = {
            id(s.bodies.inner_ring): INNER_GROUP,
            id(s.bodies.outer_ring): OUTER_GROUP,
            id(s.bodies.cage): CAGE_GROUP,
        }
        for j, actor in enumerate(s.bodies.balls):
            groups[id(actor)] = ball_group(j)
        for race, name in ((INNER, INNER_GROUP), (OUTER, OUTER_GROUP)):
            for layer in ("ellipses", "traces"):
                groups[id(s.marks.actors[layer][race])] = name
        for race, actor in zip(s.marks._edge_race, s.marks.actors["edges"], strict=True):
            groups[id(actor)] = INNER_GROUP if race == INNER else OUTER_GROUP
        return groups

    def parts(self) -> list[dict]:
        """The static parts, in drawing order: ``name``, ``layer``, ``group`` (None: fixed),
        ``mesh`` (``points``, ``polys``, ``lines``; typed arrays), ``colours`` (``values``,
        ``components``, ``location`` ``"cell"``/``"point"``; None: one colour), ``property``
        (vtk.js property settings), ``kind`` (``"tracks"``/``"ellipses"`` for the parts whose
        colours or points change with the frame, else ``"solid"``) and ``race``."""
        s = self.scene
        groups = self._groups()
        found = []
        for race in (INNER, OUTER):
            found.append(self._track_part(race))
        for layer in ("inner_ring", "outer_ring", "balls", "cage", "edges", "ellipses", "labels"):
            for k, actor in enumerate(s.actors[layer]):
                part = self._actor_part(actor, layer, groups.get(id(actor)))
                if part is None:
                    continue
                part["name"] = f"{layer}_{k}"
                if layer == "ellipses":
                    part["kind"], part["race"] = "ellipses", k
                found.append(part)
        return found

    def _actor_part(self, actor, layer: str, group) -> dict | None:
        if not actor.IsA("vtkActor"):
            return None  # 2-D labels and legends
        mapper = actor.GetMapper()
        data = mapper.GetInput() if mapper is not None else None
        if data is None or not data.IsA("vtkPolyData") or data.GetNumberOfPoints() == 0:
            return None  # text, legends, empty placeholders
        from vtkmodules.util.numpy_support import vtk_to_numpy

        points = vtk_to_numpy(data.GetPoints().GetData())
        mesh = {"points": typed_array(points, np.float32)}
        for key, cells in (("polys", data.GetPolys()), ("lines", data.GetLines())):
            encoded = _cells(cells)
            if encoded is not None:
                mesh[key] = encoded
        prop = actor.GetProperty()
        colours = None
        opaque = True
        if mapper.GetScalarVisibility():
            rgba = mapper.MapScalars(data, 1.0)
            if rgba is not None and rgba.GetNumberOfTuples() > 0:
                values = vtk_to_numpy(rgba).reshape(-1, rgba.GetNumberOfComponents())
                opaque = bool((values[:, 3] == 255).all()) if values.shape[1] == 4 else True
                cell = mapper.GetScalarMode() in SCALAR_MODE_CELL
                colours = {
                    "values": typed_array(values, np.uint8),
                    "components": int(values.shape[1]),
                    "location": "cell" if cell else "point",
                }
        opacity = float(prop.GetOpacity())
        if not opaque and opacity >= 1.0:
            opacity = 0.999  # vtk.js draws the part in its translucent pass
        return {
            "layer": layer,
            "group": group,
            "kind": "solid",
            "race": -1,
            "mesh": mesh,
            "colours": colours,
            "property": {
                "color": [float(c) for c in prop.GetColor()],
                "opacity": opacity,
                "lighting": bool(prop.GetLighting()),
                "lineWidth": float(prop.GetLineWidth()),
                "specular": float(prop.GetSpecular()),
                "interpolation": 1 if prop.GetInterpolation() == 1 else 2,
            },
        }

    def _track_grid_cells(self, race: int):
        """(points (n, 3), quads (VTK legacy), kept cell indices in texel order) of the painted
        track of ``race``: one quad per drawn cell of its grid, ring frame, m."""
        layout = self.layout
        groove, grid = layout.grooves[race], layout.grids[race]
        kept_phi = layout.kept_phi_cells(race)
        phi_edges = grid.phi_edges()
        alpha_edges = np.linspace(grid.alpha_lo, grid.alpha_hi, grid.n_alpha + 1)
        lift = 0.5 * MARK_LIFT * groove.r
        corners = groove.point(phi_edges[:, None], alpha_edges[None, :], lift=lift)
        points = corners.reshape(-1, 3)  # (n_phi + 1) x (n_alpha + 1), alpha fastest
        na = grid.n_alpha + 1
        i_phi, i_alpha = np.meshgrid(kept_phi, np.arange(grid.n_alpha), indexing="ij")
        p00 = (i_phi * na + i_alpha).ravel()
        quads = np.stack([np.full(p00.shape, 4), p00, p00 + na, p00 + na + 1, p00 + 1], axis=-1)
        texel = (i_alpha * grid.n_phi + i_phi).ravel()  # track_colours' order: phi fastest
        return points, quads.ravel(), texel

    def _track_part(self, race: int) -> dict:
        points = self._track_cells[race][0]
        prop = self.scene.tracks.actors[race].GetProperty()
        return {
            "name": f"tracks_{race}",
            "layer": "tracks",
            "group": INNER_GROUP if race == INNER else OUTER_GROUP,
            "kind": "tracks",
            "race": race,
            "mesh": {"points": typed_array(points, np.float32)},  # quads: track_cells
            "colours": None,
            "property": {
                "color": [1.0, 1.0, 1.0],
                "opacity": 1.0,
                "lighting": True,
                "lineWidth": 1.0,
                "specular": float(prop.GetSpecular()),
                "interpolation": 2,
            },
        }

    # ---- 2-D overlay ----------------------------------------------------------------------------
    def overlay_state(self) -> dict:
        """What the server view draws in 2-D over the scene, as words and colours: ``labels`` (the
        teaching overlay's labels), ``legend`` ([words, colour] of each entry of its legend) and
        ``gradient`` (the painted tracks' colour map as a CSS gradient, for the colour bar whose
        title, range and labels come with :meth:`track_state`)."""
        overlay = self.scene.overlay
        words = overlay.legend_words()
        legend = [[w, colour] for w, (_, colour) in zip(words, LEGEND, strict=False)]
        lut = self.scene.tracks.actors[INNER].mapper.lookup_table
        return {
            "labels": list(overlay.label_words),
            "legend": legend,
            "gradient": colour_bar_gradient(lut.values),
        }

    # ---- painted tracks -------------------------------------------------------------------------
    def track_cells(self) -> dict:
        """The painted tracks' quads of both races in the order the scene's painter paints them:
        ``polys`` (inner, outer; int32 typed arrays, VTK legacy layout). A painter that cannot
        say when a cell is first painted (the live session's) keeps the grid's order, every
        quad shown."""
        painter = self.scene.tracks.painter
        first_painted = getattr(painter, "first_painted", None)
        polys = []
        for race in (INNER, OUTER):
            _, quads, texel = self._track_cells[race]
            if first_painted is None:
                first = np.zeros(texel.size, np.int64)
            else:
                first = first_painted(race).T.ravel()[texel]  # texel order: phi fastest
            order = np.argsort(first, kind="stable")
            self._track_order[race] = order
            self._track_first[race] = first[order]
            polys.append(typed_array(quads.reshape(-1, 5)[order], np.int32))
        return {"polys": polys}

    def track_counts(self, stop: int) -> list[int]:
        """(inner, outer) number of quads of :meth:`track_cells` painted over frames
        ``[0, stop)``: the first ones of each race."""
        return [int(np.searchsorted(first, stop, side="left")) for first in self._track_first]

    # ---- per frame ------------------------------------------------------------------------------
    def frame_state(self, index: int, ellipse_scale: float, track_stop: int | None = None) -> dict:
        """What frame ``index`` sends: ``index``, ``m`` (group -> 16 numbers, vtk.js layout),
        ``e`` (inner, outer ellipse points, float32 typed arrays), drawn ``ellipse_scale`` times
        their size, and ``n``, the painted tracks' quads shown (:meth:`track_counts` of
        ``track_stop``; None: every quad)."""
        source = self.scene.source
        f = source.frame(index)
        if track_stop is None:
            counts = [int(first.size) for first in self._track_first]
        else:
            counts = self.track_counts(track_stop)
        groups = self._group_names(source.ball_count)
        return {
            "index": int(f.index),
            "n": counts,
            "m": dict(zip(groups, frame_matrices(f, self.layout), strict=True)),
            "e": [
                typed_array(ellipse_points(self.layout, race, f, ellipse_scale)[0], np.float32)
                for race in (INNER, OUTER)
            ],
        }

    def _group_names(self, ball_count: int) -> tuple[str, ...]:
        """The transform groups in the order of :func:`frame_matrices`."""
        names = self._names
        if len(names) != 3 + ball_count:
            names = (INNER_GROUP, OUTER_GROUP, CAGE_GROUP, *map(ball_group, range(ball_count)))
            self._names = names
        return names

    def track_state(self, stop: int, quantity: str) -> dict:
        """The painted tracks over frames ``[0, stop)`` coloured by ``quantity``: ``stop``,
        ``range`` (lo, hi in the colour bar's units), ``title`` (the colour bar's) and ``c``
        (inner, outer RGBA uint8 typed arrays, one colour per quad in the order of
        :meth:`track_cells`)."""
        tracks = self.scene.tracks
        painter = tracks.painter
        painter.accumulate(stop)
        scale = QUANTITY_SCALE[quantity]
        lo, hi = (v * scale for v in painter.value_range(quantity))
        if not hi > lo:
            hi = lo + max(abs(lo), 1.0) * 1e-3
        lut = tracks.actors[INNER].mapper.lookup_table
        colours = []
        for race in (INNER, OUTER):
            rgba = track_colours(
                painter.field(race, quantity) * scale,
                painter.painted(race),
                lo,
                hi,
                lut.values,
                lut.nan_color.int_rgba,
            )
            texel = self._track_cells[race][2][self._track_order[race]]
            colours.append(typed_array(rgba[texel], np.uint8))
        return {
            "stop": int(painter.stop),
            "range": [float(lo), float(hi)],
            "title": QUANTITY_LABELS[quantity].replace("\n", " "),
            "ticks": colour_bar_ticks(lo, hi),
            "c": colours,
        }


def frame_matrices(f, layout: RacewayLayout) -> list[list[float]]:
    """The user matrices of frame ``f`` (:class:`viz.frames.Frame`): the inner ring, the outer ring
    (shifted ``layout.outer_shift`` m along x), the cage, then each ball; each as 16 numbers in
    vtk.js's layout (column-major), rounded to 9 decimals (lengths in m)."""
    z = f.ball_center.shape[0]
    m = np.zeros((3 + z, 4, 4))
    m[:3, :3, :3] = rot_x(np.array([f.ring_angle[INNER], f.ring_angle[OUTER], f.cage_angle]))
    m[1, 0, 3] = layout.outer_shift
    m[3:, :3, :3] = f.ball_rotation
    m[3:, :3, 3] = f.ball_center
    m[:, 3, 3] = 1.0
    return np.round(m.transpose(0, 2, 1).reshape(3 + z, 16), 9).tolist()


def colour_bar_ticks(lo: float, hi: float) -> list[str]:
    """The colour bar's labels from ``hi`` down to ``lo``, as the server view's bar writes them."""
    fmt = SCALAR_BAR["fmt"]
    return [fmt % v for v in np.linspace(hi, lo, SCALAR_BAR["n_labels"])]


def colour_bar_gradient(table) -> str:
    """A CSS ``linear-gradient`` (bottom to top) of the colour map ``table`` ((m, 4) uint8)."""
    table = np.asarray(table, np.uint8)
    m = table.shape[0]
    stops = [
        f"rgb({r},{g},{b}) {100.0 * (k + 0.5) / m:.2f}%"
        for k, (r, g, b, _) in enumerate(table.tolist())
    ]
    return f"linear-gradient(to top, {', '.join(stops)})"


def camera_state(plotter) -> dict:
    """The plotter's camera as vtk.js ``setCamera`` settings (position, focal point, view up, view
    angle in degrees, parallel projection)."""
    cam = plotter.camera
    return {
        "position": [float(v) for v in cam.position],
        "focalPoint": [float(v) for v in cam.focal_point],
        "viewUp": [float(v) for v in cam.up],
        "viewAngle": float(cam.view_angle),
    }


__all__ = [
    "BrowserScene",
    "camera_state",
    "colour_bar_gradient",
    "colour_bar_ticks",
    "typed_array",
    "ball_group",
]
