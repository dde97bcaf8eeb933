"""What a run report holds for a design review, read from a shipped lesson result: the rating lives
as ``racetrace simulate`` prints them, friction torque beside the estimates, losses, film, the
margins against limits, the inputs, ring displacement and stiffness and per-ball ranges over the
analysed window, every value in engineering units; a study point's title and report heading name
its own operating point."""

from __future__ import annotations

import html
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("panel")

ROOT = Path(__file__).resolve().parents[2]
#: A dynamic lesson result whose case title (500 N + 300 N) is not its operating point.
RADIAL = ROOT / "assets" / "lessons" / "results" / "03-radial-load--radial.nc"
#: A quasi-static lesson result near the pressure limit.
HEAVY = ROOT / "assets" / "lessons" / "results" / "06-overload--heavy.nc"


@pytest.fixture(scope="module")
def radial():
    import solver

    return solver.load_dataset(RADIAL)


@pytest.fixture(scope="module")
def heavy():
    import solver

    return solver.load_dataset(HEAVY)


def test_engineering_units_and_ordinals():
    from report.units import ordinal, shown

    assert shown(1.708e9, "Pa") == "1.708 GPa"
    assert shown(3.5e8, "Pa") == "350 MPa"
    assert shown(7.128e-6, "m") == "7.128 µm"
    assert shown(0.0541, "m") == "54.1 mm"
    assert shown(0.01234, "N m") == "12.34 N·mm"
    assert shown(2.0e7, "N/m") == "20 N/µm"
    assert shown(2094.3951, "rad/s") == "20\u2009000 rpm"
    assert shown(math.nan, "Pa") == "-"
    assert [ordinal(n) for n in (1, 2, 3, 4, 11, 12, 13, 21, 22, 112)] == [
        "1st",
        "2nd",
        "3rd",
        "4th",
        "11th",
        "12th",
        "13th",
        "21st",
        "22nd",
        "112th",
    ]


def test_life_rows_are_the_lives_the_command_line_prints(radial):
    from racetrace.metrics import life_headline
    from report.build import _life_rows
    from report.units import number

    rows, notes = _life_rows(radial)
    table = dict(rows)
    life = life_headline(radial)
    assert table["basic rating life L10 (ISO 281)"] == (
        f"{number(life['L10_million_revolutions'])} million revolutions"
    )
    assert table["reference rating life L10r as time (ISO/TS 16281)"] == (
        f"{number(life['L10r_hours'])} h"
    )
    assert table["dynamic equivalent load P_r (ISO 281)"] == (
        f"{number(life['equivalent_load_N'])} N"
    )
    assert notes == life["notes"]
    torque = float(radial.racetrace.metric("mean_friction_torque"))
    assert table["mean friction torque"] == f"{number(torque * 1e3)} N·mm"
    palmgren = float(radial.racetrace.metric("friction_torque_palmgren"))
    assert table["Palmgren friction torque estimate"] == f"{number(palmgren * 1e3)} N·mm"
    # the hybrid bearing has no SKF estimate: its note stands in the table
    assert table["SKF-model friction torque estimate"].startswith("not available")
    residual = float(radial.racetrace.metric("energy_balance_residual"))
    assert table["energy balance residual"] == number(residual)


def test_losses_by_source_add_up_to_the_total(radial, heavy):
    from report.build import _loss_rows

    rows = dict(_loss_rows(radial))
    sources = [k for k in rows if k.startswith("power loss: ")]
    assert len(sources) == radial.sizes["loss_source"]
    total = sum(float(rows[k].removesuffix(" W")) for k in sources)
    mean_total = float(radial.racetrace.metric("mean_total_power_loss"))
    assert total == pytest.approx(mean_total, rel=2e-3)
    assert rows["mean total power loss"] == f"{mean_total:.4g} W"
    assert rows["mean contact heat: inner race"].endswith(" W")
    assert _loss_rows(heavy) is None  # a quasi-static result has no losses of its own


