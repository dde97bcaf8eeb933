"""The ball legend, the comparison of many runs and the Studies panel in headless Chromium.

The server runs in a subprocess with a runs folder that already holds three saved quasi-static
runs of the default bearing under different radial loads (made here with the solver). State is
set explicitly (``window.trame.state.set``) and every wait polls its condition with a deadline.
Screenshots go to ``test-artifacts/browser/ui/``.
"""

from __future__ import annotations

import pytest

from tests.helpers.browser import ARTIFACTS, BROWSER_MARKS, FIRST_IMAGE
from tests.helpers.serve import start_server, stop_server

pytestmark = BROWSER_MARKS
pytest.importorskip("distributed")

SHOTS = ARTIFACTS / "ui"
RADIAL_LOADS = (0.0, 600.0, 1200.0)
TITLE = "7008C-class hybrid spindle, 20 000 rpm, 500 N axial, {:.0f} N radial, a long run name"


def _save_runs(root) -> list[str]:
    """Three saved quasi-static runs of the default case, radial load 0, 600 and 1200 N."""
    from app.run_store import RunStore
    from app.state import DEFAULT_CASE
    from solver import solve_quasistatic
    from solver.catalogue import catalogue

    store = RunStore(root)
    base = catalogue().get(DEFAULT_CASE).load()
    titles = []
    for radial in RADIAL_LOADS:
        case = base.with_values({"operating.radial_load_N": radial})
        titles.append(TITLE.format(radial))
        store.save(solve_quasistatic(case), case.to_toml(), titles[-1])
    return titles


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    runs = tmp_path_factory.mktemp("runs")
    titles = _save_runs(runs)
    served = start_server(runs, tmp_path_factory.mktemp("log") / "serve.log")
    yield {**served, "titles": titles}
    stop_server(served)


@pytest.fixture
def page(browser, server):
    SHOTS.mkdir(parents=True, exist_ok=True)
    context = browser.new_context(viewport={"width": 1500, "height": 1000})
    pg = context.new_page()
    pg.goto(server["url"], timeout=120_000)  # a loaded machine starts sessions slowly
    pg.wait_for_selector(FIRST_IMAGE, timeout=120_000)
    pg.wait_for_function(
        "window.trame && window.trame.state.get('result_serial') > 0", timeout=60_000
    )
    pg.evaluate("window.trame.state.set('playing', false)")
    yield pg
    context.close()


def _state(pg, name):
    return pg.evaluate(f"window.trame.state.get({name!r})")


def _set_state(pg, name, value) -> None:
    import json

    pg.evaluate(f"window.trame.state.set({name!r}, {json.dumps(value)})")


def _wait(pg, js: str, timeout_s: float, what: str) -> None:
    try:
        pg.wait_for_function(js, timeout=timeout_s * 1000, polling=250)
    except Exception as error:  # noqa: BLE001 - said with what was awaited
        raise AssertionError(f"{what} not seen within {timeout_s} s: {error}") from None


def test_ball_legend_names_every_ball_in_its_colour_over_the_view(page):
    legend = page.locator("#ball-legend")
    _wait(page, "document.querySelectorAll('#ball-legend .rt-ball-entry').length > 0", 30, "legend")
    assert legend.is_visible()
    balls = _state(page, "ball_legend")
    assert len(balls) == 18  # the default case's bearing
    entries = page.locator("#ball-legend .rt-ball-entry")
    assert entries.count() == 18
    assert [entries.nth(j).inner_text().strip() for j in range(18)] == [str(j) for j in range(18)]
    # each number beside a dot in that ball's colour (the colours the scene draws)
    dots = page.evaluate(
        "[...document.querySelectorAll('#ball-legend .rt-ball-entry > span:first-child')]"
        ".map(e => getComputedStyle(e).backgroundColor)"
    )
    expected = [
        "rgb({}, {}, {})".format(*(int(b["colour"][k : k + 2], 16) for k in (1, 3, 5)))
        for b in balls
    ]
    assert dots == expected
    assert len(set(dots)) == 18
    # over the 3-D view at the default camera
    view = page.locator("#view-3d").bounding_box()
    box = legend.bounding_box()
    assert view["x"] <= box["x"] and box["x"] + box["width"] <= view["x"] + view["width"]
    assert view["y"] <= box["y"] and box["y"] + box["height"] <= view["y"] + view["height"]
    page.locator("#view-3d").screenshot(path=str(SHOTS / "ball-legend.png"))


