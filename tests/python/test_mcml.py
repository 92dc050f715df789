"""skinspec.mcml: an MCML .mci file's runs from Python (python/mcml_binding.cpp), equal to `skinspec mcml --json`
on the same file and seed, with MCML's grids as numpy arrays; energy is conserved."""
import os

import numpy as np
import pytest

import skinspec

SAMPLE = os.path.join(os.path.dirname(__file__), "..", "..", "data", "mcml", "sample.mci")


def test_mcml_equals_the_command(cli, tmp_path):
    ours = skinspec.mcml(SAMPLE, photons=3000, seed=4)
    theirs = cli("mcml", SAMPLE, "--photons", "3000", "--seed", "4", "--output-dir", str(tmp_path))["runs"]
    assert len(ours) == len(theirs)
    for a, b in zip(ours, theirs):
        for key in ("R", "R_stderr", "T", "A", "photons"):
            assert a[key] == b[key]
        np.testing.assert_array_equal(a["A_rz_per_cm3"].ravel(), b["A_rz_per_cm3"])
        assert a["A_rz_per_cm3"].shape == (b["input"]["nr"], b["input"]["nz"])
        # R + T + A = 1 to rounding (energy conservation).
        assert a["R"] + a["T"] + a["A"] == pytest.approx(1.0, abs=1e-12)


def test_mcml_adding_doubling_and_refusals():
    (run, *_) = skinspec.mcml(SAMPLE, solver="adding-doubling")
    assert run["model"] == "adding-doubling" and run["R_stderr"] == 0.0
    assert run["R"] + run["T"] + run["A"] == pytest.approx(1.0, abs=1e-9)
    with pytest.raises(skinspec.InputError, match="solver adding-doubling is deterministic: it takes no photons"):
        skinspec.mcml(SAMPLE, solver="adding-doubling", photons=100)
    with pytest.raises(skinspec.InputError, match="solver adding-doubling is deterministic: it takes no seed"):
        skinspec.mcml(SAMPLE, solver="adding-doubling", seed=99)
    with pytest.raises(skinspec.InputError, match="solver: 'mc' is not allowed"):
        skinspec.mcml(SAMPLE, solver="mc")
    with pytest.raises(skinspec.InputError, match="no_such.mci: .mci file not found"):
        skinspec.mcml("no_such.mci")
