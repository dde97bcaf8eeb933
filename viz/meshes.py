"""Meshes of the bearing's parts, in the inertial frame of case-format.md (x = bearing axis), m.

Pure mesh building (pyvista), no plotter: ring cross-sections revolved about the axis, the balls'
marked spheres, the cage, the fans and outlines of contact ellipses, polylines, and the 4x4
placement matrices that move actors.
"""

from __future__ import annotations

import math

import numpy as np
import pyvista as pv

from .raceway import Groove, groove_half_angle

# Points of the ring meshes around the inner ring and around the outer ring's half shell, and
# across the groove arc. The painted tracks' mesh uses the same ones, so that its facets lie just
# above the ring's; the tracks' detail is a texture.
RING_PHI_POINTS = (96, 72)
GROOVE_ARC_POINTS = 40
RING_COLOUR = "#b8bcc4"


def ring_profile(
    groove: Groove, ball_diameter: float, shoulder_radius: float, n_arc: int = GROOVE_ARC_POINTS
):
    """Closed (x, radius) outline of a ring cross-section, m.

    The groove arc runs between the two shoulders at groove latitude +-theta
    (:func:`viz.raceway.groove_half_angle`).
    """
    D, r = ball_diameter, groove.r
    s = groove.sign  # +1 inner (material below the groove), -1 outer (material above)
    theta = groove_half_angle(groove, D, shoulder_radius)
    alpha = np.linspace(-theta, theta, n_arc)
    arc_x = groove.x_c - s * r * np.sin(alpha)
    arc_rho = groove.rho_c - s * r * np.cos(alpha)
    land = groove.rho_c - s * r * math.cos(theta)
    back = groove.rho_c - s * r - s * 0.45 * D  # bore (inner) or outside surface (outer)
    half_width = 0.5 * 1.9 * D
    x_lo, x_hi = min(arc_x.min(), -half_width), max(arc_x.max(), half_width)
    # the arc runs from x_hi side to x_lo side for the inner ring (s=+1) and the reverse for outer
    if arc_x[0] < arc_x[-1]:
        arc_x, arc_rho = arc_x[::-1], arc_rho[::-1]
    xs = np.concatenate([[x_lo, x_hi, x_hi], arc_x, [x_lo, x_lo]])
    rhos = np.concatenate([[back, back, land], arc_rho, [land, back]])
    return xs, rhos


def revolve(xs, rhos, n_phi: int = RING_PHI_POINTS[0], phi_range=(0.0, 2 * math.pi)):
    """Surface of revolution about +x of a closed (x, radius) outline."""
    phi = np.linspace(*phi_range, n_phi)
    X = np.repeat(np.asarray(xs)[:, None], n_phi, axis=1)
    R = np.asarray(rhos)[:, None]
    grid = pv.StructuredGrid(X, R * np.cos(phi)[None, :], R * np.sin(phi)[None, :])
    try:
        surf = grid.extract_surface(algorithm="dataset_surface")
    except TypeError:  # pyvista < 0.47 has no ``algorithm`` keyword
        surf = grid.extract_surface()
    surf = surf.triangulate().clean()
    if phi_range[1] - phi_range[0] < 2 * math.pi - 1e-9:  # a cut-away ring: close the cut faces
        caps = []
        for angle in phi_range:
            pts = np.column_stack(
                [xs, np.asarray(rhos) * math.cos(angle), np.asarray(rhos) * math.sin(angle)]
            )[:-1]  # drop closing point
            face = np.concatenate([[len(pts)], np.arange(len(pts))])
            caps.append(pv.PolyData(pts, faces=face).triangulate())
        surf = pv.merge([surf, *caps]).clean()
    return surf.compute_normals(auto_orient_normals=False, split_vertices=True)


def marked_sphere(radius: float) -> pv.PolyData:
    """Sphere with an octant checker pattern (cell data ``mark``), so its spin is visible."""
    sphere = pv.Sphere(radius=radius, theta_resolution=24, phi_resolution=16)
    c = sphere.cell_centers().points
    sphere.cell_data["mark"] = (np.sign(c[:, 0]) * np.sign(c[:, 1]) * np.sign(c[:, 2]) > 0).astype(
        float
    )
    return sphere


def cage_mesh(pitch_radius: float, ball_diameter: float, ball_count: int) -> pv.PolyData:
    """Two side hoops and one bar between each pair of pockets, at cage angle 0."""
    D = ball_diameter
    parts = []
    for x in (-0.62 * D, 0.62 * D):
        hoop = pv.ParametricTorus(
            ringradius=pitch_radius, crosssectionradius=0.07 * D, u_res=96, v_res=8
        )
        parts.append(hoop.rotate_y(90.0, inplace=False).translate((x, 0.0, 0.0), inplace=False))
    for j in range(ball_count):
        psi = 2 * math.pi * (j + 0.5) / ball_count
        centre = (0.0, pitch_radius * math.cos(psi), pitch_radius * math.sin(psi))
        parts.append(
            pv.Cylinder(
                center=centre, direction=(1, 0, 0), radius=0.07 * D, height=1.24 * D, resolution=8
            )
        )
    return pv.merge(parts)


def fan_faces(count: int, n: int) -> np.ndarray:
    """Triangle-fan faces for ``count`` ellipses of ``n`` outline points plus a centre each."""
    faces = []
    for e in range(count):
        base = e * (n + 1)
        for k in range(n):
            faces.append((3, base, base + 1 + k, base + 1 + (k + 1) % n))
    return np.asarray(faces, dtype=np.int64).ravel()


def outline_lines(count: int, n: int) -> np.ndarray:
    """Closed polylines along the ``n`` outline points of ``count`` fans (:func:`fan_faces`)."""
    lines = []
    for e in range(count):
        base = e * (n + 1)
        lines.append([n + 1, *(base + 1 + np.arange(n)), base + 1])
    return np.asarray(lines, dtype=np.int64).ravel()


def placement(rotation: np.ndarray, translation=(0.0, 0.0, 0.0)) -> np.ndarray:
    """4x4 user matrix of an actor: ``rotation`` (3x3) then ``translation`` (m)."""
    m = np.eye(4)
    m[:3, :3] = rotation
    m[:3, 3] = translation
    return m


def empty_line() -> pv.PolyData:
    """A two-point line at the origin: the placeholder of a polyline drawn later."""
    return pv.PolyData(np.zeros((2, 3)), lines=np.array([2, 0, 1]))


def set_polyline(mesh: pv.PolyData, pts) -> None:
    """Make ``mesh`` the polyline through ``pts`` (m, (n, 3)); a point at the origin when n < 2."""
    pts = np.asarray(pts, float).reshape(-1, 3)
    if len(pts) < 2:
        pts = np.zeros((2, 3))
    mesh.copy_from(pv.lines_from_points(pts))
