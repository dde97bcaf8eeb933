"""Start-up check of off-screen rendering: a child process; the install command on failure."""

from __future__ import annotations

import viz.offscreen as offscreen


def test_offscreen_rendering_works_here():
    result = offscreen.check_offscreen_rendering()
    assert result.ok, result.message


def test_crashing_child_gives_install_command(monkeypatch):
    # a child killed by a signal, as VTK is when libEGL / Mesa are missing
    monkeypatch.setattr(
        offscreen, "_CHILD_SCRIPT", "import os, signal; os.kill(os.getpid(), signal.SIGSEGV)"
    )
    result = offscreen.check_offscreen_rendering()
    assert not result.ok
    assert "signal 11" in result.message
    assert offscreen.INSTALL_COMMAND in result.message


def test_failing_child_names_the_error(monkeypatch):
    monkeypatch.setattr(offscreen, "_CHILD_SCRIPT", "raise ImportError('libEGL.so.1: cannot open')")
    result = offscreen.check_offscreen_rendering()
    assert not result.ok
    assert "libEGL.so.1" in result.message


def test_egl_selected_without_display():
    env = {}
    offscreen.configure_environment(env)
    assert env["VTK_DEFAULT_OPENGL_WINDOW"] == "vtkEGLRenderWindow"
    env = {"DISPLAY": ":0"}
    offscreen.configure_environment(env)
    assert "VTK_DEFAULT_OPENGL_WINDOW" not in env
