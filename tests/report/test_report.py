"""racetrace report: one self-contained HTML file that opens in headless Chromium with no network,
whose 3-D canvas draws and whose charts hold data."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("panel")
pytest.importorskip("pyvista")

CHROMIUM = "/usr/bin/chromium"
LAUNCH_ARGS = ["--headless", "--no-sandbox", "--use-gl=swiftshader", "--ignore-gpu-blocklist"]

# every ColumnDataSource of every Bokeh document: the number of rows it holds
CHART_ROWS = """() => {
  const rows = [];
  for (const doc of (window.Bokeh ? Bokeh.documents : [])) {
    for (const m of doc.all_models) {
      const name = m.type || (m.constructor && m.constructor.name);
      if (name === "ColumnDataSource") {
        const cols = Object.values(m.data);
        rows.push(cols.length ? cols[0].length : 0);
      }
    }
  }
  return rows;
}"""


@pytest.fixture(scope="module")
def run_file(tmp_path_factory):
    import solver
    from solver.models.dynamic import SimulationOptions

    case = solver.catalogue().get("spindle-combined-load").load()
    ds = solver.simulate(
        case, options=SimulationOptions(shaft_revolutions=0.6, samples_per_revolution=60)
    )
    path = tmp_path_factory.mktemp("run") / "run.nc"
    solver.save_dataset(ds, path)
    return path


def _open_offline(path: Path, check):
    playwright = pytest.importorskip("playwright.sync_api")
    if not Path(CHROMIUM).exists():
        pytest.skip(f"{CHROMIUM} is missing")
    with playwright.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=LAUNCH_ARGS)
        try:
            context = browser.new_context(offline=True, viewport={"width": 1280, "height": 900})
            outside = []

            def route(r):
                if r.request.url.startswith(("file:", "data:", "blob:")):
                    return r.continue_()
                outside.append(r.request.url)
                return r.abort()

            context.route("**/*", route)
            page = context.new_page()
            page.goto(path.as_uri(), timeout=120_000)
            page.wait_for_function(f"({CHART_ROWS})().some((r) => r > 0)", timeout=120_000)
            check(page)
            assert outside == [], outside
        finally:
            browser.close()


def _canvas_pixels(page) -> np.ndarray:
    from PIL import Image

    canvas = page.locator("canvas").first  # the vtk.js scene comes first on a run report
    canvas.wait_for(timeout=60_000)
    page.wait_for_timeout(2000)
    png = canvas.screenshot(timeout=60_000)
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"))


def test_run_report_summary_shows_the_energy_balance(run_file):
    """A dynamic run's summary table carries its energy-balance residual (the metric)."""
    import solver
    from report.build import _summary_rows
    from report.units import number

    ds = solver.load_dataset(run_file)
    rows = {row[0]: row for row in _summary_rows(ds)}
    value = float(ds.racetrace.metric("energy_balance_residual"))
    assert np.isfinite(value)
    assert rows["energy balance residual"] == ("energy balance residual", number(value), "")


@pytest.mark.browser
def test_run_report_is_standalone_and_draws(run_file, tmp_path):
    from report import build_report

    info = build_report(run_file, tmp_path / "review.html")
    assert info["kind"] == "run"
    assert info["unresolved"] == []
    assert info["bytes"] < 15e6
    text = (tmp_path / "review.html").read_text()
    assert "cdn.holoviz.org" not in text
    for heading in ("Result warnings", "Summary", "Contact ellipses", "Case (as run)"):
        assert heading in text

    def check(page):
        pixels = _canvas_pixels(page)
        colours = np.unique(pixels.reshape(-1, 3), axis=0)
        assert len(colours) > 50, "the 3-D canvas is blank"
        rows = page.evaluate(CHART_ROWS)
        assert sum(r > 0 for r in rows) >= 4, rows  # raceway maps, angle and load lines
        # printed, the still image of the scene stands in for the interactive canvas
        picture = page.locator("img[alt='3-D scene']")
        assert not picture.is_visible()
        page.emulate_media(media="print")
        assert picture.is_visible()
        assert not page.locator("canvas").first.is_visible()
        assert len(page.pdf()) > 10_000

    _open_offline(tmp_path / "review.html", check)


def test_cli_report_names_a_missing_extra(monkeypatch, capsys, run_file, tmp_path):
    import report.build
    from racetrace import cli

    monkeypatch.setattr(report.build, "missing_report_modules", lambda: ["panel"])
    assert cli.main(["report", str(run_file), "--output", str(tmp_path / "r.html")]) == 2
    err = capsys.readouterr().err
    assert "panel" in err and 'pip install -e ".[report]"' in err
    assert not (tmp_path / "r.html").exists()


def test_cli_report_of_a_missing_source(capsys, tmp_path):
    from racetrace import cli

    assert cli.main(["report", str(tmp_path / "nothing.nc"), "-o", str(tmp_path / "r.html")]) == 2
    assert "no such result file or study folder" in capsys.readouterr().err


@pytest.mark.browser
def test_study_report_has_points_and_metric_charts(tmp_path):
    from dask.distributed import Client, LocalCluster

    from report import build_report
    from solver.study import Study

    study = Study.from_text(
        'title = "report study"\nbase = "spindle-axial-preload"\n'
        '[vary]\n"operating.radial_load_N" = [0.0, 300.0, 600.0]\n'
    )
    with LocalCluster(n_workers=1, processes=False, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            study.run(tmp_path / "study", client=client)
    info = build_report(tmp_path / "study", tmp_path / "study.html")
    assert info["kind"] == "study" and info["unresolved"] == []
    text = (tmp_path / "study.html").read_text()
    assert "p0003" in text and "report study" in text

    def check(page):
        rows = page.evaluate(CHART_ROWS)
        assert rows.count(3) >= 4, rows  # excursion, angle, pressure lines over 3 points

    _open_offline(tmp_path / "study.html", check)


def test_run_report_of_a_tilt_turning_with_the_ring(tmp_path):
    """A quasi-static answer over one revolution: the summary spans the revolution (the turning
    tilt's band thickness on the outer race), the scene and tables show ring angle 0."""
    import solver
    from report import build_report

    ds = solver.solve_over_revolution("spindle-misalignment-ring", angles=8)
    path = solver.save_dataset(ds, tmp_path / "ring.nc")
    info = build_report(path, tmp_path / "ring.html")
    assert info["kind"] == "run"
    text = (tmp_path / "ring.html").read_text()
    assert "show ring angle 0" in text
    assert "8 inner-ring angles over one revolution" in text
    thickness = float(ds.racetrace.metric("band_thickness").sel(race="outer"))
    assert np.isfinite(thickness)
    assert f"{thickness:.4g}" in text