def test_compare_four_runs_each_in_its_colour_with_full_names(page, server):
    _wait(page, "(window.trame.state.get('runs') || []).length >= 3", 30, "the saved runs")
    ids = [r["value"] for r in _state(page, "runs")]
    _set_state(page, "open_panels", ["compare"])
    _set_state(page, "compare_ids", ids)
    _wait(
        page,
        "document.querySelectorAll('#compare-legend .rt-compare-entry').length === 4",
        60,
        "a legend entry for each of the four runs",
    )
    entries = page.locator("#compare-legend .rt-compare-entry")
    texts = [entries.nth(i).inner_text() for i in range(4)]
    assert [t.split()[0] for t in texts] == ["A", "B", "C", "D"]
    for title in server["titles"]:  # every saved run named in full, none cut short
        assert sum(title in t for t in texts) == 1, (title, texts)
    for i in range(4):
        box = entries.nth(i).bounding_box()
        panel = page.locator("#compare-legend").bounding_box()
        assert box["x"] + box["width"] <= panel["x"] + panel["width"] + 1
    swatches = page.evaluate(
        "[...document.querySelectorAll('#compare-legend .rt-compare-entry')].map(e => "
        "getComputedStyle(e.querySelector('span > span')).backgroundColor)"
    )
    assert len(set(swatches)) == 4
    # the charts hold every run: two legend entries (inner, outer) per run
    _wait(
        page,
        "document.querySelectorAll('#chart-compare-angle .legend .traces').length === 8",
        60,
        "the contact-angle overlay of four runs",
    )
    assert page.locator("#chart-compare-runs .legend .traces").count() == 8
    # the summary table: a row per run and race
    rows = page.locator("#compare-summary tbody tr")
    assert rows.count() == 8
    assert [rows.nth(i).locator("td").first.inner_text().strip() for i in range(0, 8, 2)] == [
        "A",
        "B",
        "C",
        "D",
    ]
    page.locator("#compare-legend").scroll_into_view_if_needed()
    page.screenshot(path=str(SHOTS / "compare-four-runs.png"))


def test_studies_panel_opens_shipped_results_and_runs_a_study_built_from_the_case(page):
    _set_state(page, "open_panels", ["studies"])
    page.wait_for_selector("#study-build-run", timeout=30_000)
    # a shipped study's results: table and chart without running anything
    _set_state(page, "study_results", "shipped:seed-spindle.study.nc")
    _wait(page, "(window.trame.state.get('study_rows') || []).length === 30", 60, "30 rows")
    _wait(page, "document.querySelector('#chart-study .main-svg') !== null", 60, "the chart")
    assert page.locator("#study-table tbody tr").count() == 30
    assert "Seed study" in page.locator("#study-status").inner_text()
    page.locator("#studies").scroll_into_view_if_needed()
    page.screenshot(path=str(SHOTS / "study-shipped.png"))
    # build a tiny quasi-static study from the case in the form and run it
    _set_state(page, "study_key1", "operating.radial_load_N")
    _set_state(page, "study_key2", None)
    _set_state(page, "study_model", "quasistatic")
    values = page.locator("#study-values1 input")
    values.fill("0:600:3")
    values.press("Tab")
    _wait(page, "window.trame.state.get('study_values1') === '0:600:3'", 10, "the values typed")
    page.locator("#study-build-run").click()
    _wait(
        page,
        "['done', 'error'].some(w => (window.trame.state.get('study_status') || '').startsWith(w))",
        300,
        "the built study's end",
    )
    assert page.locator("#study-status").inner_text().strip() == "done"
    _wait(page, "document.querySelectorAll('#study-table tbody tr').length === 3", 30, "3 rows")
    assert [r["status"] for r in _state(page, "study_rows")] == ["done"] * 3
    # open one point's run in the 3-D view and the charts
    serial = _state(page, "result_serial")
    page.locator("#study-table tbody tr").nth(1).get_by_role("button", name="open").click()
    _wait(page, f"window.trame.state.get('result_serial') > {serial}", 60, "the point's run")
    assert "p0002" in page.locator("#result-label").inner_text()
    # a click on a point of the chart opens that point's run (plotly's click event, as a click
    # on the marker sends it)
    serial = _state(page, "result_serial")
    page.evaluate(
        "document.querySelector('#chart-study .js-plotly-plot').emit('plotly_click', "
        "{points: [{customdata: ['p0003', 'quasistatic']}]})"
    )
    _wait(page, f"window.trame.state.get('result_serial') > {serial}", 60, "the clicked run")
    assert "p0003" in page.locator("#result-label").inner_text()
    page.screenshot(path=str(SHOTS / "study-built.png"))