def test_margins_name_each_limit_and_race(radial, heavy):
    from report.build import _margin_rows
    from report.units import shown

    rows = {row[0]: row for row in _margin_rows(heavy)}
    peak = heavy.racetrace.metric("peak_pressure")
    pressure = rows["peak contact pressure"]
    assert pressure[1] == shown(float(peak.sel(race="inner")), "Pa")
    assert pressure[3] == "4.2 GPa (ISO 76)"
    below = 4.2e9 - float(peak.sel(race="outer"))
    assert f"outer {shown(below, 'Pa')} below" in pressure[4]
    margin = heavy.racetrace.metric("min_truncation_margin")
    truncation = rows["smallest truncation margin (ellipse to shoulder)"]
    assert truncation[1:3] == tuple(
        shown(float(margin.sel(race=r)), "degree") for r in ("inner", "outer")
    )
    assert "mean spin-to-roll ratio" in rows and "cage slip (1 - cage speed / epicyclic)" in rows
    dynamic = {row[0]: row for row in _margin_rows(radial)}
    assert "energy-balance residual" in dynamic
    assert dynamic["Palmgren friction torque estimate"][4].startswith("model / estimate = ")
    assert dynamic["SKF-model friction torque estimate"][4].startswith("not available")


def test_inputs_come_from_the_result(radial):
    from report.build import _input_rows

    rows = dict(_input_rows(radial))
    assert rows["ball material"].startswith("silicon_nitride: E 310 GPa")
    assert rows["ring material"].startswith("bearing_steel: E 208 GPa")
    assert rows["inner groove curvature f = r / D"].startswith("0.54 (r = 3.858 mm)")
    assert rows["outer groove curvature f = r / D"].startswith("0.53 (r = 3.786 mm)")
    assert rows["inner shoulder diameter"] == "49.1 mm"
    assert rows["outer shoulder diameter"] == "58.9 mm"
    assert "free contact angle α0 15 deg" in rows["clearance or preload"]
    assert "200 N" in rows["clearance or preload"]  # the result's own axial load
    assert "viscosity 10 mPa·s" in rows["lubricant"]


def test_displacement_and_stiffness(radial):
    from report.build import _stiffness_rows

    rows = dict(_stiffness_rows(radial))
    radial_mm = float(radial.racetrace.metric("radial_displacement"))
    assert rows["radial ring displacement"] == f"{radial_mm * 1e6:.4g} µm"
    stiffness = 550.0 / radial_mm
    assert rows["radial secant stiffness"] == f"{stiffness * 1e-6:.4g} N/µm"


def test_per_ball_ranges_span_the_analysed_window(radial):
    from report.build import _ball_range_rows
    from report.units import shown

    headers, rows = _ball_range_rows(radial)
    assert headers[:3] == ["ball", "Q inner min", "Q inner max"]
    start = float(radial.racetrace.metric("analysis_start_time"))
    window = radial["contact_load"].sel(race="outer").where(radial["time"] >= start)
    ball = 4
    low, high = (float(getattr(window.isel(ball=ball), how)("time")) for how in ("min", "max"))
    assert low < high  # a ball under radial load: its load changes around the orbit
    row = rows[ball]
    assert row[headers.index("Q outer min")] == shown(low, "N")
    assert row[headers.index("Q outer max")] == shown(high, "N")
    assert len(rows) == radial.sizes["ball"]


def test_per_ball_values_of_a_snapshot_are_one_column_each(heavy):
    from report.build import _ball_range_rows
    from report.units import shown

    assert "time" not in heavy.dims and "ring_angle" not in heavy.dims
    headers, rows = _ball_range_rows(heavy)
    assert len(set(headers)) == len(headers), headers
    assert headers[:3] == ["ball", "Q inner", "α inner"]
    load = float(heavy["contact_load"].sel(race="outer").isel(ball=2))
    assert rows[2][headers.index("Q outer")] == shown(load, "N")


