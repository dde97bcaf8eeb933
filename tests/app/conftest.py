"""Fixtures for the app tests: a session without a browser (``app``), the served app and a headless
chromium for the browser tests (``server``, ``browser``; one of each per test module), and
datasets.

The datasets built here are TEST FIXTURES that follow results-schema.md with simple analytic
distributions (contact angles and loads as cosines of the azimuth); never shipped as results.
"""

from __future__ import annotations

import math
import os

if not os.environ.get("DISPLAY"):  # off-screen VTK on EGL (ui-notes.md); must precede VTK import
    os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")

import numpy as np
import pytest
import xarray as xr

from solver.geometry import BearingGeometry
from solver.results.dataset import describing_coordinates
from tests.helpers.app_session import trame_server
from tests.helpers.cases import SPINDLE_BEARING, case_text, operating_point, spindle_bearing
from tools.chromium import CHROMIUM, LAUNCH_ARGS

SHAFT_RPM = 6000.0
FIXTURE_CASE = case_text(
    "app test fixture",
    SPINDLE_BEARING | {"ball_count": 12},
    {"inner_ring_speed_rpm": SHAFT_RPM, "axial_load_N": 500.0, "radial_load_N": 300.0},
    "[simulation]\nshaft_revolutions = 2.0\nsamples_per_revolution = 36\n",
)

# Analytic distributions sampled by the fixture (degrees, newtons), also used as test references.
ALPHA_MEAN = {"inner": 20.0, "outer": 17.0}
ALPHA_AMPL = {"inner": 3.0, "outer": 2.0}
CAGE_RATIO = 0.44  # cage speed / shaft speed
SPIN_RATE = -1200.0  # rad/s, ball spin relative to its azimuth frame
SPIN_TILT_DEG = 20.0  # attitude of the spin axis from the bearing axis


def alpha_of_psi(psi_rad, race):
    return ALPHA_MEAN[race] + ALPHA_AMPL[race] * np.cos(psi_rad)


def load_of_psi(psi_rad):
    return np.maximum(0.0, 100.0 + 150.0 * np.cos(psi_rad))


def fixture_geometry() -> BearingGeometry:
    return spindle_bearing(ball_count=12)


def fixture_coordinates() -> dict:
    """The describing coordinates of the fixture case (operating point and geometry)."""
    operating = operating_point(
        inner_ring_speed=SHAFT_RPM * 2 * np.pi / 60, axial_load=500.0, radial_load=300.0
    )
    return describing_coordinates(fixture_geometry(), operating)


def make_quasistatic_dataset(ball_count: int = 12) -> xr.Dataset:
    z = ball_count
    psi = 2 * np.pi * np.arange(z) / z
    omega = SHAFT_RPM * 2 * np.pi / 60
    w_cage = CAGE_RATIO * omega
    alpha = np.stack([alpha_of_psi(psi, "inner"), alpha_of_psi(psi, "outer")], axis=1)
    load = np.stack([load_of_psi(psi), load_of_psi(psi) + 5.0], axis=1)
    load[load[:, 0] == 0.0, 1] = 0.0
    alpha = np.where(load > 0, alpha, np.nan)
    radius = 27e-3
    centre = np.stack([np.full(z, 1e-5), radius * np.cos(psi), radius * np.sin(psi)], axis=1)
    beta = math.radians(SPIN_TILT_DEG)
    # spin relative to the azimuth frame, plus the orbital rotation, expressed in the inertial frame
    spin_az = np.array([SPIN_RATE * math.cos(beta) + w_cage, -SPIN_RATE * math.sin(beta), 0.0])
    omega_b = np.stack(
        [[spin_az[0], spin_az[1] * math.cos(p), spin_az[1] * math.sin(p)] for p in psi]
    )
    a = np.where(load > 0, 0.8e-3 * (load / 250.0) ** (1 / 3), 0.0)
    b = 0.12 * a
    pmax = np.where(load > 0, 1.5 * load / (np.pi * np.where(a > 0, a * b, 1.0)), 0.0)
    ds = xr.Dataset(
        {
            "contact_angle": (("ball", "race"), alpha, {"units": "degree"}),
            "contact_load": (("ball", "race"), load, {"units": "N"}),
            "ellipse_semi_major": (("ball", "race"), a, {"units": "m"}),
            "ellipse_semi_minor": (("ball", "race"), b, {"units": "m"}),
            "max_pressure": (("ball", "race"), pmax, {"units": "Pa"}),
            "raceway_azimuth": (
                ("ball", "race"),
                np.degrees(np.stack([psi, psi], 1)),
                {"units": "degree"},
            ),
            "ball_azimuth": (("ball",), np.degrees(psi), {"units": "degree"}),
            "orbital_speed": (("ball",), np.full(z, w_cage), {"units": "rad/s"}),
            "ball_center": (("ball", "axis"), centre, {"units": "m"}),
            "ball_angular_velocity": (("ball", "axis"), omega_b, {"units": "rad/s"}),
            "cage_speed": ((), w_cage, {"units": "rad/s"}),
        },
        coords={
            "ball": np.arange(z),
            "race": ["inner", "outer"],
            "axis": ["x", "y", "z"],
            **fixture_coordinates(),
        },
        attrs={
            "model": "quasistatic",
            "case": FIXTURE_CASE,
            "software": "test fixture",
            "created": "2026-11-22T00:00:00Z",
            "complete": 1,
        },
    )
    return ds


