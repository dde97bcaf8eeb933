"""A result or study file is outside input: text it holds is shown as text in its report, never
run as script, when the report is opened from disk."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

pytest.importorskip("panel")

# each payload marks the page if the browser runs it
IMG = "<img src=x onerror=window.__pwned=1;document.title='pwned'>"
SCRIPT = "<script>window.__pwned=2;document.title='pwned'</script>"
SVG = "<svg onload=window.__pwned=3>"
PAYLOAD = IMG + SCRIPT + SVG
PAYLOAD_ESCAPED = "&lt;img src=x onerror=window.__pwned=1;document.title=&#x27;pwned&#x27;&gt;"


def _hostile_case(text: str) -> str:
    """The case text with its title and geometry provenance replaced by the payload (TOML)."""
    text = re.sub(r'(?m)^title = ".*"$', f'title = "{PAYLOAD}"', text)
    return re.sub(r'(?m)^provenance = "[^"]*"', f'provenance = "{PAYLOAD}"', text)


@pytest.fixture(scope="module")
def hostile_result():
    """A quasi-static result whose every text attribute, its case's title and provenance and its
    text coordinate ``misalignment_frame`` are the payload."""
    import solver

    case = solver.catalogue().get("spindle-combined-load").load()
    ds = solver.solve_quasistatic(case)
    for name, value in list(ds.attrs.items()):
        if isinstance(value, str):
            ds.attrs[name] = _hostile_case(value) if name == "case" else PAYLOAD
    ds.attrs["title"] = PAYLOAD
    return ds.assign_coords(misalignment_frame=PAYLOAD)  # a text coordinate the report shows


def test_the_run_header_shows_every_attribute_as_text(hostile_result):
    from report.build import run_header

    header = run_header(hostile_result, IMG + ".nc")
    assert "<img" not in header and "<script" not in header and "<svg" not in header
    assert PAYLOAD_ESCAPED in header  # the title and the file name, shown literally
    assert "quasistatic result" not in header and "unknown result" in header  # model: not known
    assert "on an unknown time" in header  # created: not a time
    assert f"computed with {PAYLOAD_ESCAPED}" in header  # software, shown literally


def test_the_study_header_shows_every_attribute_as_text():
    import xarray as xr

    from report.build import study_header

    ds = xr.Dataset(coords={"point": ["p0001"]})
    ds.attrs.update(title=PAYLOAD, base_case=PAYLOAD, software_version=PAYLOAD, description=PAYLOAD)
    header = study_header(ds)
    assert "<img" not in header and "<script" not in header and "<svg" not in header
    assert header.count(PAYLOAD_ESCAPED) == 4


def test_the_sanitiser_keeps_the_reports_markup_only():
    from report.build import sanitized

    ours = '<div class="rt-section"><h2>a</h2><table class="rt-table"><tbody><tr>'
    ours += '<td class="text">b</td></tr></tbody></table><pre class="rt-case">c</pre></div>'
    assert sanitized(ours) == ours
    assert sanitized(f"<p>{PAYLOAD}</p>") == "<p></p>"


CHROMIUM = "/usr/bin/chromium"
CHART_ROWS = """() => {
  const rows = [];
  for (const doc of (window.Bokeh ? Bokeh.documents : [])) {
    for (const m of doc.all_models) {
      if ((m.type || m.constructor.name) === "ColumnDataSource") {
        const cols = Object.values(m.data);
        rows.push(cols.length ? cols[0].length : 0);
      }
    }
  }
  return rows;
}"""


def _open_and_check(path: Path, texts: list[str]) -> None:
    """Open ``path`` in headless Chromium (no network): nothing of the payload ran, and each of
    ``texts`` is on the page as text."""
    playwright = pytest.importorskip("playwright.sync_api")
    if not Path(CHROMIUM).exists():
        pytest.skip(f"{CHROMIUM} is missing")
    with playwright.sync_playwright() as p:
        browser = p.chromium.launch(
            executable_path=CHROMIUM, args=["--headless", "--no-sandbox", "--use-gl=swiftshader"]
        )
        try:
            context = browser.new_context(offline=True)
            context.route(
                "**/*",
                lambda r: (
                    r.continue_()
                    if r.request.url.startswith(("file:", "data:", "blob:"))
                    else r.abort()
                ),
            )
            page = context.new_page()
            page.goto(path.as_uri(), timeout=120_000)
            page.wait_for_function(f"({CHART_ROWS})().some((r) => r > 0)", timeout=120_000)
            page.wait_for_timeout(1500)  # an image's onerror fires after its failed load
            assert page.evaluate("window.__pwned") is None
            assert page.title() != "pwned" and "pwned" not in page.title().replace(IMG, "")
            for text in texts:
                assert page.get_by_text(text, exact=False).count() > 0, text
        finally:
            browser.close()


@pytest.mark.browser
def test_a_hostile_result_report_runs_no_script(hostile_result, tmp_path):
    import solver
    from report import build_report

    source = tmp_path / f"{IMG}.nc"  # the file name too
    out = tmp_path / "review.html"
    # a 'model' that is not a model makes the file no racetrace result: refused, no page built
    solver.save_dataset(hostile_result, source)
    with pytest.raises(solver.CaseError, match="'model' attribute"):
        build_report(source, out)
    assert not out.exists()
    # every other attribute hostile: the page shows them as text and runs nothing
    solver.save_dataset(hostile_result.assign_attrs(model="quasistatic"), source)
    build_report(source, out)
    # the title is shown as the case's title (the heading is the result's operating point)
    _open_and_check(out, [PAYLOAD, f"{IMG}.nc"])