def test_the_heading_is_the_results_own_operating_point(radial):
    from report.build import run_header

    header = run_header(radial, "radial.nc")
    # the result's case title says 500 N + 300 N; the lesson ran it at 200 N + 550 N
    assert "racetrace review: 20 000 rpm, 200 N axial + 550 N radial</h1>" in header
    assert f"case: <strong>{radial.attrs['title']}</strong>" in header


def test_the_run_report_page_is_in_engineering_units(radial, tmp_path):
    from report import build_report

    info = build_report(RADIAL, tmp_path / "review.html")
    text = (tmp_path / "review.html").read_text(encoding="utf-8")
    for heading in (
        "Inputs",
        "Rating life and friction torque",
        "Power loss and heat",
        "Film thickness and",
        "Margins against limits",
        "Ring displacement and stiffness",
        "Per ball over the analysed window",
        "outer ring is drawn apart from the balls and opened",
    ):
        assert heading in text, heading
    # no SI value in scientific notation with a base unit anywhere on the page
    raw = re.findall(r"\d\.\d+e[+-]\d+ ?(?:Pa|m|N m)\b", text)
    assert raw == [], raw[:5]
    assert "every 2th" not in text and info["unresolved"] == []


def test_a_study_points_title_names_its_operating_point(tmp_path):
    from solver.study import Study, StudyFolder

    study = Study.from_text(
        'title = "titles"\nbase = "spindle-combined-load"\n'
        '[vary]\n"operating.inner_ring_speed_rpm" = [10000.0, 20000.0]\n'
        '[set]\n"operating.axial_load_N" = 400.0\n"operating.radial_load_N" = 0.0\n'
    )
    points = study.points()
    titles = [p.case.title for p in points]
    assert titles == [
        "7008C-class hybrid, 10 000 rpm, 400 N axial + 0 N radial (study point p0001)",
        "7008C-class hybrid, 20 000 rpm, 400 N axial + 0 N radial (study point p0002)",
    ]
    folder = StudyFolder(tmp_path / "s")
    folder.start(study.spec, points, "test", resume=False)
    manifest = json.loads((tmp_path / "s" / "study.json").read_text())
    assert [p["title"] for p in manifest["points"]] == titles


def test_a_study_table_flags_messages_and_tables_band_width():
    import solver
    from report.build import _study_table

    ds = solver.load_dataset(ROOT / "assets" / "studies" / "results" / "seed-spindle.study.nc")
    table, notes = _study_table(ds, {})
    assert "width_i deg" in table and "width_o deg" in table
    settle = "run too short to settle"
    assert table.count(">[1]<") > 1  # a note number in each row it concerns
    assert settle not in table and f"[1] <strong>{settle}</strong>" in notes
    full = [m for m in ds["message"].values.ravel() if str(m).startswith(settle)]
    assert full and all(html.escape(str(m)[:150]) not in table for m in full)
    for message in full:  # each full text once, below the table
        assert notes.count(html.escape(str(message))) == 1
    width = float(ds["band_width"].sel(model="dynamic", race="outer").values[0])
    assert f"{width:.4g}" in table


def test_a_study_table_shows_rounding_noise_as_zero():
    import solver
    from report.build import _study_table

    ds = solver.load_dataset(ROOT / "assets" / "studies" / "results" / "seed-spindle.study.nc")
    noise = float(ds["excursion"].sel(model="quasistatic", race="outer").values[0])
    assert 0 < abs(noise) < 1e-9  # no radial load: a zero excursion, up to rounding
    table, _notes = _study_table(ds, {})
    cells = re.findall(r"<td>([^<]*)</td>", table)
    assert cells and not [c for c in cells if re.search(r"e-(1\d|[2-9]\d)$", c)]
    first = re.search(
        r"<tr><td class=\"text\">p0001</td><td class=\"text\">qs</td>(.*?)</tr>", table
    )
    assert first is not None
    row = re.findall(r"<td[^>]*>([^<]*)</td>", first.group(1))
    keys = json.loads(ds.attrs["varied_keys"])
    assert row[len(keys) + 1 : len(keys) + 3] == ["0", "0"]  # exc_i, exc_o


