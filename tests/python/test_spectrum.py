"""skinspec.spectrum and skinspec.profiles: the solver registry from Python, equal to the program's numbers for
the same material, seed and options (python/spectrum_binding.cpp)."""
import numpy as np
import pytest

import skinspec


def cli_arrays(result, key):
    return np.array([np.nan if v is None else v for v in result[key]], dtype=float)


# One case per registered solver: (mode, material, CLI arguments, Python keyword arguments).
CASES = [
    ("biospec", ["--quantities", "R,T,A", "--rays", "3000", "--seed", "7", "--geometry", "sce"],
     dict(quantities="R,T,A", rays=3000, seed=7, geometry="sce")),
    ("rte", ["--quantities", "R,T", "--rays", "400", "--seed", "3", "--boundaries", "split"],
     dict(quantities=["R", "T"], rays=400, seed=3, boundaries="split")),
    ("adding-doubling", ["--quantities", "R,T", "--channels", "8"], dict(quantities="R,T", channels=8)),
    ("biospec-adding-doubling", ["--quantities", "R,T,A", "--channels", "12", "--fold-into-skin", "resample", "--incidence", "30"],
     dict(quantities="R,T,A", channels=12, fold_into_skin="resample", incidence_deg=30)),
    ("matched-multipole", ["--quantities", "R,T,A", "--channels", "8"], dict(quantities="R,T,A", channels=8)),
    ("multipole", ["--quantities", "R,T"], dict(quantities="R,T")),
    ("dipole", ["--roughness", "0.3"], dict(roughness=0.3)),
]


def test_every_registered_solver_is_covered():
    assert sorted(s["name"] for s in skinspec.solvers()) == sorted(c[0] for c in CASES)


@pytest.mark.parametrize("mode, cli_args, kwargs", CASES, ids=[c[0] for c in CASES])
def test_module_spectrum_equals_the_cli(cli, mode, cli_args, kwargs):
    m = skinspec.Material("biospec-moderately")
    m["epidermis.melanosome_fraction"] = 0.03
    wavelengths = np.arange(450, 701, 50)
    # A solver with a bottom sees it opened; a semi-infinite one (the dipole) refuses that, and computes no T.
    bottom = next(s["bottom"] for s in skinspec.solvers() if s["name"] == mode)
    ours = skinspec.spectrum(m, wavelengths, mode=mode, **(dict(reflector=False) if bottom else {}), **kwargs)
    theirs = cli("spectrum", "--preset", "biospec-moderately", "--set", "epidermis.melanosome_fraction=0.03", "--mode", mode,
                 *(["--reflector", "off"] if bottom else []), "--wavelengths", "450:700:50", *cli_args)["results"][0]
    np.testing.assert_array_equal(ours.wavelength_nm, theirs["wavelength_nm"])
    for key in ("R", "R_specular", "T") if bottom else ("R", "R_specular"):
        np.testing.assert_allclose(getattr(ours, key), cli_arrays(theirs, key), rtol=0, atol=1e-12)
        if ours.has_uncertainty:
            np.testing.assert_allclose(getattr(ours, key + "_stderr"), cli_arrays(theirs, key + "_stderr"), rtol=0, atol=1e-12)
    if ours.has_uncertainty:
        np.testing.assert_array_equal(ours.rays, theirs["rays"])
    else:
        assert ours.R_stderr is None and ours.rays is None
    assert ours.provenance["material_toml"] == theirs["provenance"]["material_toml"]
    assert ours.settings == theirs["settings"]


def test_band_materials_give_bands(cli):
    ours = skinspec.spectrum("jensen2001-skin1", mode="dipole")
    theirs = cli("spectrum", "--preset", "jensen2001-skin1", "--mode", "dipole")["results"][0]
    assert ours.wavelength_nm is None and ours.bands == ["R", "G", "B"]
    np.testing.assert_allclose(ours.R, cli_arrays(theirs, "R"), rtol=0, atol=1e-12)


