"""skinspec.fit_profile: the dipole fit of a radial profile from numpy (python/profile_fit_binding.cpp), equal to
`skinspec fit-profile --profile` on the same profile, with the same refusals."""
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
