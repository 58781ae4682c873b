"""report.html in a real browser: headless Chromium opens the file offline, every plot renders,
the zoomable overlays zoom and reset, no tick labels overlap, and the console shows no error.

Marked ``browser`` (``pytest -m browser``, its own CI step): it needs the ``browser`` extra
(selenium) and Debian's ``chromium`` and ``chromium-driver``. It checks the report named by
``VISCOBEM_REPORT`` (CI: the quick validation's), else makes a small one, and saves screenshots
into ``VISCOBEM_SCREENSHOTS`` (else the test's temporary folder).
"""

import os
import shutil
from pathlib import Path

import pytest

from viscobem_cli.main import main

pytestmark = pytest.mark.browser
FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--window-size=1280,1400",
]
# every text label of one axis of every zoomable plot, with its box: overlapping neighbours
OVERLAPS = """
const out = [];
for (const svg of document.querySelectorAll('figure.vb-zoom svg')) {
  for (const cls of ['vb-x', 'vb-y']) {
    const boxes = [...svg.querySelectorAll('text.' + cls)].map(t => [t.textContent, t.getBBox()]);
    for (let i = 0; i < boxes.length; i++) for (let j = i + 1; j < boxes.length; j++) {
      const [a, p] = boxes[i], [b, q] = boxes[j];
      if (p.x < q.x + q.width && q.x < p.x + p.width && p.y < q.y + q.height && q.y < p.y + p.height)
        out.push([svg.closest('figure').id, a, b]);
    }
  }
}
return out;
"""
RENDERED = """
const figs = [...document.querySelectorAll('.vb-plot')];
const bad = [];
for (const f of figs) {
  const img = f.querySelector('img');
  if (img) { if (!(img.complete && img.naturalWidth > 100)) bad.push(img.alt); continue; }
  const paths = [...f.querySelectorAll('svg path')].filter(p => (p.getAttribute('d') || '').length > 10);
  if (f.dataset.rendered !== '1' || paths.length === 0) bad.push(f.id);
}
return [figs.length, Number(document.body.dataset.plots), bad];
"""


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    given = os.environ.get("VISCOBEM_REPORT")
    if given:
        return Path(given).resolve()
    out = tmp_path_factory.mktemp("report")
    argv = ["validate", "--quick", "--no-progress", "--no-vtk", "--no-baseline", "--out", str(out)]
    for case in ("westergaard", "full_contact_rough", "elastic_rough_dense"):
        argv += ["--case", case]
    assert main(argv) == 0
    return out / "report.html"


@pytest.fixture(scope="module")
def browser(tmp_path_factory):
    webdriver = pytest.importorskip("selenium.webdriver", reason="the browser extra (selenium)")
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    driver_path = shutil.which("chromedriver")
    if not (chromium and driver_path):
        pytest.skip("Chromium and chromedriver are not installed (apt-get install chromium chromium-driver)")
    options = webdriver.ChromeOptions()
    options.binary_location = chromium
    for flag in FLAGS + [f"--user-data-dir={tmp_path_factory.mktemp('chromium-profile')}"]:
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(service=webdriver.ChromeService(executable_path=driver_path), options=options)
    yield driver
    driver.quit()


@pytest.fixture(scope="module")
def page(browser, report):
    from selenium.webdriver.support.ui import WebDriverWait

    browser.get(report.as_uri())
    WebDriverWait(browser, 60).until(lambda d: d.execute_script("return document.body.dataset.zoomReady"))
    return browser


def shots(tmp_path):
    folder = Path(os.environ.get("VISCOBEM_SCREENSHOTS") or tmp_path)
    folder.mkdir(parents=True, exist_ok=True)
    return folder


def test_report_is_self_contained(report):
    text = report.read_text(encoding="utf-8")
    for attribute in ("src='http", 'src="http', "href='http", 'href="http', "@import", "url(http"):
        assert attribute not in text, f"report.html loads {attribute}...: it must work offline"


def test_every_plot_renders(page, tmp_path):
    found, promised, bad = page.execute_script(RENDERED)
    assert found == promised and found > 0, f"{found} plots on the page, the report made {promised}"
    assert not bad, f"plots that did not render: {bad}"
    assert int(page.execute_script("return document.body.dataset.zoomReady")) >= 1
    page.save_screenshot(str(shots(tmp_path) / "report.png"))


def test_no_tick_labels_overlap(page):
    assert page.execute_script(OVERLAPS) == []


def test_an_overlay_zooms_and_resets(page, tmp_path):
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By

    figure = page.find_element(By.CSS_SELECTOR, "figure.vb-zoom")
    page.execute_script("arguments[0].scrollIntoView()", figure)
    svg = figure.find_element(By.TAG_NAME, "svg")
    full = [float(v) for v in figure.get_attribute("data-x-range").split()]
    width = svg.size["width"]
    ActionChains(page).move_to_element_with_offset(svg, int(-0.1 * width), 0).click_and_hold().move_by_offset(
        int(0.2 * width), 0
    ).release().perform()
    zoomed = [float(v) for v in figure.get_attribute("data-x-range").split()]
    assert full[0] < zoomed[0] < zoomed[1] < full[1], (full, zoomed)
    assert (zoomed[1] - zoomed[0]) < 0.4 * (full[1] - full[0])
    assert page.execute_script(OVERLAPS) == []  # the zoomed axes too
    figure.screenshot(str(shots(tmp_path) / "overlay_zoomed.png"))
    ActionChains(page).double_click(svg).perform()
    assert [float(v) for v in figure.get_attribute("data-x-range").split()] == full


def test_console_shows_no_error(page):
    entries = page.get_log("browser")
    errors = [e for e in entries if e["level"] in ("SEVERE", "ERROR")]
    assert not errors, errors


# the first screen: every case's row of the summary, whole, above the first plot
FIRST_SCREEN = """
window.scrollTo(0, 0);
const rows = [...document.querySelectorAll('#summary tr.case')];
const height = window.innerHeight;
const plot = document.querySelector('.vb-plot');
return {
  cases: Number(document.body.dataset.cases),
  rows: rows.map(r => [r.cells[0].innerText.split('\\n')[0], r.cells[2].innerText, r.cells[5].innerText,
                       r.getBoundingClientRect().bottom <= height]),
  basis: (document.getElementById('basis') || {}).innerText || '',
  tableBottom: rows.length ? rows[rows.length - 1].getBoundingClientRect().bottom : null,
  plotTop: plot ? plot.getBoundingClientRect().top : null,
};
"""


def test_the_first_screen_answers(page, report, tmp_path):
    """A person opening the report sees, without scrolling, one row per case with its status and
    its worst check as value / tolerance, and how the tolerances were set; the plots come after."""
    import json

    screen = page.execute_script(FIRST_SCREEN)
    record = json.loads(report.with_name("report.json").read_text())
    assert screen["cases"] == len(record["cases"]) == len(screen["rows"])
    for (name, status, ratio, visible), (case, c) in zip(screen["rows"], record["cases"].items()):
        assert name == case and visible, f"{case}: its row is not on the first screen"
        assert status == {"passed": "PASS", "failed": "FAIL", "error": "ERROR"}[c["status"]]
        assert " / " in ratio or c["status"] == "error", ratio
    assert "regression margin" in screen["basis"] and "judged checks" in screen["basis"]
    assert screen["plotTop"] is None or screen["plotTop"] > screen["tableBottom"]
    page.save_screenshot(str(shots(tmp_path) / "first_screen.png"))