def test_scientific_numbers_are_not_in_engineering_cells():
    from report.units import number

    assert number(np.float64(12345.6)) == "12\u2009346"
    assert number(0.01123) == "0.01123"


def test_film_table_and_margins_show_lambda_per_race_with_its_regime(heavy):
    from report.build import _film_rows, _margin_rows, lambda_regime
    from report.units import number

    lam = heavy.racetrace.metric("min_film_parameter")
    values = [float(lam.sel(race=r)) for r in ("inner", "outer")]
    rows = {row[0]: row for row in _film_rows(heavy)}
    assert rows["smallest film parameter λ"][1:] == tuple(number(v, 3) for v in values)
    assert rows["lubrication regime"][1:] == tuple(lambda_regime(v) for v in values)
    margin = {row[0]: row for row in _margin_rows(heavy)}["smallest film parameter λ"]
    assert margin[3] == "> 3 full film"
    assert margin[4] == "; ".join(
        f"{r} {lambda_regime(v)}" for r, v in zip(("inner", "outer"), values, strict=True)
    )
    assert [lambda_regime(v) for v in (0.5, 1.0, 2.9, 3.0, 7.0)] == [
        "boundary",
        "mixed",
        "mixed",
        "full film",
        "full film",
    ]
    assert lambda_regime(math.nan) == "-"


def test_the_pressure_scale_spans_the_scenes_painted_range(radial):
    """The HTML scale beside the 3-D view carries the range and colours of the scene's painted
    raceways (peak pressure, GPa), which reach the result's largest contact pressure."""
    import pyvista as pv

    from report.scene import bearing_plotter, pressure_scale_html
    from solver import geometry_from_result
    from viz.frames import FrameSource
    from viz.options import SceneOptions
    from viz.scene import BearingScene

    _, _, scale = bearing_plotter(radial)
    plotter = pv.Plotter(off_screen=True)
    scene = BearingScene(
        plotter, geometry_from_result(radial), SceneOptions(track_quantity="peak_pressure")
    )
    source = FrameSource.from_dynamic(radial)
    scene.show_source(source, source.n_frames - 1)
    assert (scale.lo, scale.hi) == scene.track_range
    loaded = radial["max_pressure"].where(radial["contact_load"] > 0)
    assert scale.hi == pytest.approx(float(loaded.max()) * 1e-9, rel=1e-3)
    assert 0.0 <= scale.lo < scale.hi
    assert scale.colours[0] != scale.colours[-1]
    page = pressure_scale_html(scale)
    assert f'data-lo-gpa="{scale.lo!r}"' in page and f'data-hi-gpa="{scale.hi!r}"' in page
    assert "peak contact pressure [GPa]" in page
    assert f"{scale.hi:.3g}</span>" in page


def test_raceway_map_markers_of_a_snapshot_can_be_seen(radial, heavy):
    """A quasi-static snapshot puts one contact per ball on a raceway map: large markers; a dynamic
    run thousands: fine dots."""
    from report.charts import raceway_map

    for ds, smallest, largest in ((heavy, 4, None), (radial, None, 2)):
        for race in ("inner", "outer"):
            fig, _note = raceway_map(ds, race)
            sizes = [r.glyph.size for r in fig.renderers if hasattr(r.glyph, "size")]
            assert len(sizes) == 3, sizes  # two ellipse edges and the centre
            if smallest is not None:
                assert min(sizes) >= smallest, (race, sizes)
            if largest is not None:
                assert max(sizes) <= largest, (race, sizes)
