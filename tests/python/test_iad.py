"""skinspec.iad: inverse adding-doubling from Python (python/iad_binding.cpp), the document `skinspec iad --json`
prints, with the setup fields as keywords."""
import os

import pytest

import skinspec

INPUTS = os.path.join(os.path.dirname(__file__), "..", "inputs")
TWO_SPHERES = os.path.join(INPUTS, "iad_two_spheres.rxt")


def test_iad_equals_the_iad_command(cli):
    ours = skinspec.iad(TWO_SPHERES, r_uncertainty=0.002, t_uncertainty=0.002)
    theirs = cli("iad", TWO_SPHERES, "--r-uncertainty", "0.002", "--t-uncertainty", "0.002")
    assert [r["source"] for r in ours["rows"]] == [r["source"] for r in theirs["rows"]]
    for a, b in zip(ours["rows"], theirs["rows"]):
        for key in ("mu_a_per_mm", "mu_a_stderr_per_mm", "mu_s_reduced_per_mm", "m_r_fit"):
            assert a[key] == pytest.approx(b[key], abs=1e-12)
    # The phantom behind the file: mu_a 0.1, 0.2, 0.4 /mm, mu_s' 1 /mm.
    assert [r["mu_a_per_mm"] for r in ours["rows"]] == pytest.approx([0.1, 0.2, 0.4], rel=1e-4)


def test_iad_one_measurement_with_setup_keywords():
    # iad's README: M_R 0.4, M_T 0.1, 1 mm, index 1 -> mu_a 0.4671, mu_s' 3.9307 /mm.
    row = skinspec.iad(r=0.4, t=0.1, sample_thickness_mm=1.0)["rows"][0]
    assert row["mu_a_per_mm"] == pytest.approx(0.4671, abs=1e-4)
    assert row["mu_s_reduced_per_mm"] == pytest.approx(3.9307, abs=1e-4)
    assert row["mu_a_stderr_per_mm"] is None  # no measurement uncertainty given
    with pytest.raises(skinspec.InputError, match="'bogus' is not a setup field"):
        skinspec.iad(r=0.4, t=0.1, bogus=1.0)
    with pytest.raises(skinspec.InputError, match="sample_index = 0.5 is outside"):
        skinspec.iad(r=0.4, t=0.1, sample_index=0.5)


def test_iad_unreachable_is_refused_or_skipped():
    path = os.path.join(INPUTS, "iad_unreachable.rxt")
    with pytest.raises(skinspec.InputError, match="1 of 2 measurements are unreachable"):
        skinspec.iad(path)
    doc = skinspec.iad(path, skip_unreachable=True)
    assert len(doc["rows"]) == 1 and len(doc["unreachable"]) == 1


def test_iad_over_a_spectrum_from_arrays():
    # The phantom of iad_two_spheres.rxt given as arrays: the same rows as the file gives.
    import numpy as np
    nm = np.array([500.0, 550.0, 600.0])
    doc = skinspec.iad(r=np.array([0.253276, 0.196363, 0.141110]), t=np.array([0.515253, 0.425187, 0.315967]), wavelengths=nm,
                       sample_index=1.4, slide_index=1.5, slide_thickness_mm=1.0, spheres=2, r_standard=0.98)
    from_file = skinspec.iad(TWO_SPHERES)
    assert [r["wavelength_nm"] for r in doc["rows"]] == [500.0, 550.0, 600.0]
    for a, b in zip(doc["rows"], from_file["rows"]):
        assert a["mu_a_per_mm"] == pytest.approx(b["mu_a_per_mm"], abs=1e-12)
        assert a["mu_s_reduced_per_mm"] == pytest.approx(b["mu_s_reduced_per_mm"], abs=1e-12)
    with pytest.raises(skinspec.InputError, match="transmittance M_T: 2 values for 3 reflectances M_R"):
        skinspec.iad(r=[0.2, 0.2, 0.2], t=[0.4, 0.4])
