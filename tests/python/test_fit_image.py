"""skinspec.fit_image: per-pixel skin maps from Python (python/image_fit_binding.cpp), the library call `skinspec
fit-image` makes, with the maps as numpy arrays beside the command's --json summary."""
import numpy as np
import pytest

import skinspec

FAST = dict(delta_e=1.0, channels=8, melanin="0.005:0.45:12:log", blood="0.001:0.1:8:log")


def test_fit_image_recovers_the_fields_of_a_swatch_made_by_the_model():
    # An "image": the model's own albedo at 3 x 2 fields between the table's nodes (skinspec.swatch, linear Rec.709).
    truth = skinspec.swatch("biospec-moderately", ["epidermis.melanosome_fraction=0.02:0.2:3:log", "dermis.blood_fraction=0.004:0.04:2:log"],
                            mode="biospec-adding-doubling", geometry="sce", delta_e=1.0, space="Linear Rec.709", channels=8)
    out = skinspec.fit_image(truth["rgb"], noise=0.002, edit="epidermis.melanosome_fraction=*0.5", **FAST)
    maps = out["maps"]
    assert maps["status"].shape == (2, 3)
    assert (maps["status"] == 0).all()
    assert out["pixels"]["fitted"] == 6
    np.testing.assert_allclose(maps["epidermis.melanosome_fraction"], truth["parameters"][:, :, 0], rtol=0.05)
    np.testing.assert_allclose(maps["dermis.blood_fraction"], truth["parameters"][:, :, 1], rtol=0.05)
    assert (maps["epidermis.melanosome_fraction.stderr"] > 0).all()
    # Half the melanin is lighter skin in every channel.
    assert out["edited"].shape == (2, 3, 3)
    assert (out["edited"] > truth["rgb"]).all()


def test_fit_image_fits_the_swatch_chart_skinspec_wrote_with_both_defaults(tmp_path):
    # One geometry everywhere (docs/PROFILES.md): `skinspec swatch` with its defaults (the BioSpec walk to CIEDE2000 0.3,
    # sce, ACEScg) and fit-image with its own read the same skin. The chart's EXR states its geometry and colour space,
    # and every pixel of its 8 x 5 patches (112 px, 8 px gaps) is fitted back to the values it was made from: within
    # 6 % in melanin and 10 % in blood (measured: up to 4.5 % and 8 %: the chart's walk against the table's
    # biospec-adding-doubling, CIEDE2000 ~0.2 apart, and the table's spline). Not the blood of the darkest column
    # (melanosome fraction 0.42): there the colour barely depends on the blood and it comes back 41-57 % high
    # (docs/FIT_IMAGE.md).
    import os
    import subprocess
    chart = tmp_path / "chart.exr"
    subprocess.run([os.environ["SKINSPEC_PROGRAM"], "swatch", "-o", str(chart)], capture_output=True, check=True)
    out = skinspec.fit_image(chart, melanin="0.005:0.45:24:log", blood="0.001:0.1:16:log")
    assert out["space"] == "ACEScg"
    maps = out["maps"]
    melanin = 0.01 * (0.42 / 0.01) ** (np.arange(8) / 7)
    blood = np.linspace(0.002, 0.05, 5)
    for row in range(5):
        for column in range(8):
            patch = (slice(8 + row * 120, 8 + row * 120 + 112), slice(8 + column * 120, 8 + column * 120 + 112))
            assert (maps["status"][patch] == 0).all(), (row, column)
            assert np.median(maps["epidermis.melanosome_fraction"][patch]) == pytest.approx(melanin[column], rel=0.06)
            if column < 7:
                assert np.median(maps["dermis.blood_fraction"][patch]) == pytest.approx(blood[row], rel=0.10)
    # The gaps between the patches are not skin, and are said to be.
    assert (maps["status"][0:8, :] == 1).all()
    # Fitted as sci (given: it overrides what the image states), the model no longer reaches the chart's darker colours
    # (60 % of the patches' pixels, measured).
    assert skinspec.fit_image(chart, geometry="sci")["pixels"]["fitted"] < 0.9 * 40 * 112 * 112


def test_fit_image_refuses_bad_arguments():
    rgb = np.full((2, 2, 3), 0.3)
    with pytest.raises(skinspec.InputError, match=r"expected an array \(height, width, 3\)"):
        skinspec.fit_image(np.zeros((2, 2)), noise=0.01, **FAST)
    with pytest.raises(skinspec.InputError, match=r"--white -1 is outside \(0, inf\)"):
        skinspec.fit_image(rgb, white=-1, **FAST)
    with pytest.raises(skinspec.InputError, match="expected FIELD=\\*SCALE or FIELD=VALUE"):
        skinspec.fit_image(rgb, edit="melanin=*2", **FAST)
    with pytest.raises(skinspec.InputError, match=r"--noise -1 is outside"):
        skinspec.fit_image(rgb, noise=-1, **FAST)
