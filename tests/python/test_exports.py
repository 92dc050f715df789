"""skinspec.export_pbrt / export_mitsuba / export_profile / export_lut (python/export_binding.cpp): the files the
`skinspec export ...` commands write, written by the same library calls, equal to the command's files, with the
command's refusals; and the physics the exports must keep (the fit's total R, a scene that reads back)."""
import json
import os
import subprocess

import numpy as np
import pytest

import skinspec

PROGRAM = os.environ.get("SKINSPEC_PROGRAM", "skinspec")


def run(*args):
    done = subprocess.run([PROGRAM, *args], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stdout


def spd_files(folder):
    return {name: open(os.path.join(folder, name)).read() for name in sorted(os.listdir(folder))}


def test_export_pbrt_equals_the_command(tmp_path):
    ours = skinspec.export_pbrt("biospec-lightly", tmp_path / "py.pbrt", wavelengths=[450, 550, 650])
    theirs = json.loads(run("export", "pbrt", "--preset", "biospec-lightly", "--wavelengths", "450,550,650", "-o", str(tmp_path / "cli.pbrt"), "--json"))
    assert ours["renderer"] == "pbrt-v4" and len(ours["files"]) == 1 + 2 * 4
    for a, b in zip(ours["layers"], theirs["layers"]):
        assert a["name"] == b["name"] and a["phase"] == b["phase"] == "henyey-greenstein"
        np.testing.assert_array_equal(a["sigma_a_per_mm"], b["sigma_a_per_mm"])
        np.testing.assert_array_equal(a["sigma_s_per_mm"], b["sigma_s_per_mm"])
    assert spd_files(tmp_path / "py_spectra") == spd_files(tmp_path / "cli_spectra")
    # Written, then read back through the renderer's syntax: the same coefficients to rounding.
    assert ours["read_back_largest_relative_difference"] <= 1e-12
    # Each layer's thickness in mm is the material's in cm x 10.
    skin = skinspec.Material("biospec-lightly")
    assert ours["layers"][1]["thickness_mm"] == pytest.approx(10 * skin["epidermis.thickness_cm"], rel=1e-12)


def test_export_mitsuba_rgb_and_refusals(tmp_path):
    d = skinspec.export_mitsuba("biospec-lightly", tmp_path / "s.xml", rgb=[650, 550, 450])
    assert d["rgb"] and d["files"] == [str(tmp_path / "s.xml")]
    # Mitsuba takes each layer's own phase: the measured (Bruls & van der Leun) layers as tabulated.
    assert "tabulated" in [layer["phase"] for layer in d["layers"]]
    assert all(layer["sigma_a_per_mm"].shape == (3,) for layer in d["layers"])
    with pytest.raises(skinspec.InputError, match="exists already"):
        skinspec.export_mitsuba("biospec-lightly", tmp_path / "s.xml", rgb=[650, 550, 450])
    with pytest.raises(skinspec.InputError, match="give exactly three wavelengths"):
        skinspec.export_mitsuba("biospec-lightly", tmp_path / "t.xml", rgb=[650, 550])
    with pytest.raises(skinspec.InputError, match="is given per band"):
        skinspec.export_mitsuba("jensen2001-skin1", tmp_path / "u.xml")
    with pytest.raises(skinspec.InputError, match="extension '.pbrt' is not supported"):
        skinspec.export_mitsuba("biospec-lightly", tmp_path / "u.pbrt")
    assert not os.path.exists(tmp_path / "t.xml") and not os.path.exists(tmp_path / "u.xml")


def test_export_profile_equals_the_command_and_keeps_total_reflectance(tmp_path):
    ours = skinspec.export_profile("biospec-moderately", output=tmp_path / "py.json", table=tmp_path / "py.csv")
    run("export", "profile", "--preset", "biospec-moderately", "-o", str(tmp_path / "cli.json"), "--table", str(tmp_path / "cli.csv"))
    assert json.load(open(tmp_path / "py.json")) == json.load(open(tmp_path / "cli.json"))
    assert open(tmp_path / "py.csv").read() == open(tmp_path / "cli.csv").read()
    assert [c["name"] for c in ours["fit"]] == ["R", "G", "B"] and ours["variances_mm2"].shape == (6,)
    # Each Gaussian integrates to 1 over the plane: the weights sum to the model's total diffuse R (held by the fit).
    for c in ours["fit"]:
        assert np.sum(c["weights"]) == pytest.approx(c["total_reflectance_model"], rel=2e-3)
    per_band = skinspec.export_profile("jensen2001-skin1", gaussians=4)
    assert per_band["channels"] == "bands" and per_band["variances_mm2"].shape == (4,)
    with pytest.raises(skinspec.InputError, match="is given per band; it has no wavelengths"):
        skinspec.export_profile("jensen2001-skin1", per="wavelength")
    with pytest.raises(skinspec.InputError, match="--gaussians 13 is outside"):
        skinspec.export_profile("biospec-lightly", gaussians=13)


def test_export_profile_of_a_grid_equals_the_command(tmp_path):
    own = "model.volumetric_matched_to_biospec=false"
    material = skinspec.Material("biospec-moderately")
    material["model.volumetric_matched_to_biospec"] = False
    args = dict(per="wavelength", wavelengths=[550], radii_mm=np.arange(0, 101) * 0.05, gaussians=3, rays=5000)
    ours = skinspec.export_profile(material, output=tmp_path / "py.json", table=tmp_path / "py.csv",
                                   vary={"epidermis.melanosome_fraction": [0.01, 0.2], "papillary_dermis.blood_fraction": [0.002, 0.05]}, **args)
    run("export", "profile", "--set", own, "--vary", "epidermis.melanosome_fraction=0.01:0.2:2", "--vary", "papillary_dermis.blood_fraction=0.002:0.05:2",
        "--per", "wavelength", "--wavelengths", "550", "--radii", "0:5:0.05", "--gaussians", "3", "--rays", "5000",
        "-o", str(tmp_path / "cli.json"), "--table", str(tmp_path / "cli.csv"))
    assert json.load(open(tmp_path / "py.json")) == json.load(open(tmp_path / "cli.json"))
    assert open(tmp_path / "py.csv").read() == open(tmp_path / "cli.csv").read()
    assert len(ours["members"]) == 4 and "shared by the 4 members" in ours["precision"]
    # More melanin, less light back: the fit's total follows the member.
    totals = [m["fit"][0]["total_reflectance_fit"] for m in ours["members"]]
    assert totals[0] > totals[1] and totals[2] > totals[3]
    with pytest.raises(skinspec.InputError, match="vary: expected a dict"):
        skinspec.export_profile(material, vary=["epidermis.melanosome_fraction"], **args)


def test_export_mcml_equals_the_command(tmp_path):
    ours = skinspec.export_mcml("biospec-moderately", tmp_path / "py.mci", photons=1000)
    run("export", "mcml", "--preset", "biospec-moderately", "--photons", "1000", "-o", str(tmp_path / "cli.mci"))
    # The same file but for the output names each run writes (STEM_NNNnm.mco), which follow the file's own name.
    assert open(tmp_path / "py.mci").read().replace("py_", "cli_") == open(tmp_path / "cli.mci").read()
    assert ours["wavelengths_nm"] == [450.0, 550.0, 650.0] and ours["photons"] == 1000
    assert any("HG of its mean cosine" in s for s in ours["substitutions"])
    # What leaving the reflector out changes, by adding-doubling: the red, which reaches the reflector, loses the most.
    change = [e - o for e, o in zip(ours["exported_reflectance"], ours["own_reflectance"])]
    assert change[2] < change[0] and change[2] < 0
    with pytest.raises(skinspec.InputError, match="exists already"):
        skinspec.export_mcml("biospec-moderately", tmp_path / "py.mci")
    with pytest.raises(skinspec.InputError, match="given per band"):
        skinspec.export_mcml("jensen2001-skin1", tmp_path / "bands.mci")


def test_export_lut_equals_the_command(tmp_path):
    axes = dict(melanin="0.01:0.42:3:log", blood="0.002:0.05:2:log")
    ours = skinspec.export_lut("biospec-moderately", tmp_path / "py.exr", mode="adding-doubling", spectra=tmp_path / "py.csv", **axes)
    run("export", "lut", "--melanin", axes["melanin"], "--blood", axes["blood"], "--mode", "adding-doubling", "-o", str(tmp_path / "cli.exr"),
        "--spectra", str(tmp_path / "cli.csv"))
    assert open(tmp_path / "py.csv").read() == open(tmp_path / "cli.csv").read()
    assert ours["files"] == [str(tmp_path / "py.exr"), str(tmp_path / "py.csv")] and os.path.getsize(tmp_path / "py.exr") > 0
    assert ours["shape"] == (2, 3) and ours["rgb"].shape == (2, 3, 3) and not ours["partial"]
    # Columns: melanin rises, the skin darkens.
    assert np.all(np.diff(ours["Lab"][:, :, 0], axis=1) < 0)
    # The worst texel's colour uncertainty is the largest in the spectra file, every one finite (adding-doubling's
    # stated error on the derived description grows with melanin: ~2 CIEDE2000 at 0.42 in SCE, where L* is steep).
    rows = [line.split(",") for line in open(tmp_path / "py.csv").read().splitlines() if not line.startswith("#")]
    header, rows = rows[0], rows[1:]
    uncertainties = np.array([[float(r[header.index(k)]) for k in ("delta_e_uncertainty", "L_uncertainty", "a_uncertainty", "b_uncertainty")] for r in rows])
    assert np.all(np.isfinite(uncertainties)) and np.all(uncertainties >= 0)
    assert ours["worst_delta_e_uncertainty"] == pytest.approx(uncertainties[:, 0].max(), rel=1e-3)
    with pytest.raises(skinspec.InputError, match="exists already"):
        skinspec.export_lut("biospec-moderately", tmp_path / "py.exr", **axes)
    with pytest.raises(skinspec.InputError, match="preview.txt: extension"):
        skinspec.export_lut("biospec-moderately", tmp_path / "new.exr", preview=tmp_path / "preview.txt", **axes)
    assert not os.path.exists(tmp_path / "new.exr")
