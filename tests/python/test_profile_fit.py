"""skinspec.fit_profile, fit_profile_image, fit_profile_patches: the dipole fits of a radial profile, an image pair
and a patch list from numpy or the command's files (python/profile_fit_binding.cpp), equal to `skinspec fit-profile`
on the same input, recovering the parameters of a scene made here with Jensen et al.'s dipole, with the same
refusals."""
import os
import subprocess

import numpy as np
import pytest

import skinspec


def test_fit_profile_equals_the_command(cli, tmp_path):
    csv = tmp_path / "marble.csv"
    subprocess.run([os.environ["SKINSPEC_PROGRAM"], "profile", "--preset", "jensen2001-marble", "--mode", "dipole", "--radii", "0.1:8:0.1",
                    "--output", str(csv)], check=True, capture_output=True)
    lines = [l for l in open(csv) if not l.startswith("#")]
    column = lines[0].strip().split(",")[1]
    table = np.array([[float(v) for v in l.split(",")] for l in lines[1:]])
    # The file's R is per incident power; the fit takes it per power entering (the command divides by the entry
    # transmittance the file records).
    entry = [l for l in open(csv) if l.startswith("# entry transmittance per column")][0]
    transmittance = float(entry.split(column + "=")[1].split(",")[0])
    ours = skinspec.fit_profile(table[:, 0], table[:, 1] / transmittance)
    theirs = cli("fit-profile", "--profile", str(csv))["channels"][0]
    for key in ("reduced_scattering_per_mm", "absorption_per_mm", "residual_per_mm4"):
        assert ours[key] == theirs[key]
    assert ours["at_bounds"] == theirs["at_bounds"]
    assert column.startswith("R_")
    assert ours["fitted_profile_per_mm2"].shape == table[:, 1].shape


def test_fit_profile_refuses_bad_input():
    with pytest.raises(skinspec.InputError, match="profile_per_mm2: 2 values for 3 radii"):
        skinspec.fit_profile([0.1, 0.2, 0.3], [1.0, 0.5])
    with pytest.raises(skinspec.InputError, match=r"grid_scattering: expected \(first, last, step\)"):
        skinspec.fit_profile([0.1, 0.2, 0.3], [1.0, 0.5, 0.2], grid_scattering=(0.1, 3))


def dipole_per_mm2(r, reduced_scattering, absorption, eta):
    """Jensen et al. 2001 Eq. 4-5 (the classical dipole, A from Groenhuis' F_dr fit), written here independently."""
    extinction = reduced_scattering + absorption
    albedo = reduced_scattering / extinction
    effective = np.sqrt(3 * absorption * extinction)
    f_dr = -1.440 / eta**2 + 0.710 / eta + 0.668 + 0.0636 * eta
    a = (1 + f_dr) / (1 - f_dr)
    z_r = 1 / extinction
    z_v = z_r * (1 + 4 * a / 3)
    d_r, d_v = np.sqrt(r**2 + z_r**2), np.sqrt(r**2 + z_v**2)
    return albedo / (4 * np.pi) * (z_r * (effective * d_r + 1) * np.exp(-effective * d_r) / d_r**3
                                   + z_v * (effective * d_v + 1) * np.exp(-effective * d_v) / d_v**3)


def lit_scene(n=48, pitch=0.1, reduced_scattering=1.5, absorption=0.05, eta=1.3):
    """Twelve lit pixels on a flat sample and the exitance the dipole gives (Mukaigawa et al. 2009 Eq. 10)."""
    rng = np.random.default_rng(1)
    irradiance = np.zeros((n, n))
    lit = rng.choice(n * n, 12, replace=False)
    irradiance.flat[lit] = rng.uniform(0.5, 1.0, 12) / pitch**2
    y, x = np.mgrid[0:n, 0:n] * pitch
    exitance = np.zeros((n, n))
    for k in lit:
        ky, kx = divmod(k, n)
        exitance += dipole_per_mm2(np.hypot(x - kx * pitch, y - ky * pitch), reduced_scattering, absorption, eta) * irradiance.flat[k] * pitch**2
    return irradiance, exitance, x, y


def test_fit_profile_image_and_patches_recover_the_dipole():
    irradiance, exitance, x, y = lit_scene()
    search = dict(step_mm=0.1, grid_absorption=(0, 0.2, 0.005))
    fits = skinspec.fit_profile_image(irradiance, exitance, 0.1, **search)
    assert len(fits) == 1 and fits[0]["channel"] == "Y"
    fit = fits[0]
    # sigma_s' 1.5 and sigma_a 0.05 per mm went in (measured: 1.5010 and 0.0511 out, PSNR 58 dB).
    assert fit["reduced_scattering_per_mm"] == pytest.approx(1.5, rel=0.01)
    assert fit["absorption_per_mm"] == pytest.approx(0.05, rel=0.05)
    assert fit["at_bounds"] == [] and fit["psnr_db"] > 50 and fit["synthesised"].shape == (48, 48)
    # Three channels: one fit each.
    assert [f["channel"] for f in skinspec.fit_profile_image(np.dstack([irradiance] * 3), np.dstack([exitance] * 3), 0.1, **search)] == ["R", "G", "B"]
    # The same pixels as a patch list (flat, normals +z): the same system, the same parameters.
    n = irradiance.size
    patches = np.column_stack([x.ravel(), y.ravel(), np.zeros(n), np.zeros(n), np.zeros(n), np.ones(n), irradiance.ravel() * 0.01, exitance.ravel(), np.ones(n)])
    from_patches = skinspec.fit_profile_patches(patches, **search)
    assert from_patches["reduced_scattering_per_mm"] == pytest.approx(fit["reduced_scattering_per_mm"], rel=1e-6)
    assert from_patches["absorption_per_mm"] == pytest.approx(fit["absorption_per_mm"], rel=1e-6)
    with pytest.raises(skinspec.InputError, match="patches row 0: the normal has length 2"):
        skinspec.fit_profile_patches(np.column_stack([patches[:, :5], 2 * patches[:, 5:6], patches[:, 6:]]))
    with pytest.raises(skinspec.InputError, match="exitance: its shape differs"):
        skinspec.fit_profile_image(irradiance, exitance[:, :10], 0.1)
    with pytest.raises(skinspec.InputError, match="--pitch = 0 mm is outside"):
        skinspec.fit_profile_image(irradiance, exitance, 0.0)


def test_fit_profile_image_files_equal_the_command(cli, tmp_path):
    subprocess.run([os.environ["SKINSPEC_PROGRAM"], "fit-profile", "--synthetic", "--output-dir", str(tmp_path)], check=True, capture_output=True)
    images = [str(tmp_path / "synthetic_irradiance.exr"), str(tmp_path / "synthetic_exitance.exr")]
    ours = skinspec.fit_profile_image(*images, 0.05)
    theirs = cli("fit-profile", "--irradiance", images[0], "--exitance", images[1], "--pitch", "0.05")["channels"]
    assert len(ours) == len(theirs) == 1
    for key in ("reduced_scattering_per_mm", "absorption_per_mm", "residual_per_mm4", "psnr_db"):
        assert ours[0][key] == theirs[0][key]
