"""Frame source: what the 3-D view and the time-following charts show at animation frame ``i``.

A :class:`FrameSource` holds, for every frame, the ball centres and orientations (inertial frame),
the ring and cage angles and the contact data of every (ball, race) contact, plus the raceway
coordinates of the contact points (each ring's own frame) from which trajectory traces are drawn.

Two ways to build one (:func:`frame_source` picks the right one):

* :meth:`FrameSource.from_dynamic` — a dynamic result (``time`` dimension): frame ``i`` is
  time index ``i``.
* :func:`from_revolution` — a quasi-static solution over one revolution (``ring_angle``
  dimension): as below, with the contacts of the inner ring's angle at each frame.
* :meth:`FrameSource.from_quasistatic` — a quasi-static result (no ``time``): rigid steady
  kinematics.
  The balls orbit at the quasi-static cage speed (the cage keeps their spacing; per-ball orbital
  speeds are shown in the charts), each ball's spin vector relative to its azimuth frame is the
  quasi-static one at its current azimuth, the inner ring turns at the shaft speed and the contact
  data are those of the load zone, fixed in space: a ball at azimuth psi sees the quasi-static
  contact of azimuth psi (periodic linear interpolation between the solved balls).

Units: s, m, rad (the dataset's degrees are converted here), N, Pa. Races are indexed 0 = inner,
1 = outer. Ring angles are rotations about +x of each ring relative to the inertial frame.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import xarray as xr

from solver import loaded_mask

from .raceway import INNER, OUTER

TWO_PI = 2.0 * math.pi

QS_SAMPLES_PER_REVOLUTION = 72  # animation frames per shaft revolution for a quasi-static result
QS_DEFAULT_REVOLUTIONS = 10.0  # shaft revolutions animated when the caller names none
QS_MAX_REVOLUTIONS = 20.0  # the steady animation repeats; longer runs only add frames to handle

# Read when the result has them (contact[name], (N, Z, 2)); the ball-surface coordinates only from
# a dynamic result, whose ball orientations they are measured against (angles in rad).
_OPTIONAL_CONTACT_VARS = ("spin_to_roll", "ball_latitude", "ball_longitude")
_ANGLE_VARS = ("contact_angle", "ball_latitude", "ball_longitude")
_CONTACT_VARS = (
    "contact_angle",
    "contact_load",
    "ellipse_semi_major",
    "ellipse_semi_minor",
    "max_pressure",
)


@dataclass(frozen=True)
class Frame:
    """State of the bearing at one animation frame (see module docstring for units and frames)."""

    index: int
    time: float  # s
    ball_center: np.ndarray  # (Z, 3) m, inertial
    ball_rotation: np.ndarray  # (Z, 3, 3) ball-fixed -> inertial
    ball_azimuth: np.ndarray  # (Z,) rad, inertial
    ring_angle: np.ndarray  # (2,) rad [inner, outer]
    cage_angle: float  # rad
    contact_angle: np.ndarray  # (Z, 2) rad
    raceway_azimuth: np.ndarray  # (Z, 2) rad, ring frame
    contact_load: np.ndarray  # (Z, 2) N
    semi_major: np.ndarray  # (Z, 2) m, across the groove
    semi_minor: np.ndarray  # (Z, 2) m, rolling direction
    max_pressure: np.ndarray  # (Z, 2) Pa

    @property
    def loaded(self) -> np.ndarray:
        """(Z, 2) bool: contact carries load and has a finite contact angle
        (``solver.loaded_mask``)."""
        return loaded_mask(self.contact_load, self.contact_angle)


@dataclass(frozen=True)
class FrameSource:
    """All frames of one result as arrays with a leading frame axis (length ``n_frames``)."""

    model: str  # "quasistatic" | "dynamic"
    times: np.ndarray  # (N,) s
    ball_center: np.ndarray  # (N, Z, 3)
    ball_rotation: np.ndarray  # (N, Z, 3, 3)
    ball_azimuth: np.ndarray  # (N, Z) rad
    ring_angle: np.ndarray  # (N, 2) rad
    cage_angle: np.ndarray  # (N,) rad
    contact: dict  # name -> (N, Z, 2), angles in rad
    raceway_azimuth: np.ndarray  # (N, Z, 2) rad, ring frame, unwrapped along N

    @property
    def n_frames(self) -> int:
        return len(self.times)

    @property
    def ball_count(self) -> int:
        return self.ball_center.shape[1]

    def frame(self, i: int) -> Frame:
        """Frame ``i`` (clipped to the valid range)."""
        i = int(min(max(i, 0), self.n_frames - 1))
        c = self.contact
        return Frame(
            index=i,
            time=float(self.times[i]),
            ball_center=self.ball_center[i],
            ball_rotation=self.ball_rotation[i],
            ball_azimuth=self.ball_azimuth[i],
            ring_angle=self.ring_angle[i],
            cage_angle=float(self.cage_angle[i]),
            contact_angle=c["contact_angle"][i],
            raceway_azimuth=self.raceway_azimuth[i],
            contact_load=c["contact_load"][i],
            semi_major=c["ellipse_semi_major"][i],
            semi_minor=c["ellipse_semi_minor"][i],
            max_pressure=c["max_pressure"][i],
        )

    def trace(self, race: int, stop: int | None = None):
        """Trajectory samples of every ball on ``race`` for frames ``[0, stop)``.

        Returns ``(phi, alpha, loaded)``, each (Z, n): raceway azimuth (rad, ring frame, unwrapped),
        contact angle (rad) and whether the contact carried load at that sample.
        """
        stop = self.n_frames if stop is None else int(min(max(stop, 0), self.n_frames))
        phi = self.raceway_azimuth[:stop, :, race].T
        alpha = self.contact["contact_angle"][:stop, :, race].T
        load = self.contact["contact_load"][:stop, :, race].T
        return phi, alpha, loaded_mask(load, alpha)

    def reference_contact_angle(self, race: int) -> float:
        """Mean contact angle of the loaded contacts on ``race`` over all frames (rad).

        The exaggeration of the across-groove deviation is taken about this value.
        """
        alpha = self.contact["contact_angle"][:, :, race]
        ok = loaded_mask(self.contact["contact_load"][:, :, race], alpha)
        if not ok.any():
            ok = np.isfinite(alpha)
        return float(alpha[ok].mean()) if ok.any() else 0.0

    # ---- construction ---------------------------------------------------------------------------
    @classmethod
    def from_dynamic(cls, ds: xr.Dataset) -> FrameSource:
        """Frames of a dynamic result: one per ``time`` sample."""
        _require(ds, ("ball_center", "ball_azimuth", "raceway_azimuth", *_CONTACT_VARS))
        t = np.asarray(ds["time"].values, float)
        omega_i, omega_o = ring_speeds(ds)
        centre = _arr(ds, "ball_center", ("time", "ball", "axis"))
        if "ball_orientation" in ds:
            quat = _arr(ds, "ball_orientation", ("time", "ball", "quaternion"))
            rotation = quaternion_to_matrix(quat)
        else:
            raise ValueError(
                "the dynamic result has no 'ball_orientation' variable (results-schema.md): "
                "the 3-D "
                "view needs it to show the ball spin"
            )
        psi = np.unwrap(np.radians(_arr(ds, "ball_azimuth", ("time", "ball"))), axis=0)
        if "cage_speed" in ds:
            w_cage = _arr(ds, "cage_speed", ("time",))
            cage = np.concatenate([[0.0], np.cumsum(0.5 * (w_cage[1:] + w_cage[:-1]) * np.diff(t))])
        else:
            cage = psi.mean(axis=1) - psi[0].mean()
        contact = {}
        for name in (*_CONTACT_VARS, *[v for v in _OPTIONAL_CONTACT_VARS if v in ds]):
            values = _arr(ds, name, ("time", "ball", "race"))
            contact[name] = np.radians(values) if name in _ANGLE_VARS else values
        raceway = np.unwrap(
            np.radians(_arr(ds, "raceway_azimuth", ("time", "ball", "race"))), axis=0
        )
        rings = np.stack(
            [
                _ring_turn(ds, "inner_ring_speed", omega_i, t),
                _ring_turn(ds, "outer_ring_speed", omega_o, t),
            ],
            axis=1,
        )
        return cls("dynamic", t, centre, rotation, psi, rings, cage, contact, raceway)

    @classmethod
    def from_quasistatic(
        cls,
        ds: xr.Dataset,
        revolutions: float | None = None,
        samples_per_revolution: int = QS_SAMPLES_PER_REVOLUTION,
    ) -> FrameSource:
        """Steady rigid kinematics from a quasi-static result (see module docstring).

        ``revolutions`` (shaft revolutions to animate, at most :data:`QS_MAX_REVOLUTIONS`)
        defaults to :data:`QS_DEFAULT_REVOLUTIONS`. Ring speeds come from the result's
        coordinates.
        """
        _require(ds, ("ball_center", "ball_azimuth", "ball_angular_velocity", *_CONTACT_VARS))
        omega_i, omega_o = ring_speeds(ds)
        if revolutions is None:
            revolutions = QS_DEFAULT_REVOLUTIONS
        revolutions = min(float(revolutions), QS_MAX_REVOLUTIONS)
        psi0 = np.radians(_arr(ds, "ball_azimuth", ("ball",)))
        if "cage_speed" in ds and np.isfinite(float(ds["cage_speed"])):
            w_cage = float(ds["cage_speed"])
        else:
            w_cage = float(np.nanmean(_arr(ds, "orbital_speed", ("ball",))))
        # Period of one shaft revolution relative to the outer ring; a static case animates 1 s.
        w_rel = abs(omega_i - omega_o)
        period = TWO_PI / w_rel if w_rel > 0 else 1.0
        n = max(2, int(round(revolutions * samples_per_revolution)) + 1)
        t = np.linspace(0.0, revolutions * period, n)

        psi = psi0[None, :] + w_cage * t[:, None]  # (N, Z)
        # Per-ball steady quantities as periodic functions of azimuth.
        centre0 = _arr(ds, "ball_center", ("ball", "axis"))
        centre_az = np.einsum("zij,zj->zi", rot_x(-psi0), centre0)  # azimuth-frame components
        omega_b = _arr(ds, "ball_angular_velocity", ("ball", "axis"))
        spin_az = np.einsum("zij,zj->zi", rot_x(-psi0), omega_b)
        spin_az[:, 0] -= w_cage  # spin relative to the azimuth frame, which turns at the cage speed
        centre_t = periodic_interp(psi, psi0, centre_az)  # (N, Z, 3)
        spin_t = periodic_interp(psi, psi0, spin_az)
        ball_centre = np.einsum("nzij,nzj->nzi", rot_x(psi), centre_t)
        rate = np.linalg.norm(spin_t, axis=-1)  # (N, Z) rad/s
        angle = np.concatenate(
            [
                np.zeros((1, psi.shape[1])),
                np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(t)[:, None], axis=0),
            ]
        )
        axis = spin_t / np.where(rate > 0, rate, 1.0)[..., None]
        axis[rate == 0] = (1.0, 0.0, 0.0)
        rotation = np.einsum("nzij,nzjk->nzik", rot_x(psi), axis_angle_matrix(axis, angle))

        contact = {}
        for name in (*_CONTACT_VARS, *[v for v in ("spin_to_roll",) if v in ds]):
            values = _arr(ds, name, ("ball", "race"))
            if name == "contact_angle":
                values = np.radians(values)
            contact[name] = periodic_interp(psi, psi0, values)
        rings = np.stack([omega_i * t, omega_o * t], axis=1)
        raceway = psi[:, :, None] - rings[:, None, :]  # contact in the ball's meridian plane
        cage = w_cage * t
        return cls("quasistatic", t, ball_centre, rotation, psi, rings, cage, contact, raceway)


def frame_source(ds: xr.Dataset, **quasistatic_options) -> FrameSource:
    """Frame source for a result: dynamic when it has a ``time`` dimension, quasi-static over a
    revolution when it has a ``ring_angle`` dimension, else quasi-static."""
    if "time" in ds.dims:
        return FrameSource.from_dynamic(ds)
    if "ring_angle" in ds.dims:
        return from_revolution(ds, **quasistatic_options)
    return FrameSource.from_quasistatic(ds, **quasistatic_options)


def from_revolution(ds: xr.Dataset, **quasistatic_options) -> FrameSource:
    """Frames of a quasi-static solution over one revolution (``solver.solve_over_revolution``).

    The kinematics are those of :meth:`FrameSource.from_quasistatic` for the first ring angle; the
    contact data at a frame are those of the solution at the inner ring's angle at that time
    relative to the outer ring (linear between the solved angles, periodic), each at the ball's
    azimuth (periodic linear interpolation between the solved balls). So a misalignment turning
    with the inner ring is shown over the whole revolution, not frozen at t = 0.
    """
    first = ds.isel(ring_angle=0).drop_vars("ring_angle")
    base = FrameSource.from_quasistatic(first, **quasistatic_options)
    angles = np.radians(np.asarray(ds["ring_angle"].values, float))
    theta = np.mod(base.ring_angle[:, INNER] - base.ring_angle[:, OUTER], TWO_PI)  # (N,)
    position = np.interp(theta, np.append(angles, TWO_PI), np.arange(angles.size + 1))
    k0 = np.floor(position).astype(int) % angles.size
    k1 = (k0 + 1) % angles.size
    w = (position - np.floor(position))[:, None, None]
    psi0 = np.radians(_arr(ds, "ball_azimuth", ("ring_angle", "ball")))  # (K, Z)
    stacked = np.stack(
        [_arr(ds, name, ("ring_angle", "ball", "race")) for name in _CONTACT_VARS], axis=-1
    )  # (K, Z, 2, V)
    rows = np.arange(base.n_frames)
    per_angle = np.array(
        [periodic_interp(base.ball_azimuth, psi0[k], stacked[k]) for k in range(angles.size)]
    )  # (K, N, Z, 2, V)
    blended = (1.0 - w[..., None]) * per_angle[k0, rows] + w[..., None] * per_angle[k1, rows]
    contact = {}
    for v, name in enumerate(_CONTACT_VARS):
        values = blended[..., v]
        contact[name] = np.radians(values) if name == "contact_angle" else values
    return FrameSource(
        "quasistatic",
        base.times,
        base.ball_center,
        base.ball_rotation,
        base.ball_azimuth,
        base.ring_angle,
        base.cage_angle,
        contact,
        base.raceway_azimuth,
    )


# ---- helpers ------------------------------------------------------------------------------------
def _ring_turn(ds: xr.Dataset, name: str, speed: float, t: np.ndarray) -> np.ndarray:
    """Turn of a ring since the first sample [rad]: ``speed`` [rad/s] times the time, or, where the
    result's speed ``name`` varies over ``time`` (along a history), the trapezoid integral of it."""
    if name in ds.data_vars and "time" in ds.variables[name].dims:
        w = _arr(ds, name, ("time",))
        return np.concatenate([[0.0], np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(t))])
    return speed * (t - t[0])


