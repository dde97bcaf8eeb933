"""The app's palettes: every ball of a bearing its own colour, runs in distinct colours."""

from __future__ import annotations

import re

import pytest

from viz import palette

HEX = re.compile(r"^#[0-9a-f]{6}$")


@pytest.mark.parametrize("n", [9, 16, 18, 20, 40])
def test_every_ball_gets_its_own_colour(n):
    colours = palette.ball_colours(n)
    assert len(colours) == n
    assert len(set(colours)) == n
    assert all(HEX.match(c) for c in colours)
    assert colours[:3] == list(palette.BALL_PALETTE[:3])


def test_ball_legend_names_each_ball_with_its_colour():
    legend = palette.ball_legend(18)
    assert [e["ball"] for e in legend] == list(range(18))
    assert [e["colour"] for e in legend] == palette.ball_colours(18)
    with pytest.raises(ValueError, match="numbered from 0"):
        palette.ball_colour(-1)


def test_runs_get_distinct_colours_and_a_darker_outer_shade():
    runs = [palette.run_colours(i) for i in range(palette.MAX_COMPARED)]
    assert len({r["run"] for r in runs}) == palette.MAX_COMPARED
    for r in runs:
        assert r[0] == r["run"] and r[1] != r[0]
        assert sum(int(r[1][k : k + 2], 16) for k in (1, 3, 5)) < sum(
            int(r[0][k : k + 2], 16) for k in (1, 3, 5)
        )
    assert [palette.run_tag(i) for i in range(4)] == ["A", "B", "C", "D"]
