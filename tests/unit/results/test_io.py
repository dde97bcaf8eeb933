"""NetCDF save/load: round trip (strings included) and atomic writes."""

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from solver.results.io import load_dataset, save_dataset
from tests.helpers.cases import DEEP_GROOVE_RADIAL
from tests.helpers.faults import check_failed_write_keeps_the_old_file


def small_dataset():
    return xr.Dataset(
        {
            "contact_load": (("ball", "race"), np.arange(6.0).reshape(3, 2), {"units": "N"}),
            "race_control": (("ball",), np.array(["inner", "outer", "outer"], dtype=object)),
            "cage_speed": ((), 12.5, {"units": "rad/s"}),
        },
        coords={"ball": np.arange(3), "race": np.array(["inner", "outer"], dtype=object)},
        attrs={"model": "quasistatic", "complete": 1, "case": "title = 'x'\n"},
    )


def test_round_trip_keeps_values_strings_and_attributes(tmp_path):
    ds = small_dataset()
    path = save_dataset(ds, tmp_path / "r.nc")
    back = load_dataset(path)
    xr.testing.assert_identical(back, ds)
    assert list(back.race_control.values) == ["inner", "outer", "outer"]


def test_round_trip_of_a_model_dataset(tmp_path):
    from solver.case import parse_case
    from solver.models.quasistatic import solve_quasistatic

    ds = solve_quasistatic(parse_case(DEEP_GROOVE_RADIAL))
    back = load_dataset(save_dataset(ds, tmp_path / "qs.nc"))
    xr.testing.assert_identical(back, ds)


def test_failed_write_leaves_no_temporary_file_and_keeps_the_old_one(tmp_path, monkeypatch):
    target = tmp_path / "r.nc"
    save_dataset(small_dataset(), target)
    check_failed_write_keeps_the_old_file(
        target, lambda: save_dataset(small_dataset(), target), monkeypatch
    )


def test_saved_file_has_the_usual_permissions(tmp_path):
    """The atomic write goes through a private temporary file; the result must not stay private."""
    import os
    import stat

    mask = os.umask(0o022)
    try:
        path = save_dataset(small_dataset(), tmp_path / "shared.nc")
    finally:
        os.umask(mask)
    assert stat.S_IMODE(path.stat().st_mode) == 0o644


@pytest.mark.parametrize(
    ("failure", "words"),
    [
        (
            RuntimeError("NetCDF: HDF error"),
            "NetCDF: HDF error (is the disk full or the folder read-only?)",
        ),
        (OSError(28, "No space left on device"), "No space left on device"),
        (OSError(27, "File too large"), "File too large (a file-size limit, e.g. ulimit -f)"),
        (KeyboardInterrupt(), None),
        (SystemExit(143), None),
    ],
)
def test_interrupted_or_failed_write_names_the_file_and_cleans_up(
    tmp_path, monkeypatch, failure, words
):  # noqa: E501
    from solver.errors import ResultWriteError

    def broken(self, *args, **kwargs):
        Path(args[0]).write_bytes(b"\x89HDF\r\n\x1a\npartial")
        raise failure

    monkeypatch.setattr(xr.Dataset, "to_netcdf", broken)
    target = tmp_path / "r.nc"
    expected = ResultWriteError if words else type(failure)
    with pytest.raises(expected) as caught:
        save_dataset(small_dataset(), target)
    if words:
        assert str(caught.value) == f"could not write {target}: {words}"
        assert isinstance(caught.value, OSError) and caught.value.path == target
    assert list(tmp_path.iterdir()) == []


def test_missing_folder_folder_and_device_are_refused_by_name(tmp_path):
    from solver.errors import ResultWriteError

    for target, words in [
        (tmp_path / "missing" / "r.nc", "No such file or directory"),
        (tmp_path, "it is a folder"),
        (Path("/dev/null"), "not a regular file"),
    ]:
        with pytest.raises(ResultWriteError, match=words):
            save_dataset(small_dataset(), target)
    assert Path("/dev/null").exists() and not Path("/dev/null").is_file()
