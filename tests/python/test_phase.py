"""skinspec.compare_phase: measured versus HG thin layers from Python (python/phase_binding.cpp), equal to
`skinspec compare-phase` on the same request, with the same refusals."""
import numpy as np
import pytest

import skinspec


def test_compare_phase_equals_the_command(cli):
    ours = skinspec.compare_phase("biospec-lightly", [400, 500, 600, 700], stderr=0.01, seed=2)
    theirs = cli("compare-phase", "--preset", "biospec-lightly", "--wavelengths", "400,500,600,700", "--stderr", "0.01", "--seed", "2")
    assert [c.quantity for c in ours] == [c["quantity"] for c in theirs["comparisons"]] == ["R", "T"]
    assert ours[0].hg_source == theirs["hg_source"]
    for a, b in zip(ours, theirs["comparisons"]):
        np.testing.assert_array_equal(a.wavelength_nm, [r["wavelength_nm"] for r in b["rows"]])
        np.testing.assert_allclose(a.difference, [r["difference"] for r in b["rows"]], rtol=0, atol=1e-15)
        np.testing.assert_allclose(a.difference_stderr, [r["difference_stderr"] for r in b["rows"]], rtol=0, atol=1e-15)
        assert list(a.significant) == [r["significant"] for r in b["rows"]]
    assert ours[0].delta_e2000 == pytest.approx(theirs["comparisons"][0]["delta_e00"], abs=1e-12)
    assert ours[1].delta_e2000 is None
    # The difference is HG - measured, its standard error the two combined (independent runs).
    np.testing.assert_allclose(ours[0].difference, ours[0].hg - ours[0].measured, rtol=0, atol=1e-15)
    np.testing.assert_allclose(ours[0].difference_stderr, np.hypot(ours[0].hg_stderr, ours[0].measured_stderr), rtol=1e-12)


def test_compare_phase_refuses_what_the_command_refuses():
    with pytest.raises(skinspec.InputError, match=r"hg_source '1.5' is not allowed \(allowed: rms, van-gemert, or a number in \[-1, 1\]\)"):
        skinspec.compare_phase("biospec-lightly", [550], hg_source="1.5")
    with pytest.raises(skinspec.InputError, match="is homogeneous; compare-phase needs a layered material"):
        skinspec.compare_phase("jensen2001-skin1", [550])
    with pytest.raises(skinspec.InputError, match="stderr"):
        skinspec.compare_phase("biospec-lightly", [550], stderr=0.0)


def test_phase_study_equals_the_command(cli):
    ours = skinspec.phase_study(seed=2)
    theirs = cli("phase-study", "--seed", "2")
    np.testing.assert_array_equal(ours["bin_edges_deg"], theirs["bin_edges_deg"])
    assert [(c["tissue"], c["wavelength_nm"]) for c in ours["cases"]] == [(c["tissue"], c["wavelength_nm"]) for c in theirs["cases"]]
    for a, b in zip(ours["cases"], theirs["cases"]):
        assert a["g_rms"] == b["g_rms"]
        for approach in ("table_lookup", "hg_rms", "hg_van_gemert"):
            assert isinstance(a["approaches"][approach]["btdf_per_sr"], np.ndarray)
            np.testing.assert_array_equal(a["approaches"][approach]["btdf_per_sr"], b["approaches"][approach]["btdf_per_sr"])
