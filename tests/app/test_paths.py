"""app.paths: a name from a page is a bare file name under its folder, never a path."""

from __future__ import annotations

import os

import pytest

from app.paths import UnsafeNameError, child_path, name_problem


def test_a_bare_name_is_its_folder_child(tmp_path):
    assert child_path(tmp_path, "run-1.nc") == tmp_path / "run-1.nc"
    assert child_path(tmp_path, "not-there-yet") == tmp_path / "not-there-yet"
    assert child_path(tmp_path, "..hidden..") == tmp_path / "..hidden.."
    assert name_problem("p0001.dynamic.nc") == ""


@pytest.mark.parametrize(
    ("name", "words"),
    [
        ("/etc/passwd", "separator"),
        ("../secret", "separator"),
        ("..", "reference to a folder"),
        (".", "reference to a folder"),
        ("a/../../b", "separator"),
        ("a\\..\\b", "separator"),
        ("run\x00.nc", "NUL"),
        ("", "empty"),
        ("x" * 256, "longer than"),
        (None, "must be text"),
        (["a"], "must be text"),
        (7, "must be text"),
    ],
)
def test_anything_but_a_bare_name_is_refused(tmp_path, name, words):
    with pytest.raises(UnsafeNameError, match=words) as caught:
        child_path(tmp_path, name, "study folder")
    assert str(caught.value).startswith("study folder ")


def test_a_link_leading_out_of_the_folder_is_refused(tmp_path):
    root = tmp_path / "root"
    root.mkdir()
    (tmp_path / "outside").mkdir()
    os.symlink(tmp_path / "outside", root / "escape")
    os.symlink(root, root / "itself")
    os.symlink(root / "inner", root / "inside")
    for name in ("escape", "itself"):
        with pytest.raises(UnsafeNameError, match="leads out of its folder"):
            child_path(root, name)
    assert child_path(root, "inside") == root / "inside"  # a link that stays under the root


def test_a_relative_root_is_kept_as_given(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert child_path("runs", "a.nc") == tmp_path.joinpath("runs", "a.nc").relative_to(tmp_path)
