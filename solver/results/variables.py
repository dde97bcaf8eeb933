"""The one registry of results variables (results-schema.md): dimensions, units, names, meaning.

Both models fill values into these definitions; nothing else defines a results variable's units or
description. Units are UDUNITS spellings; angles are in degree in every Dataset, everything else SI.
Dimensions are given for the quasi-static model; the dynamic model appends ``time`` (schema order:
per-contact ``(ball, race, time)``, per-ball ``(ball, time)``, rings ``(time)``).

Frames: "inertial" = x along the bearing axis (the direction in which the inner ring carries
thrust), y, z radial, origin at the outer ring centre on the plane of the ball centres in the
just-touching state (rings concentric, every ball touching both races at the free contact angle). A
ring's own frame is attached to that ring and coincides with the inertial frame in the just-touching
state at t = 0.
"""

from __future__ import annotations

from dataclasses import dataclass

DIMENSION_VALUES = {
    "race": ["inner", "outer"],
    "axis": ["x", "y", "z"],
    "tilt_axis": ["y", "z"],
    "quaternion": ["w", "x", "y", "z"],
}


@dataclass(frozen=True)
class Variable:
    """One results variable: dimensions (without ``time``), UDUNITS units, long name, description
    (sign and frame), and which models produce it."""

    dims: tuple[str, ...]
    units: str
    long_name: str
    description: str
    models: tuple[str, ...] = ("quasistatic", "dynamic")
    time_dependent: bool = True  # False for the dynamic model's summary metrics

    def dims_for(self, model: str) -> tuple[str, ...]:
        """Dimensions in a Dataset of ``model`` ("quasistatic" or "dynamic")."""
        if model == "dynamic" and self.time_dependent:
            return (*self.dims, "time")
        return self.dims

    def attrs(self) -> dict[str, str]:
        """NetCDF attributes: units, long_name, description."""
        return {"units": self.units, "long_name": self.long_name, "description": self.description}


_C = ("ball", "race")
_B = ("ball",)
_QS = ("quasistatic",)
_DYN = ("dynamic",)

