"""``viscobem bench fem_profile``: a row is the FEM's result against the converged BEM with its cost,
and its errors are the FEM's (measured on the 4-term rubber a decade above its friction peak, 64
squares a period: moment form -7.7e-4, dissipation form +1.7e-4, contact fraction +0.98 %)."""

import pytest

from viscobem_bench.fem_profile import profile_case


def test_a_row_holds_the_fem_against_the_bem_with_its_cost():
    row = profile_case("4-term", 0.3, 64)
    assert row["success"] and not row["warned"]
    assert row["unknowns"] > 0 and row["meshes"] >= 1 and row["wall_s"] > 0 and row["peak_gib"] > 0
    # the bounds, 2 % and 3 % (margins 26x, 120x and 3x), and the estimates cover the errors
    assert abs(row["moment_error"]) <= 0.02 and abs(row["dissipation_error"]) <= 0.02
    assert abs(row["contact_error"]) <= 0.03
    assert abs(row["moment_error"]) <= row["moment_estimate"]
    assert abs(row["dissipation_error"]) <= row["dissipation_estimate"]
    assert row["contact"] == pytest.approx(0.0606, abs=5e-4)  # the BEM's, 4096 points