def make_dynamic_dataset(ball_count: int = 12, n_time: int = 40) -> xr.Dataset:
    """Rigid steady motion sampled in time, with a quaternion spin about +x (test fixture)."""
    z = ball_count
    omega = SHAFT_RPM * 2 * np.pi / 60
    w_cage = CAGE_RATIO * omega
    t = np.linspace(0.0, 2 * 2 * np.pi / omega, n_time)
    psi0 = 2 * np.pi * np.arange(z) / z
    psi = psi0[:, None] + w_cage * t[None, :]  # (ball, time)
    alpha = np.stack([alpha_of_psi(psi, "inner"), alpha_of_psi(psi, "outer")], axis=1)
    load = np.stack([load_of_psi(psi), load_of_psi(psi)], axis=1)
    centre = np.stack([np.full_like(psi, 1e-5), 27e-3 * np.cos(psi), 27e-3 * np.sin(psi)], axis=1)
    half = 0.5 * SPIN_RATE * t[None, :] * np.ones((z, 1))
    quat = np.stack([np.cos(half), np.sin(half), 0 * half, 0 * half], axis=1)  # spin about +x
    raceway = np.stack([np.mod(psi - omega * t, 2 * np.pi), np.mod(psi, 2 * np.pi)], axis=1)
    a = 0.8e-3 * np.ones_like(load)
    ds = xr.Dataset(
        {
            "contact_angle": (("ball", "race", "time"), alpha, {"units": "degree"}),
            "contact_load": (("ball", "race", "time"), load, {"units": "N"}),
            "ellipse_semi_major": (("ball", "race", "time"), a, {"units": "m"}),
            "ellipse_semi_minor": (("ball", "race", "time"), 0.1 * a, {"units": "m"}),
            "max_pressure": (("ball", "race", "time"), 1e9 * np.ones_like(load), {"units": "Pa"}),
            "raceway_azimuth": (("ball", "race", "time"), np.degrees(raceway), {"units": "degree"}),
            "ball_azimuth": (
                ("ball", "time"),
                np.degrees(np.mod(psi, 2 * np.pi)),
                {"units": "degree"},
            ),
            "ball_center": (("ball", "axis", "time"), centre, {"units": "m"}),
            "ball_orientation": (("ball", "quaternion", "time"), quat, {"units": "1"}),
            "cage_speed": (("time",), np.full(n_time, w_cage), {"units": "rad/s"}),
        },
        coords={
            "ball": np.arange(z),
            "race": ["inner", "outer"],
            "axis": ["x", "y", "z"],
            "quaternion": ["w", "x", "y", "z"],
            "time": t,
            **fixture_coordinates(),
        },
        attrs={
            "model": "dynamic",
            "case": FIXTURE_CASE,
            "software": "test fixture",
            "created": "2026-11-22T00:00:00Z",
            "complete": 1,
        },
    )
    return ds


@pytest.fixture
def qs_dataset() -> xr.Dataset:
    return make_quasistatic_dataset()


@pytest.fixture
def dynamic_dataset() -> xr.Dataset:
    return make_dynamic_dataset()


@pytest.fixture
def geometry() -> BearingGeometry:
    return fixture_geometry()


@pytest.fixture
def fixture_model():
    """This module: the analytic distributions the fixture datasets sample (test references)."""
    import sys

    return sys.modules[__name__]


@pytest.fixture
def app(tmp_path):
    """A session (``RacetraceApp``) on the default case, not playing, without rendering; its runs
    folder is ``tmp_path / "runs"``."""
    from app.state import DEFAULT_CASE, RacetraceApp

    session = RacetraceApp(trame_server(), runs_dir=tmp_path / "runs", render=False)
    session.start(DEFAULT_CASE, play=False)
    yield session
    session.shutdown()


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    """``racetrace serve`` in a subprocess with an empty runs folder (a module that needs another
    server defines its own ``server``)."""
    from tests.helpers.serve import start_server, stop_server

    runs = tmp_path_factory.mktemp("runs")
    served = start_server(runs, tmp_path_factory.mktemp("log") / "serve.log")
    yield served
    stop_server(served)


@pytest.fixture(scope="module")
def browser():
    """Headless Debian chromium driven by Playwright."""
    import playwright.sync_api as playwright_api

    with playwright_api.sync_playwright() as p:
        launched = p.chromium.launch(executable_path=CHROMIUM, args=LAUNCH_ARGS)
        yield launched
        launched.close()
