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
