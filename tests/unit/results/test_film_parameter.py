"""The film parameter λ (solver.results.metrics ``min_film_parameter``): the smallest film
thickness of each race over the composite roughness of the case's balls and raceways, read from
the result's case (its roughness keys or their schema defaults); a bad roughness is a clear case
error, and the roughness does not enter a result's fingerprint (no model reads it)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import solver
from solver.case import parse_case
from solver.case.schema import BALL_ROUGHNESS_UM, RACEWAY_ROUGHNESS_UM
from solver.errors import CaseError

ROOT = Path(__file__).resolve().parents[3]
RESULT = ROOT / "assets" / "lessons" / "results" / "03-radial-load--radial.nc"


@pytest.fixture(scope="module")
def result():
    return solver.load_dataset(RESULT)


def _with_roughness(ds, ball_um: float, raceway_um: float):
    """``ds`` with its case text given the two roughness keys (in place of any it has)."""
    kept = [
        line
        for line in str(ds.attrs["case"]).splitlines(keepends=True)
        if not line.lstrip().startswith(("ball_roughness_um", "raceway_roughness_um"))
    ]
    text = "".join(kept).replace(
        "[bearing]\n",
        f"[bearing]\nball_roughness_um = {ball_um}\nraceway_roughness_um = {raceway_um}\n",
        1,
    )
    assert text != ds.attrs["case"]
    out = ds.copy()
    out.attrs = {**ds.attrs, "case": text}
    return out


def test_lambda_is_the_smallest_film_over_the_schema_default_roughness(result):
    """The shipped case gives no roughness: the schema defaults apply."""
    lam = result.racetrace.metric("min_film_parameter")
    film = result.racetrace.metric("min_film_thickness")
    composite = math.hypot(BALL_ROUGHNESS_UM, RACEWAY_ROUGHNESS_UM) * 1e-6
    assert lam.attrs["units"] == "1"
    assert np.all(np.isfinite(lam.values))
    np.testing.assert_allclose(lam.values, film.values / composite, rtol=1e-12)


def test_lambda_follows_the_roughness_of_the_case(result):
    rough = _with_roughness(result, 0.3, 0.4)  # composite 0.5 um
    lam = rough.racetrace.metric("min_film_parameter")
    film = rough.racetrace.metric("min_film_thickness")
    np.testing.assert_allclose(lam.values, film.values / 0.5e-6, rtol=1e-12)


def test_no_readable_case_gives_nan_with_the_reason(result):
    bare = result.copy()
    bare.attrs = {k: v for k, v in result.attrs.items() if k != "case"}
    lam = bare.racetrace.metric("min_film_parameter")
    assert np.all(np.isnan(lam.values))
    assert "roughness" in lam.attrs["note"]


@pytest.mark.parametrize(
    ("value", "words"),
    [(0.0, "at least 0.001 um"), (50.0, "at most 10 um"), ('"smooth"', "number")],
)
def test_bad_roughness_is_a_clear_case_error(result, value, words):
    text = str(_with_roughness(result, 0.025, 0.08).attrs["case"]).replace(
        "raceway_roughness_um = 0.08\n", f"raceway_roughness_um = {value}\n", 1
    )
    with pytest.raises(CaseError) as info:
        parse_case(text, "test case")
    message = str(info.value)
    assert "bearing.raceway_roughness_um" in message and words in message


def test_roughness_does_not_change_a_result_fingerprint(result):
    plain = parse_case(str(result.attrs["case"]), "plain")
    rough = parse_case(str(_with_roughness(result, 0.3, 0.4).attrs["case"]), "rough")
    assert rough.bearing.raceway_roughness_um == 0.4
    assert solver.result_fingerprint(plain, "dynamic") == solver.result_fingerprint(
        rough, "dynamic"
    )
