"""The review pages in headless Chromium: the run report of a shipped lesson result draws its 3-D
scene without WebGL framebuffer warnings and shows no stray "..." under it; the study report's
points table fits a 1300-px page; a study report links each point to its own run report, headed
with the point's own operating point. Screenshots of the three pages go to
``test-artifacts/browser/report/`` (gitignored) for inspection."""

from __future__ import annotations

import io
import re
from pathlib import Path

import numpy as np
import pytest

from tests.helpers.browser import ARTIFACTS, BROWSER_MARKS

pytest.importorskip("panel")
pytest.importorskip("pyvista")
playwright = pytest.importorskip("playwright.sync_api")

pytestmark = BROWSER_MARKS

from tests.report.test_report import CHART_ROWS, CHROMIUM, LAUNCH_ARGS  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
LESSON = ROOT / "assets" / "lessons" / "results" / "03-radial-load--radial.nc"
SEED_STUDY = ROOT / "assets" / "studies" / "results" / "seed-spindle.study.nc"
#: Every shipped study's results: of one bearing (per-race charts) and of a bearing set
#: (spindle-pair-db-speed: the set's line and one per bearing).
SHIPPED_STUDIES = sorted((ROOT / "assets" / "studies" / "results").glob("*.study.nc"))
SHOTS = ARTIFACTS / "report"
PAGE_WIDTH = 1300  # px: the page a review is read and printed on
FRAMEBUFFER = re.compile(r"framebuffer", re.IGNORECASE)
# every Bokeh figure on the page: its title and its plot area (the frame inside the axes) in page
# pixels
CHART_FRAMES = """() => {
  const frames = [];
  const isFigure = (view) => view.model && view.model.type === "Figure";
  for (const view of window.Bokeh ? Bokeh.index.query(isFigure) : []) {
    const box = view.el.getBoundingClientRect();
    const frame = view.frame.bbox;
    frames.push({
      title: view.model.title ? view.model.title.text : "",
      x: Math.round(box.left + window.scrollX + frame.left),
      y: Math.round(box.top + window.scrollY + frame.top),
      width: Math.round(frame.width),
      height: Math.round(frame.height),
    });
  }
  return frames;
}"""


@pytest.fixture(scope="module")
def chromium():
    """One headless Chromium for the module; each visit opens a context of its own."""
    with playwright.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=LAUNCH_ARGS)
        yield browser
        browser.close()


@pytest.fixture(scope="module")
def run_report(tmp_path_factory):
    """The run report of the shipped lesson result :data:`LESSON`, built once for the module (the
    tests only read it)."""
    from report import build_report

    path = tmp_path_factory.mktemp("run-report") / "run.html"
    build_report(LESSON, path)
    return path


def _visit(chromium, path: Path, check, screenshot: str):
    """Open ``path`` offline at PAGE_WIDTH in a new context of ``chromium``, wait for its charts,
    run ``check(page, console)`` and save a full-page screenshot as ``screenshot``."""
    context = chromium.new_context(offline=True, viewport={"width": PAGE_WIDTH, "height": 900})
    try:
        page = context.new_page()
        console: list[str] = []
        page.on("console", lambda message: console.append(message.text))
        page.goto(path.as_uri(), timeout=180_000)
        page.wait_for_function(f"({CHART_ROWS})().some((r) => r > 0)", timeout=180_000)
        page.wait_for_timeout(3000)
        check(page, console)
        SHOTS.mkdir(parents=True, exist_ok=True)
        page.screenshot(path=str(SHOTS / screenshot), full_page=True, timeout=120_000)
    finally:
        context.close()


def test_run_report_draws_without_framebuffer_warnings(chromium, run_report):
    from PIL import Image

    def check(page, console):
        canvas = page.locator("canvas").first  # the vtk.js scene comes first on a run report
        canvas.wait_for(timeout=60_000)
        page.wait_for_timeout(2000)
        pixels = np.asarray(Image.open(io.BytesIO(canvas.screenshot())).convert("RGB"))
        assert len(np.unique(pixels.reshape(-1, 3), axis=0)) > 50, "the 3-D canvas is blank"
        warnings = [m for m in console if FRAMEBUFFER.search(m)]
        assert warnings == [], f"{len(warnings)} WebGL warnings, e.g. {warnings[:2]}"
        # vtk.js's camera-info toggle ("...") is not shown under the scene
        dots = page.locator(".vtk_info")
        assert all(not dots.nth(k).is_visible() for k in range(dots.count()))
        heading = page.locator("h1").first.inner_text()
        assert heading == "racetrace review: 20 000 rpm, 200 N axial + 550 N radial"

    _visit(chromium, run_report, check, "run-report.png")


