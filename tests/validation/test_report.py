"""The validation report's plots: one PNG file per plot beside report.html, zoomable overlays
drawn from their data, and no overlapping tick labels (in the browser: test_report_browser)."""

import json
import re

import numpy as np
import pytest

from validation import report

pytest.importorskip("matplotlib")


def case(logx_span=(0.15, 6.0)):
    x = np.linspace(-1e-3, 1e-3, 41)
    p = np.clip(1 - (x / 8e-4) ** 2, 0, None) * 1e6
    s = np.geomspace(*logx_span, 5)
    return {
        "status": "passed",
        "profiles": [
            {
                "label": "s=0.3",
                "reference": "exact",
                "xlabel": "x (m)",
                "curves": {"exact": [x.tolist(), p.tolist()], "bem": [x.tolist(), (p * 1.01).tolist()]},
                "errors": {"bem": [x.tolist(), (p * 0.01).tolist()]},
            }
        ],
        "sweeps": [
            {
                "title": "friction against speed",
                "xlabel": "s",
                "ylabel": "friction",
                "logx": True,
                "logy": False,
                "curves": {"bem": [s.tolist(), (0.1 * s).tolist()]},
            }
        ],
        "runs": [{"solver": "bem", "label": "s=0.3", "seconds": 0.5, "peak_mib": 10.0, "detail": ""}],
    }


def test_declutter_removes_overlapping_tick_labels():
    """A log axis over 1.6 decades labels its minor ticks, which overlap (the reported case);
    declutter removes them, and the check sees it."""
    import matplotlib.pyplot as plt

    figures = report._figures(case())
    sweep = next(fig for _, fig, kind in figures if kind == "sweep")
    assert report.overlapping_ticks(sweep), "the check must see the overlap it guards against"
    report.declutter(sweep)
    assert report.overlapping_ticks(sweep) == []
    for _, fig, _ in figures:
        assert report.overlapping_ticks(report.declutter(fig)) == []
        plt.close(fig)


def test_every_plot_is_a_png_beside_the_report(tmp_path):
    record = {
        "quick": True,
        "seconds": 1.0,
        "environment": {"commit": "0" * 40, "date": "today", "machine": "m", "python": "3"},
        "summary": {"cases": 1, "passed": 1, "failed": [], "checks": 0, "failed_checks": []},
        "cases": {
            "demo": dict(
                case(), title="demo", description="d", solvers=["bem"], checks=[], files=[], notes=[], seconds=1.0
            )
        },
    }
    report.write_reports(record, tmp_path)
    pngs = sorted((tmp_path / "plots").glob("*.png"))
    assert [p.name[:8] for p in pngs] == ["demo_00_", "demo_01_", "demo_02_"]
    assert all(p.read_bytes().startswith(b"\x89PNG") for p in pngs)
    page = (tmp_path / "report.html").read_text()
    assert "data-plots='3'" in page and page.count("class='vb-zoom vb-plot'") == 1
    assert page.count("data:image/png;base64,") == 2  # the sweep and the timings
    for p in pngs:
        assert f"href='plots/{p.name}'" in page
    spec = json.loads(re.search(r"<script type='application/json'>(.*?)</script>", page).group(1))
    assert spec["panels"][0]["series"][0]["name"] == "exact" and max(spec["panels"][0]["series"][0]["y"]) == 1.0
    assert not re.search(r"(src|href)=['\"]https?:", page)  # nothing to fetch: it works offline
