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
    # Each patch's category is its ITA's (Chardon, Cretois & Hourseau 1991: ITA = atan((L* - 50) / b*); above 55 very
    # light, 41 light, 28 intermediate, 10 tan, -30 brown, else dark).
    L, b = ours["Lab"][0, :, 0], ours["Lab"][0, :, 2]
    ita = np.degrees(np.arctan((L - 50.0) / b))
    limits = ((55, "very light"), (41, "light"), (28, "intermediate"), (10, "tan"), (-30, "brown"), (-np.inf, "dark"))
    assert list(ours["category"]) == [next(name for limit, name in limits if a > limit) for a in ita]
    # More melanin, darker skin: L* falls along the row.
    assert np.all(np.diff(ours["Lab"][0, :, 0]) < 0)


def test_swatch_defaults_and_refusals():
    with pytest.raises(skinspec.InputError, match="seed: solver 'dipole' is deterministic"):
        skinspec.swatch("biospec-lightly", ["epidermis.melanosome_fraction=0.02:0.2:2"], mode="dipole", seed=1)
    with pytest.raises(skinspec.InputError, match="vary"):
        skinspec.swatch("biospec-lightly", ["epidermis.melanosome_fraction"])
    # A dict iterated its keys, its values dropped; skinspec.spectrum's form is refused here with a message.
    with pytest.raises(skinspec.InputError, match="vary: expected a string or a list of strings, not a dict"):
        skinspec.swatch("biospec-lightly", {"epidermis.melanosome_fraction": [0.01, 0.2]})
    # Not a skin (no epidermis, no dermis): one patch, no default sweep, as the command.
    one = skinspec.swatch(os.path.join(INPUTS, "white_reflector.toml"), delta_e=1)
    assert one["shape"] == (1, 1) and one["fields"] == []
    with pytest.raises(skinspec.InputError, match="is given per band; a swatch needs reflectance spectra"):
        skinspec.swatch("jensen2001-skin1", mode="dipole")


def test_lit_swatch_conserves_energy_and_writes_its_files(tmp_path):
    lit = skinspec.lit_swatch("biospec-moderately", "edge", pixels=64, field_mm=30, mode="matched-multipole",
                              output=[tmp_path / "edge.exr", tmp_path / "edge.png"])
    assert lit["rgb"].shape == (64, 64, 3) and lit["exitance"].shape == (31, 64, 64) and lit["model"] == "matched-multipole"
    assert lit["files"] == [str(tmp_path / "edge.exr"), str(tmp_path / "edge.png")] and all(os.path.getsize(f) > 0 for f in lit["files"])
    # Its profiles' shape against the walk, as `swatch --lit` states it (docs/DIFFUSION.md).
    assert [w["wavelength_nm"] for w in lit["shape"]["wavelengths"]] == [450.0, 550.0, 650.0]
    # Far into the lit half, a uniformly lit half-space returns the whole diffuse reflectance (R without the
    # first-surface reflection: the lit swatch has no specular); 13 mm into the shadow, almost nothing (the red, which
    # the dermis scatters least, reaches furthest: 5e-5 of the lit half at 700 nm).
    plane = skinspec.spectrum("biospec-moderately", mode="matched-multipole")
    np.testing.assert_allclose(lit["exitance"][:, 32, -3], plane.R - plane.R_specular, rtol=1e-4)
    assert np.all(lit["exitance"][:, 32, 2] < 1e-4 * lit["exitance"][:, 32, -3])
    # A pattern sets the view's aspect: 16 x 32 pixels of irradiance -> 32 x 64.
    pattern = skinspec.lit_swatch("biospec-moderately", "pattern", pattern=np.ones((16, 32)), pixels=64, mode="dipole")
    assert pattern["rgb"].shape == (32, 64, 3) and pattern["files"] == []
    with pytest.raises(skinspec.InputError, match="exists already"):
        skinspec.lit_swatch("biospec-moderately", "edge", pixels=64, output=tmp_path / "edge.exr")
    with pytest.raises(skinspec.InputError, match="'flash' is not a lighting"):
        skinspec.lit_swatch("biospec-moderately", "flash")
    with pytest.raises(skinspec.InputError, match="pattern: give it with lighting"):
        skinspec.lit_swatch("biospec-moderately", "spot", pattern=np.ones((4, 4)))
    with pytest.raises(skinspec.InputError, match="--field 0 mm is outside"):
        skinspec.lit_swatch("biospec-moderately", field_mm=0)



def test_lit_swatch_defaults_to_the_exact_transport():
    # Far into the lit half the exitance is the walk's whole-plane diffuse reflectance, which adding-doubling of the same
    # (derived) description gives independently: within 4 of the walk's standard errors plus the kernel's reach.
    lit = skinspec.lit_swatch("biospec-moderately", "edge", pixels=64, field_mm=30, wavelengths=[450, 550, 650], seed=3)
    assert lit["model"] == "rte" and lit["shape"] is None and "target 0.002" in lit["precision"]
    exact = skinspec.spectrum("biospec-moderately", [450, 550, 650], mode="adding-doubling")
    np.testing.assert_allclose(lit["exitance"][:, 32, -3], exact.R - exact.R_specular, atol=4 * 0.002 + 0.005)
    with pytest.raises(skinspec.InputError, match="stderr: solver 'dipole' is deterministic"):
        skinspec.lit_swatch("biospec-moderately", "edge", pixels=64, mode="dipole", stderr=0.01)

def test_swatch_writes_the_chart_files(tmp_path):
    charts = [tmp_path / "chart.png", tmp_path / "chart.exr"]
    ours = skinspec.swatch("biospec-lightly", ["epidermis.melanosome_fraction=0.02:0.2:3"], delta_e=2, seed=3, output=charts)
    assert ours["files"] == [str(f) for f in charts] and all(os.path.getsize(f) > 0 for f in charts)
    with pytest.raises(skinspec.InputError, match="exists already"):
        skinspec.swatch("biospec-lightly", ["epidermis.melanosome_fraction=0.02:0.2:3"], output=charts[0])
    with pytest.raises(skinspec.InputError, match="--patch-size 8 is outside"):
        skinspec.swatch("biospec-lightly", ["epidermis.melanosome_fraction=0.02:0.2:3"], output=tmp_path / "small.png", patch_size=8)
    assert not os.path.exists(tmp_path / "small.png")


def test_swatch_takes_the_solver_switches():
    # Honoured, not ignored: the switch reaches the solver, which checks it (and refuses a switch it does not take).
    with pytest.raises(skinspec.InputError, match=r"channels = 2 is outside \[4, 256\]"):
        skinspec.swatch(vary="epidermis.melanosome_fraction=0.05:0.05:1", mode="biospec-adding-doubling", channels=2)
    with pytest.raises(skinspec.InputError, match="does not take the switch 'channels'"):
        skinspec.swatch(vary="epidermis.melanosome_fraction=0.05:0.05:1", mode="dipole", channels=8)
    coarse = skinspec.swatch(vary="epidermis.melanosome_fraction=0.05:0.05:1", mode="biospec-adding-doubling", geometry="sce", channels=8)
    fine = skinspec.swatch(vary="epidermis.melanosome_fraction=0.05:0.05:1", mode="biospec-adding-doubling", geometry="sce", channels=32)
    assert coarse["delta_e2000_uncertainty"][0, 0] > fine["delta_e2000_uncertainty"][0, 0]