def test_study_report_table_fits_the_page(chromium, tmp_path):
    from report import build_report

    build_report(SEED_STUDY, tmp_path / "study.html")

    def check(page, console):  # noqa: ARG001 - the check's interface
        table = page.locator("table.rt-points")
        assert table.count() == 1
        box = table.bounding_box()
        assert box is not None and box["x"] >= 0
        assert box["x"] + box["width"] <= PAGE_WIDTH, box
        width = page.evaluate("document.documentElement.scrollWidth")
        assert width <= PAGE_WIDTH, f"the page scrolls sideways: {width} px"
        rows = table.locator("tbody tr:not(.rt-sweep)").count()
        assert rows == 30

    _visit(chromium, tmp_path / "study.html", check, "study-report.png")


@pytest.fixture(scope="module")
def point_study(tmp_path_factory):
    """A study folder of two quasi-static points solved as a worker solves them (no Dask)."""
    import solver
    from solver.study import Study, StudyFolder
    from solver.study.worker import run_one

    study = Study.from_text(
        'title = "point reports"\nbase = "spindle-combined-load"\nmodel = "quasistatic"\n'
        '[vary]\n"operating.radial_load_N" = [0.0, 400.0]\n'
        '[set]\n"operating.inner_ring_speed_rpm" = 10000.0\n'
    )
    path = tmp_path_factory.mktemp("points") / "study"
    folder = StudyFolder(path)
    points = study.points()
    folder.start(study.spec, points, solver.__version__, resume=False)
    for point in points:
        record, ds = run_one(point.case, "quasistatic")
        folder.save_run(point.name, "quasistatic", record, ds)
    folder.save_dataset()
    return path


def test_study_report_links_each_point_to_its_own_report(chromium, point_study, tmp_path):
    from report import build_report
    from report.build import point_report_path

    output = tmp_path / "study.html"
    build_report(point_study, output, point_reports=True)
    text = output.read_text(encoding="utf-8")
    for point in ("p0001", "p0002"):
        report = point_report_path(output, point, "quasistatic")
        assert report.is_file()
        assert f"study.points/{point}.quasistatic.html" in text
    second = point_report_path(output, "p0002", "quasistatic")

    def check(page, console):  # noqa: ARG001 - the check's interface
        heading = page.locator("h1").first.inner_text()
        assert heading == "racetrace review: 10 000 rpm, 500 N axial + 400 N radial"
        case = page.get_by_text("(study point p0002)").first.inner_text()
        assert "10 000 rpm, 500 N axial + 400 N radial" in case

    _visit(chromium, second, check, "point-report.png")

    def links(page, console):  # noqa: ARG001 - the check's interface
        link = page.locator("table.rt-points a", has_text="p0002")
        assert link.get_attribute("href") == "study.points/p0002.quasistatic.html"

    _visit(chromium, output, links, "point-study-report.png")


def _colour_pixels(image: np.ndarray, colour: str, tolerance: float = 40.0) -> int:
    """Pixels of ``image`` (RGB) within ``tolerance`` of ``colour`` ("#rrggbb")."""
    target = np.array([int(colour[k : k + 2], 16) for k in (1, 3, 5)], float)
    return int((np.linalg.norm(image.astype(float) - target, axis=-1) < tolerance).sum())


def _on_white(colour: str, alpha: float) -> str:
    """The colour ("#rrggbb") that ``colour`` drawn with opacity ``alpha`` shows on white."""
    rgb = [int(colour[k : k + 2], 16) for k in (1, 3, 5)]
    return "#" + "".join(f"{round(255 - alpha * (255 - c)):02x}" for c in rgb)


