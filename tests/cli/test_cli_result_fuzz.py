"""Fuzz tests over result files: every mutated result file given to ``racetrace export`` or
``racetrace report`` is written or refused as invalid input (exit 2) naming what is wrong, never a
traceback (tests/helpers/fuzz.py says how result files are mutated). Fixed seeds, so that CI runs
the same inputs every time; ``python -m tests.explore_fuzz --surface report --seeds A-B`` explores
new ones."""

from __future__ import annotations

import random
import warnings

import pytest

from tests.helpers.fuzz import (
    ODD_CASE_TEXTS,
    RESULT_OUTCOMES,
    _base_dataset,
    _netcdf_bytes,
    mutated_result_bytes,
    result_outcome,
)

#: Seeds given to export: a mix of refused and written files, and one (2349: a scale factor
#: that numpy cannot apply, decoded as the check read it) that once ended in a traceback.
EXPORT_SEEDS = (*range(0, 12), 2349)
#: Seeds given to report whose files are refused before the page is built (quick), among them
#: three that once ended in a traceback in the 3-D scene (6: a quasi-static result with NaN ball
#: velocities; 104: one without them; 110: a dynamic result with a NaN cage speed), and one built
#: in full (5: a study Dataset).
REPORT_SEEDS = (1, 2, 3, 4, 7, 8, 9, 10, 11, 12, 14, 15, 17, 18, 19, 20, 6, 104, 110, 2349, 5)


def _outcome(seed: int, surface: str, folder) -> str:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # xarray's and numpy's warnings on odd values
        content = mutated_result_bytes(random.Random(seed))
    try:
        return result_outcome(content, surface, folder)
    except Exception as error:
        raise AssertionError(f"seed {seed}: {type(error).__name__}: {error}") from error


def test_every_mutated_result_file_given_to_export_ends_cleanly(tmp_path):
    outcomes = {_outcome(seed, "export", tmp_path) for seed in EXPORT_SEEDS}
    assert outcomes == set(RESULT_OUTCOMES)  # both refused and written files were tried


def test_every_mutated_result_file_given_to_report_ends_cleanly(tmp_path):
    pytest.importorskip("panel")
    outcomes = [_outcome(seed, "report", tmp_path) for seed in REPORT_SEEDS]
    assert "invalid input" in outcomes


@pytest.mark.parametrize("surface", ["report", "export"])
@pytest.mark.parametrize("text", ODD_CASE_TEXTS[:3], ids=["arrays", "tables", "digits"])
def test_a_case_attribute_nested_deep_is_named(tmp_path, surface, text):
    """A result whose ``case`` attribute nests thousands deep (or holds a number of thousands
    of digits) is refused naming that attribute, before anything parses it."""
    ds = _base_dataset(random.Random(0))
    ds.attrs["case"] = text
    content = _netcdf_bytes(ds)
    assert result_outcome(content, surface, tmp_path) == "invalid input"


@pytest.mark.parametrize("surface", ["report", "export"])
@pytest.mark.parametrize(
    "change, words",
    [
        (lambda ds: ds.drop_vars("contact_load"), "no 'contact_load' variable"),
        (lambda ds: ds.drop_vars("ball_diameter"), "no 'ball_diameter' coordinate"),
        (lambda ds: ds.drop_vars([]).assign_attrs(model=None), "no 'model' attribute"),
        (lambda ds: ds.assign_attrs(model=5), "'model' attribute is 5"),
    ],
    ids=["variable", "coordinate", "attributes", "model"],
)
def test_what_a_result_lacks_is_named(tmp_path, capsys, surface, change, words):
    from racetrace.cli import main

    ds = change(_base_dataset(random.Random(0)))
    ds.attrs = {k: v for k, v in ds.attrs.items() if v is not None}
    source = tmp_path / "bad.nc"
    source.write_bytes(_netcdf_bytes(ds))
    output = ["--output", str(tmp_path / "r.html")] if surface == "report" else []
    output = output or ["--csv", str(tmp_path / "t.csv")]
    assert main([surface, str(source), *output]) == 2
    err = capsys.readouterr().err
    assert words in err and "Traceback" not in err, err


def test_a_foreign_netcdf_file_is_said_to_be_no_result(tmp_path, capsys):
    import xarray as xr

    from racetrace.cli import main

    source = tmp_path / "foreign.nc"
    xr.Dataset({"temperature": ("x", [1.0, 2.0])}).to_netcdf(source)
    assert main(["export", str(source), "--csv", str(tmp_path / "t.csv")]) == 2
    assert "it is not a racetrace result file" in capsys.readouterr().err


@pytest.mark.parametrize(
    ("where", "words"),
    [("missing/r.html", ["does not exist"]), ("", ["is a folder", "review.html"])],
)
def test_report_checks_its_output_before_building(tmp_path, capsys, monkeypatch, where, words):
    """The page takes a minute to build: a missing folder or a folder as --output is refused
    first (exit 2), the page never built."""
    import report
    from racetrace.cli import main

    def refuse(*args, **kwargs):
        raise AssertionError("the page was built before the output was checked")

    monkeypatch.setattr(report, "build_report", refuse)
    source = tmp_path / "qs.nc"
    source.write_bytes(_netcdf_bytes(_base_dataset(random.Random(0))))
    assert main(["report", str(source), "--output", str(tmp_path / where)]) == 2
    err = capsys.readouterr().err
    assert all(w in err for w in words) and "Traceback" not in err, err


def test_every_shipped_result_passes_the_check():
    """The results and study Datasets racetrace ships read as results, values and all."""
    from solver.results.io import load_result
    from tests.helpers.fuzz import ROOT

    shipped = sorted(ROOT.glob("assets/**/*.nc"))
    assert len(shipped) >= 10
    for path in shipped:
        load_result(path)