def test_energy_is_conserved_per_wavelength():
    # R + T + A (every layer) + A_surface = 1 for every photon history: the conservation law, to rounding.
    s = skinspec.spectrum("biospec-lightly", np.arange(400, 701, 100), quantities="R,T,A", rays=2000, reflector="off")
    total = s.R + s.T + s.A.sum(axis=-1) + s.A_surface
    np.testing.assert_allclose(total, 1.0, rtol=0, atol=1e-12)
    assert s.A.shape == (4, 4) and s.layer_names[1] == "epidermis"
    # Over the measured hypodermis what it keeps is T, so the sum holds there too.
    h = skinspec.spectrum("biospec-lightly", np.arange(400, 701, 100), quantities="R,T,A", rays=2000, reflector="hypodermis")
    np.testing.assert_allclose(h.R + h.T + h.A.sum(axis=-1) + h.A_surface, 1.0, rtol=0, atol=1e-12)
    assert (h.T > 0.0).all()


def test_sweep_arrays_have_the_sweep_shape_and_equal_the_cli_grid(cli):
    melanin = [0.01 + (0.1 - 0.01) * i / 2 for i in range(3)]
    blood = [0.002 + (0.02 - 0.002) * i / 1 for i in range(2)]
    ours = skinspec.spectrum("biospec-moderately", np.arange(400, 701, 100), rays=1500, seed=4,
                             vary={"epidermis.melanosome_fraction": melanin, "dermis.blood_fraction": blood})
    assert ours.R.shape == (3, 2, 4) and ours.rays.shape == (3, 2, 4) and ours.provenance.shape == (3, 2)
    theirs = cli("spectrum", "--preset", "biospec-moderately", "--wavelengths", "400:700:100", "--rays", "1500", "--seed", "4",
                 "--vary", "epidermis.melanosome_fraction=0.01:0.1:3", "--vary", "dermis.blood_fraction=0.002:0.02:2")["results"]
    assert len(theirs) == 6
    for k, result in enumerate(theirs):  # the CLI lists the first field fastest
        i, j = k % 3, k // 3
        assert ours.provenance[i, j]["varied"] == {"epidermis.melanosome_fraction": melanin[i], "dermis.blood_fraction": blood[j]}
        np.testing.assert_allclose(ours.R[i, j], cli_arrays(result, "R"), rtol=0, atol=1e-12)
        np.testing.assert_allclose(ours.R_stderr[i, j], cli_arrays(result, "R_stderr"), rtol=0, atol=1e-12)
    # More melanin, less reflectance at 400 nm (far beyond the standard errors here).
    assert ours.R[0, 0, 0] > ours.R[2, 0, 0] + 5 * ours.R_stderr[2, 0, 0]
    np.testing.assert_array_equal(ours.vary["epidermis.melanosome_fraction"], melanin)


def test_default_stops_at_the_cli_default_target():
    s = skinspec.spectrum("biospec-lightly", [450, 550, 650])
    assert np.all(s.R_stderr <= 0.002) and np.all(s.converged)


def test_threads_do_not_change_the_numbers():
    one = skinspec.spectrum("biospec-lightly", [500, 600], rays=20000, threads=1)
    two = skinspec.spectrum("biospec-lightly", [500, 600], rays=20000, threads=2)
    np.testing.assert_array_equal(one.R, two.R)


