"""skinspec.color and skinspec.delta_e2000: colorimetry of numpy spectra (python/color_binding.cpp), against
analytic values (the perfect reflector, a flat grey), the published CIEDE2000 pairs and the program's numbers."""
import os

import numpy as np
import pytest

import skinspec
from conftest import REFERENCE_DIR

NM = np.arange(380, 781, 5)


def test_perfect_reflector_is_white_in_every_space():
    c = skinspec.color(NM, np.ones_like(NM, dtype=float))
    assert c.XYZ[1] == pytest.approx(1.0, abs=1e-12)
    np.testing.assert_allclose(c.Lab, [100.0, 0.0, 0.0], atol=1e-9)
    for space in ("sRGB", "Linear Rec.709", "ACEScg"):
        np.testing.assert_allclose(c.rgb[space], [1.0, 1.0, 1.0], atol=1e-5)


def test_flat_grey_follows_the_cielab_and_srgb_formulas():
    c = skinspec.color(NM, np.full(NM.shape, 0.18))
    # CIE 015:2018 Eq. 8.1: L* = 116 (Y/Yn)^(1/3) - 16; IEC 61966-2-1: 1.055 * 0.18^(1/2.4) - 0.055.
    assert c.Lab[0] == pytest.approx(116 * 0.18 ** (1 / 3) - 16, abs=1e-9)
    np.testing.assert_allclose(c.rgb["sRGB"], 1.055 * 0.18 ** (1 / 2.4) - 0.055, atol=1e-5)


def test_stacks_of_spectra_keep_their_shape():
    spectra = np.linspace(0.1, 0.9, 24).reshape(2, 3, 4, 1) * np.ones(NM.shape)
    c = skinspec.color(NM, spectra, spaces=["ACEScg"])
    assert c.XYZ.shape == (2, 3, 4, 3) and c.xy.shape == (2, 3, 4, 2) and list(c.rgb) == ["ACEScg"]
    single = skinspec.color(NM, spectra[1, 2, 3])
    np.testing.assert_allclose(c.Lab[1, 2, 3], single.Lab, rtol=0, atol=1e-12)


def test_equals_the_color_command(cli):
    path = os.path.join(skinspec.data_directory(), "spectra", "example_reflectance.csv")
    rows = [line.split(",") for line in open(path) if line.strip() and not line.startswith("#")]
    rows = np.array([[float(v) for v in r] for r in rows if r[0].strip()[0].isdigit()])
    ours = skinspec.color(rows[:, 0], rows[:, 1], illuminant="D50", observer=10)
    theirs = cli("color", path, "--illuminant", "D50", "--observer", "10")
    np.testing.assert_allclose(ours.XYZ, theirs["XYZ"], rtol=0, atol=1e-12)
    np.testing.assert_allclose(ours.Lab, theirs["Lab"], rtol=0, atol=1e-12)
    np.testing.assert_allclose(ours.rgb["sRGB"], theirs["srgb"], atol=1e-6)


def test_uncertainties_match_the_spread_of_noisy_spectra_and_the_color_command(cli):
    # Brute force: the standard deviation of Lab and sRGB over many noisy copies of the spectrum (independent
    # errors plus one common to all wavelengths, as a stated solver error) within 10 % of the linear propagation.
    nm = np.arange(400, 701, 10)
    r = 0.1 + 0.3 / (1 + np.exp(-(nm - 580) / 25.0))
    se = np.full(nm.shape, 0.004)
    c = skinspec.color(nm, r, standard_errors=se, stated_error=0.003)
    rng = np.random.default_rng(3)
    noisy = r + se * rng.standard_normal((6000, nm.size)) + 0.003 * rng.standard_normal((6000, 1))
    spread = skinspec.color(nm, noisy)
    np.testing.assert_allclose(c.Lab_uncertainty, spread.Lab.std(axis=0), rtol=0.1)
    np.testing.assert_allclose(c.rgb_uncertainty["sRGB"], spread.rgb["sRGB"].std(axis=0), rtol=0.1)
    assert skinspec.color(nm, r).Lab_uncertainty is None
    # The command reads the same standard errors from a R_stderr column.
    theirs = cli("color", os.path.join(os.path.dirname(__file__), "..", "inputs", "spectrum_with_stderr.csv"))
    rows = np.loadtxt(os.path.join(os.path.dirname(__file__), "..", "inputs", "spectrum_with_stderr.csv"), delimiter=",", comments="#", skiprows=2)
    ours = skinspec.color(rows[:, 0], rows[:, 1], standard_errors=rows[:, 2])
    np.testing.assert_allclose(ours.Lab_uncertainty, theirs["Lab_uncertainty"], rtol=1e-9)
    assert ours.delta_e2000_uncertainty == pytest.approx(theirs["delta_e2000_uncertainty"], rel=1e-9)


def test_ciede2000_reproduces_sharma_wu_dalal_2005():
    rows = [line.split() for line in open(os.path.join(REFERENCE_DIR, "ciede2000_sharma2005.txt"))
            if line.strip() and not line.startswith("#") and not line.startswith("pair")]
    first = np.array([[float(v) for v in r[2:5]] for r in rows if r[1] == "1"])
    second = np.array([[float(v) for v in r[2:5]] for r in rows if r[1] == "2"])
    expected = np.array([float(r[-1]) for r in rows if r[1] == "1"])
    assert len(expected) == 34
    np.testing.assert_allclose(skinspec.delta_e2000(first, second), expected, atol=5e-5)
    assert skinspec.delta_e2000([50, 0, 0], first).shape == (34,)


@pytest.mark.parametrize("wavelengths, spectra, kwargs, message", [
    (NM, np.full(NM.shape, 1.2), {}, r"value 1.2 \(entry 0 in C order\) is outside \[0, 1\]"),
    (NM, np.full(NM.shape, -0.1), dict(allow_over_one=True), r"outside \[0, inf\)"),
    (NM, np.r_[np.nan, np.ones(len(NM) - 1)], {}, r"spectra\[0\] = nan is not a finite number"),
    (NM, np.ones(len(NM) - 1), {}, "one value per wavelength"),
    (np.arange(450, 701, 10), np.ones(26), {}, "must span 400-700 nm"),
    (NM, np.ones(NM.shape), dict(spaces="Rec.2020 nonsense"), "Rec.2020 nonsense"),
    (NM, np.ones(NM.shape), dict(illuminant="F2"), "'F2'"),
    (NM, np.ones(NM.shape), dict(observer=5), "'5'"),
])
def test_bad_colour_input_raises(wavelengths, spectra, kwargs, message):
    with pytest.raises(skinspec.InputError, match=message):
        skinspec.color(wavelengths, spectra, **kwargs)
    assert np.isfinite(skinspec.color(NM, np.full(NM.shape, 1.2), allow_over_one=True).XYZ).all()
