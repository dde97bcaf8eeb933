"""Off-screen VTK rendering: the environment it needs, and a start-up check that it works here.

Used by the app's server and the report (both render without a display).

VTK picks its OpenGL back end at run time; without a display it uses EGL on Mesa's software driver,
which needs the Debian packages ``libegl1`` and ``libgl1-mesa-dri``. When they are missing VTK dies
with a segmentation fault rather than a Python error, so the check renders one small frame in a
CHILD process and reports what to install when the child fails.
"""

from __future__ import annotations

import os
import subprocess
import sys
from dataclasses import dataclass

INSTALL_COMMAND = "apt-get install -y --no-install-recommends libegl1 libgl1-mesa-dri"

# Rendered by the child: one sphere, 64x64 pixels, must not be blank.
_CHILD_SCRIPT = """
import pyvista as pv
pv.global_theme.multi_samples = 0
p = pv.Plotter(off_screen=True, window_size=(64, 64))
p.set_background("white")
p.add_mesh(pv.Sphere(), color="black")
p.render()
img = p.screenshot(return_img=True)
p.close()
assert img.shape[:2] == (64, 64), img.shape
assert img.min() < 128, "rendered image is blank"
print("ok")
"""


@dataclass(frozen=True)
class OffscreenCheck:
    """Outcome of :func:`check_offscreen_rendering`: ``ok`` and a message for the user when not."""

    ok: bool
    message: str


def configure_environment(environ: dict | None = None) -> None:
    """Select the EGL render window when there is no X display (X probing can segfault).

    Also sets ``pv.global_theme.multi_samples = 0`` if pyvista is already imported (a frame in
    software rendering is about 3.5x cheaper without multisampling).
    """
    env = os.environ if environ is None else environ
    if not env.get("DISPLAY"):
        env.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    if "pyvista" in sys.modules:
        sys.modules["pyvista"].global_theme.multi_samples = 0


def check_offscreen_rendering(timeout: float = 120.0) -> OffscreenCheck:
    """Render one frame in a child Python process; never crashes the caller.

    ``timeout`` is in seconds. Returns ``OffscreenCheck(ok=False, message=...)`` naming the packages
    to install when the child fails (a segfault shows as a negative return code).
    """
    env = dict(os.environ)
    configure_environment(env)
    try:
        proc = subprocess.run(
            [sys.executable, "-c", _CHILD_SCRIPT],
            env=env,
            capture_output=True,
            text=True,
            timeout=timeout,
        )
    except subprocess.TimeoutExpired:
        return OffscreenCheck(
            False, _failure_message(f"the test render took longer than {timeout:.0f} s")
        )
    if proc.returncode == 0 and proc.stdout.strip().endswith("ok"):
        return OffscreenCheck(True, "off-screen rendering works")
    if proc.returncode < 0:
        reason = (
            f"the test render was killed by signal {-proc.returncode} (VTK could not open OpenGL)"
        )
    else:
        last = (proc.stderr.strip().splitlines() or ["no output"])[-1]
        reason = f"the test render failed ({last})"
    return OffscreenCheck(False, _failure_message(reason))


def _failure_message(reason: str) -> str:
    return (
        f"off-screen 3-D rendering does not work: {reason}.\n"
        "The 3-D view renders on the server with VTK, which needs the system OpenGL libraries "
        "(EGL and Mesa). On Debian/Ubuntu install them with:\n"
        f"    {INSTALL_COMMAND}"
    )