@pytest.mark.parametrize("kwargs, message", [
    (dict(mode="dipole", quantities="brdf"), "does not compute brdf"),
    (dict(mode="dipole", stderr=0.01), "is deterministic"),
    (dict(mode="rte", estimator="random"), "estimator"),
    (dict(mode="adding-doubling", channels=3), r"channels = 3 is outside \[4, 256\]"),
    (dict(mode="dipole", roughness=-0.1), r"roughness = -0.1 is outside \(0, 2\]"),
    (dict(estimater="random"), r"'estimater' is not a keyword \(solver switches: estimator, fold_into_skin, roughness, boundaries, channels\)"),
    (dict(mode="mcml"), "allowed"),
    (dict(quantities="R,X"), "'X' is not a quantity"),
    (dict(wavelengths=[[400, 500], [600, 700]]), r"expected a 1-D array, got shape \(2, 2\)"),
    (dict(wavelengths=[400, float("nan"), 600]), r"wavelengths\[1\] = nan is not a finite number"),
    (dict(wavelengths=[600, 500]), "increasing"),
    (dict(wavelengths="400:700:10"), "expected numbers"),
    (dict(rays=0), r"rays = 0 is outside \[100, "),
    (dict(rays=100, stderr=0.01), "not both"),
    (dict(stderr=-1.0), r"stderr = -1.0 is outside \(0, inf\)"),
    (dict(seed=-1), r"seed = -1 is outside \[0, "),
    (dict(seed=1.5), "seed: expected a whole number"),
    (dict(threads=0), r"threads = 0 is outside \[1, 1024\]"),
    (dict(reflector="maybe"), r"reflector: 'maybe' is not allowed \(allowed: on, off, hypodermis\)"),
    (dict(reflector=3), "reflector: must be True, False or one of on, off, hypodermis"),
    (dict(geometry="45-0"), "is not a measurement geometry"),
    (dict(vary={"epidermis.melanosome_fraction": [0.01, -0.2]}), r"= -0.2 is outside \[0, 1\]"),
    (dict(vary={"epidermis.melanosome_fraction": [0.01, float("nan")]}), "is not a finite number"),
    (dict(vary={"epidermis.melanin": [0.01]}), "unknown key 'epidermis.melanin'"),
    (dict(vary={"epidermis.melanosome_fraction": []}), "no values"),
    (dict(layers="epidermis,dermis"), "dermis"),
])
def test_bad_requests_raise_input_errors(kwargs, message):
    if "stderr" not in kwargs and kwargs.get("mode") not in ("dipole", "multipole"):
        kwargs.setdefault("rays", 100)  # keep the Monte Carlo cases short; the refusal comes first anyway
    wavelengths = kwargs.pop("wavelengths", [500, 600])
    with pytest.raises(skinspec.InputError, match=message):
        skinspec.spectrum("biospec-moderately", wavelengths, **kwargs)


def test_profiles_equal_the_cli_profile_table():
    import os
    import subprocess
    radii = np.arange(0.0, 2.01, 0.5)
    ours = skinspec.profiles("biospec-moderately", radii, [550, 650], mode="matched-multipole", transmittance=True)
    table = subprocess.run([os.environ["SKINSPEC_PROGRAM"], "profile", "--preset", "biospec-moderately", "--wavelengths", "550,650",
                            "--radii", "0:2:0.5", "--mode", "matched-multipole"], capture_output=True, text=True, check=True).stdout
    rows = np.array([[float(v) for v in line.split(",")] for line in table.splitlines() if line and line[0].isdigit()])
    np.testing.assert_allclose(rows[:, 0], radii)
    np.testing.assert_allclose(ours.R_per_mm2.T, rows[:, 1:3], rtol=1e-8)
    # 2 pi int R(r) r dr over all r is the total diffuse R; the profile integrates to it (most of it within 2 mm).
    assert ours.total_R.shape == (2,) and np.all(ours.total_R > 0.1)
    # The diffusion profile's shape against the walk, as the command states it (its CSV comments), one per wavelength.
    assert [w["wavelength_nm"] for w in ours.shape["wavelengths"]] == [550.0, 650.0]
    stated = [line for line in table.splitlines() if line.startswith("#   650 nm: the share of R")][0]
    assert f"{ours.shape['wavelengths'][1]['largest_share_difference']:+.3f}" in stated
    with pytest.raises(skinspec.InputError, match="radial"):
        skinspec.profiles("biospec-moderately", radii, mode="biospec")