VARIABLES: dict[str, Variable] = {
    # ---- per contact -------------------------------------------------------------------------
    "contact_load": Variable(
        _C,
        "N",
        "contact normal load",
        "normal load Q of the ball-race contact (>= 0; 0 when the contact is open)",
    ),
    "contact_angle": Variable(
        _C,
        "degree",
        "contact angle",
        "angle of the contact line in the ring's meridian plane, from the radial plane; positive "
        "when the outer contact lies on the +x side of the ball centre and the inner contact on "
        "the -x side (thrust carried in +x); may be negative. For an open contact: the angle of "
        "the line between the two groove curvature centres (where the ball would touch if the gap "
        "closed)",
    ),
    "contact_deflection": Variable(
        _C,
        "m",
        "contact elastic approach",
        "Hertz elastic approach delta (>= 0; 0 when the contact is open)",
    ),
    "ellipse_semi_major": Variable(
        _C,
        "m",
        "contact ellipse semi-major axis",
        "Hertz semi-axis a across the groove (0 when open)",
    ),
    "ellipse_semi_minor": Variable(
        _C,
        "m",
        "contact ellipse semi-minor axis",
        "Hertz semi-axis b in the rolling direction (0 when open)",
    ),
    "max_pressure": Variable(
        _C, "Pa", "peak contact pressure", "peak Hertz pressure 3Q/(2 pi a b) (0 when open)"
    ),
    "raceway_azimuth": Variable(
        _C,
        "degree",
        "contact azimuth on the raceway",
        "circumferential position of the contact centre in that ring's own (rotating) frame, "
        "measured from +y towards +z, wrapped to [0, 360)",
    ),
    "raceway_contact_point": Variable(
        (*_C, "axis"),
        "m",
        "contact centre on the raceway",
        "contact centre (mid-plane of the deformed zone) in that ring's own frame (x, y, z)",
    ),
    "ball_latitude": Variable(
        _C,
        "degree",
        "contact latitude on the ball",
        "latitude of the contact centre on the ball, in the ball-fixed frame (z_b = spin axis "
        "direction cos(beta) e_x - sin(beta) e_r at t = 0; see solver.physics.kinematics)",
    ),
    "ball_longitude": Variable(
        _C,
        "degree",
        "contact longitude on the ball",
        "longitude of the contact centre on the ball in the ball-fixed frame, in (-180, 180]; "
        "x_b = sin(beta) e_x + cos(beta) e_r, y_b = e_theta at t = 0",
    ),
    "spin_to_roll": Variable(
        _C,
        "1",
        "spin-to-roll ratio",
        "omega_spin / omega_roll of the ball relative to the ring (physics.md 2.5.7): projections "
        "of the relative angular velocity on the contact normal and on the rolling axis; 0 without "
        "rolling",
    ),
    "sliding_speed": Variable(
        _C,
        "m/s",
        "sliding speed at the contact centre",
        "magnitude of the sliding velocity at the contact centre",
    ),
    "film_thickness": Variable(
        _C,
        "m",
        "central EHL film thickness",
        "Hamrock-Dowson isothermal central film thickness (only with a lubricant)",
    ),
    "truncation_margin": Variable(
        _C,
        "degree",
        "contact ellipse truncation margin",
        "shoulder angle minus the groove angle of the ellipse edge |alpha| + a/r; negative = the "
        "ellipse is truncated by the shoulder; NaN when no shoulder diameter is given",
    ),
    # ---- per ball ----------------------------------------------------------------------------
    "ball_azimuth": Variable(
        _B,
        "degree",
        "ball azimuth",
        "orbital position psi of the ball centre, inertial, from +y towards +z",
    ),
    "orbital_speed": Variable(
        _B,
        "rad/s",
        "ball orbital speed",
        "orbital (cage) speed omega_c of the ball centre about +x",
    ),
    "ball_center": Variable((*_B, "axis"), "m", "ball centre", "ball centre position, inertial"),
    "ball_angular_velocity": Variable(
        (*_B, "axis"),
        "rad/s",
        "ball angular velocity",
        "absolute angular velocity of the ball, inertial components",
    ),
    "attitude_angle": Variable(
        _B,
        "degree",
        "ball attitude angle",
        "angle beta of the ball's spin axis (relative to the cage) from the bearing axis, in the "
        "meridian plane: spin axis direction cos(beta) e_x - sin(beta) e_r",
    ),
    "ball_spin_speed": Variable(
        _B,
        "rad/s",
        "ball spin speed relative to the cage",
        "omega_R: the ball's angular velocity relative to the cage is omega_R (cos(beta) e_x - "
        "sin(beta) e_r); negative when the inner ring turns forward with the outer ring fixed",
        _QS,
    ),
    "centrifugal_force": Variable(
        _B,
        "N",
        "ball centrifugal force",
        "m r omega_c^2 with the ball's actual orbit radius r",
        _QS,
    ),
    "gyroscopic_moment": Variable(
        _B,
        "N m",
        "ball gyroscopic moment",
        "moment the contacts apply to the ball along e_theta, M_g = -J omega_c omega_R sin(beta) "
        "(rate of change of the ball's angular momentum in the cage frame)",
        _QS,
    ),
    "race_control": Variable(
        _B, "1", "controlling race", "'inner' or 'outer' (Jones criterion, decided per ball)", _QS
    ),
    "ball_orientation": Variable(
        (*_B, "quaternion"),
        "1",
        "ball orientation",
        "unit quaternion [w, x, y, z] of the ball-fixed frame, inertial",
        _DYN,
    ),
    "cage_pocket_force": Variable(
        _B, "N", "cage pocket force", "magnitude of the ball-pocket contact force", _DYN
    ),
    # ---- rings and cage ------------------------------------------------------------------------
    "inner_ring_offset": Variable(
        ("axis",),
        "m",
        "inner ring displacement",
        "inner ring centre relative to the outer ring, from the just-touching position",
    ),
    "inner_ring_tilt": Variable(
        ("tilt_axis",),
        "degree",
        "inner ring tilt",
        "tilt of the inner ring relative to the outer ring: rotation vector components about y and "
        "z",
    ),
    "inner_ring_moment": Variable(
        ("tilt_axis",),
        "N m",
        "moment on the inner ring",
        "moment applied to the inner ring about its centre: the given tilting moment when the tilt "
        "is solved, otherwise the moment needed to hold the imposed tilt",
        _QS,
    ),
    "cage_speed": Variable(
        (),
        "rad/s",
        "cage speed",
        "cage angular speed about +x (quasi-static: mean of the balls' orbital speeds)",
    ),
    "cage_center": Variable(("axis",), "m", "cage centre", "cage centre, inertial", _DYN),
    # ---- summary metrics (dynamic) -------------------------------------------------------------
    "trajectory_band_width": Variable(
        ("race",),
        "degree",
        "contact trajectory band width",
        "across-groove width of each race's contact track over the analysed window, as a "
        "contact-angle range",
        _DYN,
        False,
    ),
    "trajectory_band_width_arc": Variable(
        ("race",),
        "m",
        "contact trajectory band width (arc)",
        "groove radius times the contact-angle range of trajectory_band_width",
        _DYN,
        False,
    ),
}


def variable(name: str) -> Variable:
    """The registered definition of ``name``; KeyError naming the known variables otherwise."""
    try:
        return VARIABLES[name]
    except KeyError:
        known = ", ".join(sorted(VARIABLES))
        raise KeyError(f"unknown results variable {name!r}; known: {known}") from None


_COORDINATE_NAMES = {
    "race": "race",
    "axis": "Cartesian axis of the frame named by the variable",
    "tilt_axis": "axis of the tilt rotation vector",
    "quaternion": "quaternion component",
}


def coordinates(ball_count: int, times=None, *, quaternion: bool = False) -> dict:
    """Coordinates of a results Dataset, each with ``units`` and ``long_name``.

    ``times`` (s) adds the ``time`` coordinate of the dynamic model; ``quaternion`` adds the
    [w, x, y, z] dimension of ``ball_orientation``.
    """
    import numpy as np

    coords = {
        "ball": (
            "ball",
            np.arange(ball_count),
            {"long_name": "ball index (ball 0 starts at azimuth 0)", "units": "1"},
        )
    }
    for dim, long_name in _COORDINATE_NAMES.items():
        if dim == "quaternion" and not quaternion:
            continue
        values = np.array(DIMENSION_VALUES[dim], dtype=object)
        coords[dim] = (dim, values, {"long_name": long_name, "units": "1"})
    if times is not None:
        coords["time"] = (
            "time",
            np.asarray(times, dtype=np.float64),
            {"long_name": "time", "units": "s"},
        )
    return coords