def ring_speeds(ds: xr.Dataset) -> tuple[float, float]:
    """(inner, outer) ring speeds in rad/s from the result's coordinates (ValueError without)."""
    from solver import ring_speeds as result_ring_speeds

    return result_ring_speeds(ds)


def _require(ds: xr.Dataset, names) -> None:
    missing = [n for n in names if n not in ds]
    if missing:
        raise ValueError(f"the result lacks the variables {', '.join(missing)} (results-schema.md)")


def _arr(ds: xr.Dataset, name: str, dims: tuple[str, ...]) -> np.ndarray:
    """Variable ``name`` of ``ds`` with its dimensions in the order ``dims``, as floats. Read as
    a bare ``Variable``: building a DataArray attaches every coordinate of a result (dozens), and
    a live chunk's frames were mostly that (65 ms of a chunk's 90 ms in the app's session)."""
    return np.asarray(ds.variables[name].transpose(*dims).values, dtype=float)


def periodic_interp(psi: np.ndarray, psi0: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Values known at azimuths ``psi0`` (Z,) evaluated at ``psi`` (any shape), period 2 pi.

    ``values`` has shape (Z, ...); the result has shape ``psi.shape + values.shape[1:]``.
    """
    flat = values.reshape(len(psi0), -1)
    out = np.empty((psi.size, flat.shape[1]))
    q = np.mod(psi.ravel(), TWO_PI)
    p0 = np.mod(psi0, TWO_PI)
    for k in range(flat.shape[1]):
        out[:, k] = np.interp(q, p0, flat[:, k], period=TWO_PI)
    return out.reshape(psi.shape + values.shape[1:])


def rot_x(angle) -> np.ndarray:
    """Rotation matrices about +x by ``angle`` (rad, any shape) -> shape (..., 3, 3)."""
    angle = np.asarray(angle, float)
    c, s = np.cos(angle), np.sin(angle)
    m = np.zeros(angle.shape + (3, 3))
    m[..., 0, 0] = 1.0
    m[..., 1, 1] = c
    m[..., 1, 2] = -s
    m[..., 2, 1] = s
    m[..., 2, 2] = c
    return m


def axis_angle_matrix(axis: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """Rodrigues rotation matrices for unit ``axis`` (..., 3) and ``angle`` (...) rad."""
    x, y, z = axis[..., 0], axis[..., 1], axis[..., 2]
    c, s = np.cos(angle), np.sin(angle)
    C = 1.0 - c
    m = np.empty(axis.shape[:-1] + (3, 3))
    m[..., 0, 0] = c + x * x * C
    m[..., 0, 1] = x * y * C - z * s
    m[..., 0, 2] = x * z * C + y * s
    m[..., 1, 0] = y * x * C + z * s
    m[..., 1, 1] = c + y * y * C
    m[..., 1, 2] = y * z * C - x * s
    m[..., 2, 0] = z * x * C - y * s
    m[..., 2, 1] = z * y * C + x * s
    m[..., 2, 2] = c + z * z * C
    return m


def quaternion_to_matrix(q: np.ndarray) -> np.ndarray:
    """Quaternions [w, x, y, z] (..., 4) -> rotation matrices (..., 3, 3), normalised first."""
    q = q / np.linalg.norm(q, axis=-1, keepdims=True)
    w, x, y, z = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    m = np.empty(q.shape[:-1] + (3, 3))
    m[..., 0, 0] = 1 - 2 * (y * y + z * z)
    m[..., 0, 1] = 2 * (x * y - w * z)
    m[..., 0, 2] = 2 * (x * z + w * y)
    m[..., 1, 0] = 2 * (x * y + w * z)
    m[..., 1, 1] = 1 - 2 * (x * x + z * z)
    m[..., 1, 2] = 2 * (y * z - w * x)
    m[..., 2, 0] = 2 * (x * z - w * y)
    m[..., 2, 1] = 2 * (y * z + w * x)
    m[..., 2, 2] = 1 - 2 * (x * x + y * y)
    return m


__all__ = ["Frame", "FrameSource", "frame_source", "ring_speeds", "INNER", "OUTER"]