def test_volumetric_profiles_equal_the_cli_with_standard_errors():
    import os
    import subprocess
    radii = np.arange(0.0, 1.01, 0.25)
    ours = skinspec.profiles("biospec-moderately", radii, [550], mode="rte", rays=20000, seed=4)
    table = subprocess.run([os.environ["SKINSPEC_PROGRAM"], "profile", "--mode", "rte", "--preset", "biospec-moderately", "--wavelengths", "550",
                            "--radii", "0:1:0.25", "--rays", "20000", "--seed", "4"], capture_output=True, text=True, check=True).stdout
    rows = np.array([[float(v) for v in line.split(",")] for line in table.splitlines() if line and line[0].isdigit()])
    np.testing.assert_allclose(ours.R_per_mm2[0], rows[:, 1], rtol=1e-8)
    np.testing.assert_allclose(ours.R_stderr_per_mm2[0], rows[:, 2], rtol=1e-2)
    assert ours.shape is None  # the walk's profile is the reference itself
    assert skinspec.profiles("biospec-moderately", radii, [550], mode="matched-multipole").R_stderr_per_mm2 is None
    with pytest.raises(skinspec.InputError, match="deterministic: it takes no ray count"):
        skinspec.profiles("biospec-moderately", radii, [550], mode="matched-multipole", rays=100)
    # The default is the exact transport at its precision target, the same numbers as the command's default.
    default = skinspec.profiles("biospec-moderately", radii, [550], stderr=0.004)
    table = subprocess.run([os.environ["SKINSPEC_PROGRAM"], "profile", "--preset", "biospec-moderately", "--wavelengths", "550",
                            "--radii", "0:1:0.25", "--stderr", "0.004"], capture_output=True, text=True, check=True).stdout
    rows = np.array([[float(v) for v in line.split(",")] for line in table.splitlines() if line and line[0].isdigit()])
    np.testing.assert_allclose(default.R_per_mm2[0], rows[:, 1], rtol=1e-8)
    with pytest.raises(skinspec.InputError, match="rays and stderr / max_rays"):
        skinspec.profiles("biospec-moderately", radii, [550], rays=1000, stderr=0.01)
    with pytest.raises(skinspec.InputError, match="rays and stderr / max_rays"):
        skinspec.profiles("biospec-moderately", radii, [550], rays=1000, max_rays=5000)
    with pytest.raises(skinspec.InputError, match="equal steps"):
        skinspec.profiles("biospec-moderately", [0.1, 0.2, 0.3], [550], mode="rte", rays=100)


def test_profiles_honour_the_boundaries_switch():
    # The volumetric walk's split boundaries reach profiles as they reach spectrum; a solver without the switch refuses it.
    radii = np.arange(0.0, 1.01, 0.25)
    split = skinspec.profiles("biospec-moderately", radii, [550], mode="rte", rays=20000, seed=4, boundaries="split")
    random = skinspec.profiles("biospec-moderately", radii, [550], mode="rte", rays=20000, seed=4, boundaries="random")
    assert not np.array_equal(split.R_per_mm2, random.R_per_mm2)
    with pytest.raises(skinspec.InputError, match="does not take the switch 'boundaries'"):
        skinspec.profiles("biospec-moderately", radii, [550], mode="multipole", boundaries="split")


def test_switch_keywords_come_from_the_descriptors():
    assert [s["keyword"] for s in skinspec.switches()] == ["estimator", "fold_into_skin", "roughness", "boundaries", "channels"]
    for solver in skinspec.solvers():
        for switch in solver["switches"]:
            assert switch == "thin-layer-phase" or switch.replace("-", "_") in [s["keyword"] for s in skinspec.switches()]


def test_spectrum_arrays_follow_the_result_quantity_table():
    names = [q["python_name"] for q in skinspec.result_quantities()]
    assert names == ["R", "R_specular", "T", "A", "A_surface", "brdf_per_sr", "btdf_per_sr"]
    s = skinspec.spectrum("biospec-lightly", [500, 600], quantities="R,A,brdf", rays=500)
    for name in names:
        assert hasattr(s, name) and hasattr(s, name + "_stderr")
    assert s.T is None and s.A.shape == (2, 4) and s.brdf_per_sr.shape[0] == 2 and s.btdf_per_sr.shape == s.brdf_per_sr.shape


def test_monte_carlo_settings_are_refused_by_deterministic_modes():
    # As the CLI refuses --seed / --max-rays for them (issue 33): given, never silently ignored.
    with pytest.raises(skinspec.InputError, match="seed: solver 'dipole' is deterministic"):
        skinspec.spectrum("biospec-lightly", [550], mode="dipole", seed=5)
    with pytest.raises(skinspec.InputError, match="max_rays: solver 'adding-doubling' is deterministic"):
        skinspec.spectrum("biospec-lightly", [550], mode="adding-doubling", max_rays=100)
    with pytest.raises(skinspec.InputError, match="seed: solver 'matched-multipole' is deterministic"):
        skinspec.profiles("biospec-lightly", [0.0, 0.5, 1.0], mode="matched-multipole", seed=2)
    with pytest.raises(skinspec.InputError, match="stderr: solver 'multipole' is deterministic"):
        skinspec.profiles("biospec-lightly", [0.0, 0.5, 1.0], mode="multipole", stderr=0.01)
    assert skinspec.spectrum("biospec-lightly", [550], mode="dipole").R[0] > 0.0
