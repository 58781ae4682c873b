"""The benchmark suite's own logic (no solves): Pareto front, exponent fit, README update."""
import numpy as np
import pytest

from benchmarks import suite


def test_pareto_front_keeps_only_undominated_points():
    pts = [{"time": 1.0, "error": 1e-2}, {"time": 2.0, "error": 1e-3}, {"time": 3.0, "error": 5e-3},
           {"time": 0.5, "error": 5e-2}, {"time": 4.0, "error": None}, {"time": 5.0, "error": 1e-4}]
    assert suite.pareto_front(pts) == [3, 0, 1, 5]  # sorted by time; 2 is dominated by 1


def test_fit_exponent_recovers_n_log_n():
    n = np.array([64, 128, 256, 512, 1024])
    N = n.astype(float) ** 2
    k, k_nlogn = suite._fit_exponent(n, 3e-8 * N * np.log(N))
    assert k_nlogn == pytest.approx(0.0, abs=1e-12)  # exact N log N data
    assert 1.0 < k < 1.15  # log N adds ~0.1 to the apparent power over this range
    assert suite._fit_exponent(n, 1e-9 * N**1.5)[0] == pytest.approx(1.5, abs=1e-12)


def test_readme_table_replaced_between_markers_only(tmp_path):
    path = tmp_path / "README.md"
    head = "# viscobem\n\nfirst lines stay\n"
    path.write_text(head + f"\n{suite.README_BEGIN}\nold table\n{suite.README_END}\n\ntail\n")
    suite.update_readme(path, "| new | table |")
    text = path.read_text()
    assert text.startswith(head) and text.endswith("\n\ntail\n")
    assert "old table" not in text and f"{suite.README_BEGIN}\n| new | table |\n{suite.README_END}" in text
    suite.update_readme(path, "| newer |")  # idempotent structure: one block
    assert path.read_text().count(suite.README_BEGIN) == 1 and "| new | table |" not in path.read_text()


def test_rough_heights_are_one_surface_at_every_size():
    h64, h128 = suite.rough_heights(64), suite.rough_heights(128)
    assert np.allclose(h128[::2, ::2], h64, rtol=0, atol=1e-12 * np.abs(h64).max())  # exact resampling


def test_registry_entries_are_complete():
    assert {"periodic-westergaard", "periodic-rough-viscoelastic", "fem-hunter"} <= set(suite.REGISTRY)
    for entry in suite.REGISTRY.values():
        assert entry.knobs and callable(entry.measure)
        assert list(entry.groups(True))  # a quick run has work in every entry
