"""Accuracy contract of the dynamic model's default integration (docs/numerics.md): runs of four
cases against the stored explicit reference at tolerance 1e-6 (tests/helpers/accuracy.py), three
over 3 revolutions, the 218 heavy case over a fixed window of a 30-revolution run."""

from __future__ import annotations

import pytest

from tests.helpers import accuracy as A

#: the cases checked over their stored 3-revolution runs. The 218 heavy case is checked over a
#: long window instead (test_default_method_meets_the_contract_over_a_long_window): it does not
#: settle (sustained irregular cage and ball motion), and over 3 revolutions two reference-quality
#: runs (1e-6, 3e-6) differ by up to 3x the angle allowance and 3-15x the band and excursion
#: allowances (tests/helpers/reference_spread.py, docs/numerics.md), so no run can be checked there.
CONTRACT_CASES = [label for label in A.CASES if label not in A.LONG_WINDOW_CASES]


@pytest.mark.slow
@pytest.mark.parametrize("label", CONTRACT_CASES)
def test_default_method_meets_the_contract(label):
    reference = A.load_reference()
    assert reference["tolerance"] == A.REFERENCE_TOLERANCE
    ds = A.run(label)
    assert ds.attrs["complete"] == 1
    worst = A.deviations(A.metrics(ds), reference["cases"][label])
    assert max(worst.values()) <= 1.0, worst


@pytest.mark.parametrize(
    ("key", "change", "metric"),
    [
        ("contact_angle_deg", lambda v: v + 0.006, "contact_angle"),
        ("contact_load_N", lambda v: v * 1.003, "contact_load"),
        ("cage_speed_rad_s", lambda v: v * 1.0006, "cage_speed"),
        ("band_thickness_deg", lambda v: v * 1.03 + 0.0021, "band_thickness"),
    ],
)
def test_contract_comparison_flags_each_metric(key, change, metric):
    """The comparison itself: the reference matches itself, and a change just beyond one metric's
    allowance is flagged on that metric."""
    reference = A.load_reference()["cases"]["spindle_combined"]
    assert max(A.deviations(reference, reference).values()) == 0.0
    changed = dict(reference)
    value = reference[key]
    if isinstance(value, list):
        changed[key] = [
            [change(x) for x in row] if isinstance(row, list) else change(row) for row in value
        ]
    else:
        changed[key] = change(value)
    worst = A.deviations(changed, reference)
    assert worst[metric] > 1.0 and all(v == 0.0 for k, v in worst.items() if k != metric), worst


@pytest.mark.slow
@pytest.mark.parametrize("label", list(A.LONG_WINDOW_CASES))
def test_default_method_meets_the_contract_over_a_long_window(label):
    """A case whose short-run metrics are not reproducible (above): its long run against the
    stored reference run over the same fixed window, on the metrics that two reference-quality
    runs reproduce there (the 218 heavy case: per-ball mean contact angles and loads and the cage
    speed over revolutions 10-30, the angles within twice the reference runs' own spread
    (LONG_WINDOW_ALLOWANCE); its excursion and band thickness are not reproducible even between
    tolerances 1e-6 and 3e-6, docs/numerics.md)."""
    reference = A.load_reference()["long_window"][label]
    revolutions, first, checked = A.LONG_WINDOW_CASES[label]
    assert (reference["revolutions"], reference["window_start_revolution"]) == (revolutions, first)
    got, ds = A.long_run(label)
    assert ds.attrs["complete"] == 1
    worst = A.deviations(got, reference)
    allowance = A.LONG_WINDOW_ALLOWANCE.get(label, {})
    assert all(worst[k] <= allowance.get(k, 1.0) for k in checked), worst