@pytest.mark.parametrize("study", SHIPPED_STUDIES, ids=lambda p: p.name.split(".")[0])
def test_study_report_charts_draw_their_lines(chromium, study, tmp_path):
    """In every chart of a shipped study's report, the plot area holds pixels of both races'
    colours (the lines and markers of the inner and outer race), not an empty frame; in a set
    study's, the colour of each line the chart draws: each bearing's and the set's (its
    markers)."""
    from PIL import Image

    import solver
    from report import build_report
    from report.build import SET_STUDY_CHART_METRICS, STUDY_CHART_METRICS
    from report.charts import PALETTE, RACE_COLOURS, SET_LINE_ALPHA, SET_LINE_COLOUR

    build_report(study, tmp_path / "study.html")
    ds = solver.load_dataset(study)
    sweeps = set(np.asarray(ds["sweep"].values).astype(str).tolist())
    if "bearing" in ds.dims:
        metrics = SET_STUDY_CHART_METRICS
        bearings = {str(b): PALETTE[k] for k, b in enumerate(ds["bearing"].values)}

        def colours_of(title):
            """{line: colour} of the set chart titled ``title``."""
            row = next(r for r in metrics if title.startswith(r[1] + " ("))
            out = {}
            for variable, *_ in row[3]:
                out.update(bearings if "bearing" in ds[variable].dims else {"set": SET_LINE_COLOUR})
            return out
    else:
        metrics = STUDY_CHART_METRICS

        def colours_of(title):  # noqa: ARG001 - every chart draws both races
            return RACE_COLOURS

    def check(page, console):  # noqa: ARG001 - the check's interface
        frames = page.evaluate(CHART_FRAMES)
        assert len(frames) == len(sweeps) * len(metrics), [f["title"] for f in frames]
        page_image = Image.open(io.BytesIO(page.screenshot(full_page=True, timeout=120_000)))
        pixels = np.asarray(page_image.convert("RGB"))
        empty = []
        for frame in frames:
            assert frame["width"] > 100 and frame["height"] > 100, frame
            area = pixels[
                frame["y"] : frame["y"] + frame["height"], frame["x"] : frame["x"] + frame["width"]
            ]
            counts = {
                line: _colour_pixels(area, colour)
                for line, colour in colours_of(frame["title"]).items()
            }
            if "set" in counts:  # its markers, or its translucent line under a bearing's
                counts["set"] += _colour_pixels(area, _on_white(SET_LINE_COLOUR, SET_LINE_ALPHA))
            if min(counts.values()) < 30:
                empty.append((frame["title"], counts))
        assert empty == [], f"charts without their lines: {empty}"

    _visit(chromium, tmp_path / "study.html", check, f"study-report-{study.name.split('.')[0]}.png")


#: Most pages a printed run report of a lesson result may take (A4): five on a 1300-px page
#: today; a break before every section made sixteen, most of them near empty.
MAX_PRINTED_PAGES = 7


def _pdf_pages(data: bytes) -> int:
    """Pages of a PDF written by Chromium (its page objects)."""
    return len(re.findall(rb"/Type\s*/Page\b", data))


def test_run_report_shows_a_pressure_scale_and_prints_in_few_pages(chromium, run_report):
    """On screen a colour scale in GPa sits with the 3-D view, spanning the scene's painted
    pressures, and the "..." stays hidden; printed (A4 PDF, kept as an artefact) the report takes
    few pages, the live view replaced by its still."""
    import solver

    ds = solver.load_dataset(LESSON)
    loaded = ds["max_pressure"].where(ds["contact_load"] > 0)
    largest = float(loaded.max()) * 1e-9  # GPa

    def check(page, console):  # noqa: ARG001 - the check's interface
        scale = page.locator(".rt-colour-scale")
        scale.wait_for(timeout=60_000)
        assert scale.count() == 1 and scale.is_visible()
        box = scale.bounding_box()
        assert box["width"] > 200 and box["height"] > 20
        lo = float(scale.get_attribute("data-lo-gpa"))
        hi = float(scale.get_attribute("data-hi-gpa"))
        assert 0.0 <= lo < hi and hi == pytest.approx(largest, rel=1e-3)
        text = scale.inner_text()
        assert "[GPa]" in text and f"{hi:.3g}" in text and f"{lo:.3g}" in text
        dots = page.locator(".vtk_info")
        assert all(not dots.nth(k).is_visible() for k in range(dots.count()))
        still = page.locator(".rt-still")
        assert still.count() == 1 and not still.is_visible()  # on paper only
        SHOTS.mkdir(parents=True, exist_ok=True)
        pdf = page.pdf(path=str(SHOTS / "run-report.pdf"), format="A4", print_background=True)
        pages = _pdf_pages(pdf)
        assert 2 <= pages <= MAX_PRINTED_PAGES, f"{pages} printed pages"
        page.emulate_media(media="print")
        assert still.is_visible() and not scale.is_visible()
        assert not page.locator("canvas").first.is_visible()  # the live view is not printed
        page.emulate_media(media="screen")

    _visit(chromium, run_report, check, "run-report-scale.png")
