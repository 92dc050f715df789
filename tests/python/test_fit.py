"""skinspec.fit_spectrum: the fit of measured spectra from numpy (python/fit_binding.cpp), equal to `skinspec
fit-spectrum` on the same spectra, and recovering the melanin of spectra made by the model."""
import os

import numpy as np
import pytest

import skinspec

INPUTS = os.path.join(os.path.dirname(__file__), "..", "inputs")


def two_spectra():
    rows = [line.split(",") for line in open(os.path.join(INPUTS, "fit_two.csv")) if line[0].isdigit()]
    table = np.array([[float(v) for v in r] for r in rows])
    return table[:, 0], table[:, 1:].T


def test_fit_equals_the_fit_command(cli):
    nm, measured = two_spectra()
    ours = skinspec.fit_spectrum(nm, measured, rays=2000, seed=3, names=["light", "moderate"])
    theirs = cli("fit-spectrum", os.path.join(INPUTS, "fit_two.csv"), "--rays", "2000", "--seed", "3")["fits"]
    assert [f.name for f in ours] == [f["name"] for f in theirs]
    for a, b in zip(ours, theirs):
        assert a.parameters.keys() == b["parameters"].keys()
        for key in a.parameters:
            assert a.parameters[key] == pytest.approx(b["parameters"][key], abs=1e-12)
        assert a.rms == pytest.approx(b["rms"], abs=1e-12)
        np.testing.assert_allclose(a.fitted, b["fitted"], rtol=0, atol=1e-12)


def test_fit_recovers_the_melanin_of_model_spectra():
    # The two spectra were computed from biospec-lightly (melanosome fraction 0.019) and biospec-moderately (0.052).
    nm, measured = two_spectra()
    light, moderate = skinspec.fit_spectrum(nm, measured, rays=20000, free=["epidermis.melanosome_fraction"])
    assert light.parameters["epidermis.melanosome_fraction"] == pytest.approx(0.019, abs=0.003)
    assert moderate.parameters["epidermis.melanosome_fraction"] == pytest.approx(0.052, abs=0.005)
    assert light.rms < 0.01 and light.delta_e2000 < 2.0
    one = skinspec.fit_spectrum(nm, measured[0], rays=2000, free="epidermis.melanosome_fraction")
    assert isinstance(one, skinspec.Fit) and one.name == "measured"


def test_the_exact_model_fit_states_its_quadrature_accuracy(cli):
    # mode and channels as the command's --mode and --channels: the same fit, the same stated accuracy.
    nm, measured = two_spectra()
    free = ["epidermis.melanosome_fraction"]
    ours = skinspec.fit_spectrum(nm, measured[0], free=free, mode="biospec-adding-doubling", channels=8, starts=1)
    theirs = cli("fit-spectrum", os.path.join(INPUTS, "fit_two.csv"), "--spectra", "light", "--free", free[0],
                 "--mode", "biospec-adding-doubling", "--channels", "8", "--starts", "1")["fits"][0]
    assert ours.model_accuracy is not None and ours.model_accuracy > 0
    assert ours.model_accuracy == pytest.approx(theirs["model_accuracy"], abs=1e-12)
    assert ours.parameters[free[0]] == pytest.approx(theirs["parameters"][free[0]], abs=1e-12)
    assert skinspec.fit_spectrum(nm, measured[0], free=free, rays=500, starts=1).model_accuracy is None


@pytest.mark.parametrize("change, message", [
    (dict(measured=np.ones((2, 2, 16)) * 0.3), "expected shape"),
    (dict(measured=np.full(16, 1.6)), r"outside \[0, 1.5\]"),
    (dict(measured=np.r_[np.nan, np.full(15, 0.3)]), r"measured\[0\] = nan is not a finite number"),
    (dict(wavelengths=[400, 450, 500], measured=[0.2, 0.3, 0.4]), "at least 5"),
    (dict(free=["epidermis.melanin"]), "melanin"),
    (dict(bounds={"epidermis.thickness_cm": (0.001, 0.02)}), "not a free parameter"),
    (dict(bounds={"epidermis.melanosome_fraction": (0.2, 0.1)}), "lo < hi"),
    (dict(material="jensen2001-skin1"), "homogeneous"),
    (dict(names=["a", "b", "c"]), "3 given for 1 spectra"),
    (dict(mode="rte"), r"mode: 'rte' is not a fit mode \(allowed: biospec, biospec-adding-doubling, adding-doubling\)"),
    (dict(mode="biospec-adding-doubling"), "rays: mode 'biospec-adding-doubling'"),
    (dict(channels=48), "channels: the quadrature"),
    (dict(mode="biospec-adding-doubling", rays=None, channels=2), r"channels = 2 is outside \[4, 256\]"),
])
def test_bad_fit_input_raises(change, message):
    nm, measured = two_spectra()
    kwargs = dict(wavelengths=nm, measured=measured[0], rays=500)
    kwargs.update(change)
    with pytest.raises(skinspec.InputError, match=message):
        skinspec.fit_spectrum(**kwargs)
