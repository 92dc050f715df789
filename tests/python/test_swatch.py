"""skinspec.swatch: a swatch chart's colours as numpy arrays (python/swatch_binding.cpp), equal to `skinspec
swatch --json` for the same request, with the command's default sweeps and refusals."""
import os

import numpy as np
import pytest

import skinspec

INPUTS = os.path.join(os.path.dirname(__file__), "..", "inputs")


def test_swatch_equals_the_command(cli):
    ours = skinspec.swatch("biospec-lightly", ["epidermis.melanosome_fraction=0.02:0.2:3"], delta_e=2, seed=3)
    theirs = cli("swatch", "--preset", "biospec-lightly", "--vary", "epidermis.melanosome_fraction=0.02:0.2:3", "--delta-e", "2", "--seed", "3")
    assert ours["shape"] == (1, 3)
    np.testing.assert_allclose(ours["Lab"].reshape(-1, 3), [p["Lab"] for p in theirs["patches"]], rtol=0, atol=1e-12)
    assert ours["reflectance"].shape == (1, 3, len(ours["wavelength_nm"]))
    assert list(ours["category"]) == ["intermediate", "brown", "dark"]
    # More melanin, darker skin: L* falls along the row.
    assert np.all(np.diff(ours["Lab"][0, :, 0]) < 0)


def test_swatch_defaults_and_refusals():
    with pytest.raises(skinspec.InputError, match="seed: solver 'dipole' is deterministic"):
        skinspec.swatch("biospec-lightly", ["epidermis.melanosome_fraction=0.02:0.2:2"], solver="dipole", seed=1)
    with pytest.raises(skinspec.InputError, match="vary"):
        skinspec.swatch("biospec-lightly", ["epidermis.melanosome_fraction"])
    # Not a skin (no epidermis, no dermis): one patch, no default sweep, as the command.
    one = skinspec.swatch(os.path.join(INPUTS, "white_reflector.toml"), delta_e=1)
    assert one["shape"] == (1, 1) and one["fields"] == []
    with pytest.raises(skinspec.InputError, match="is given per band; a swatch needs reflectance spectra"):
        skinspec.swatch("jensen2001-skin1", solver="dipole")
