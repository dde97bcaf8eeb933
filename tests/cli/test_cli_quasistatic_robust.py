"""``racetrace quasistatic --json`` on mutated and extreme cases: exit 0, 2 or 3 only, never a
traceback, and stdout is valid JSON every time (an ``error`` object when it fails)."""

from __future__ import annotations

import json
import math
import random
import tomllib

import pytest
import tomli_w

from racetrace.cli import main
from solver.case.schema import FIELDS
from tests.helpers.cases import SPINDLE
from tests.helpers.fuzz import mutated_case_bytes


def _run(path, capsys):
    code = main(["quasistatic", str(path), "--json"])
    out, err = capsys.readouterr()
    assert "Traceback" not in err
    assert code in (0, 2, 3), err
    body = json.loads(out, parse_constant=lambda c: pytest.fail(f"{c} in JSON"))
    if code:
        assert body["error"]["exit_code"] == code and body["error"]["message"]
    else:
        assert body["model"] == "quasistatic"
    return code, body


@pytest.mark.parametrize("seed", range(40))
def test_mutated_cases_give_json_and_a_clean_exit(tmp_path, capsys, seed):
    path = tmp_path / "case.toml"
    path.write_bytes(mutated_case_bytes(random.Random(seed)))
    _run(path, capsys)


@pytest.mark.parametrize("end", ["minimum", "maximum"])
def test_every_operating_value_at_its_bound_together(tmp_path, capsys, end):
    data = tomllib.loads(SPINDLE)
    for f in FIELDS:
        bound = getattr(f, end)
        if f.section == "operating" and f.type == "float" and bound is not None:
            exclusive = not getattr(f, f"{end}_inclusive")
            value = float(bound)
            if exclusive:
                value = math.nextafter(value, math.inf if end == "minimum" else -math.inf)
            data["operating"][f.name] = value
    path = tmp_path / "case.toml"
    path.write_text(tomli_w.dumps(data))
    _run(path, capsys)


def test_invalid_input_json_lists_the_problems(tmp_path, capsys):
    path = tmp_path / "case.toml"
    path.write_text(SPINDLE.replace("ball_count = 18", "ball_count = 1"))
    code, body = _run(path, capsys)
    assert code == 2 and body["error"]["kind"] == "invalid input"
    assert [p["key"] for p in body["error"]["problems"]] == ["bearing.ball_count"]


def test_a_shaft_so_slow_that_the_speed_ratio_overflows_gives_null(tmp_path, capsys):
    """A subnormal shaft speed (what the fuzz test found: 1.1e-308 rpm) makes cage speed / shaft
    speed overflow; the JSON says null instead of failing on Infinity."""
    data = tomllib.loads(SPINDLE)
    data["operating"]["inner_ring_speed_rpm"] = 1.1e-308
    data["operating"]["outer_ring_speed_rpm"] = -20000.0
    path = tmp_path / "case.toml"
    path.write_text(tomli_w.dumps(data))
    code, body = _run(path, capsys)
    assert code == 0, body
    assert body["cage_to_shaft_speed_ratio"] is None
