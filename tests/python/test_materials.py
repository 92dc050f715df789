"""skinspec.Material: loading, reading and setting fields with the --set checks, saving (python/materials_binding.cpp)."""
import copy
import pickle

import pytest

import skinspec


def test_presets_load_and_describe_their_layers():
    assert "biospec-moderately" in skinspec.presets()
    m = skinspec.Material("biospec-moderately")
    assert m.kind == "layered"
    assert m.layers == ["stratum_corneum", "epidermis", "papillary_dermis", "reticular_dermis"]
    assert m["model.variant"] == "biospec"
    assert "epidermis.melanosome_fraction" in m.keys()
    jensen = [p for p in skinspec.presets() if p.startswith("jensen")]
    assert jensen and skinspec.Material(jensen[0]).kind == "homogeneous"


def test_set_field_reads_back_and_is_recorded():
    m = skinspec.Material("biospec-moderately")
    m["epidermis.melanosome_fraction"] = 0.03
    assert m["epidermis.melanosome_fraction"] == 0.03
    assert m.overrides == [("epidermis.melanosome_fraction", "0.03")]
    # A suffix addresses every layer it names, as --set does.
    m["dermis.oxygen_saturation"] = 0.8
    assert m["papillary_dermis.oxygen_saturation"] == 0.8 and m["reticular_dermis.oxygen_saturation"] == 0.8
    assert m["dermis.oxygen_saturation"] == 0.8
    # Its labels follow the data (issue 33): the name and description say it was changed, and how.
    assert m.name == "biospec-moderately_changed"
    assert "changed from biospec-moderately: epidermis.melanosome_fraction=0.03, dermis.oxygen_saturation=0.8" in m.description
    assert skinspec.Material("biospec-moderately").name == "biospec-moderately"


def test_same_material_as_the_cli_set():
    python_side = skinspec.Material("biospec-moderately")
    python_side["epidermis.melanosome_fraction"] = 0.03
    python_side["bottom.boundary"] = "exit"
    assert python_side.to_toml() == skinspec.Material.from_toml(python_side.to_toml()).to_toml()
    assert python_side == skinspec.Material.from_toml(python_side.to_toml())


@pytest.mark.parametrize("key, value, message", [
    ("epidermis.melanosome_fractoin", 0.1, "unknown key 'epidermis.melanosome_fractoin'"),
    ("epidermis.melanosome_fraction", -0.1, r"= -0.1 is outside \[0, 1\]"),
    ("epidermis.melanosome_fraction", float("nan"), r"= nan is outside \[0, 1\]"),
    ("epiderm.melanosome_fraction", 0.1, "no layer or section 'epiderm'"),
    ("epidermis.thickness_cm", "thick", "must be a number"),
])
def test_bad_fields_raise_and_leave_the_material_unchanged(key, value, message):
    m = skinspec.Material("biospec-moderately")
    before = m.to_toml()
    with pytest.raises(skinspec.InputError, match=message):
        m[key] = value
    assert m.to_toml() == before and m.overrides == []


def test_reading_unknown_or_ambiguous_fields_raises():
    m = skinspec.Material("biospec-moderately")
    with pytest.raises(skinspec.InputError, match="no layer or section 'epiderm'"):
        m["epiderm.melanosome_fraction"]
    m["papillary_dermis.blood_fraction"] = 0.01
    m["reticular_dermis.blood_fraction"] = 0.002
    with pytest.raises(skinspec.InputError, match="differ"):
        m["dermis.blood_fraction"]
    assert "epidermis.melanosome_fraction" in m and "epidermis.nothing" not in m


def test_update_is_all_or_none():
    m = skinspec.Material("biospec-moderately")
    with pytest.raises(skinspec.InputError):
        m.update({"epidermis.melanosome_fraction": 0.02, "epidermis.blood_fraction": 2.0})
    assert m["epidermis.melanosome_fraction"] == skinspec.Material("biospec-moderately")["epidermis.melanosome_fraction"]
    m.update({"epidermis.melanosome_fraction": 0.02, "dermis.blood_fraction": 0.01})
    assert m["epidermis.melanosome_fraction"] == 0.02 and len(m.overrides) == 2


def test_unknown_preset_names_the_presets():
    with pytest.raises(skinspec.InputError, match="neither a preset nor a .toml file"):
        skinspec.Material("biospec-medium")
    with pytest.raises(skinspec.InputError, match="expected a skinspec.Material"):
        skinspec.Material(3)


def test_save_does_not_overwrite_unless_asked(tmp_path):
    m = skinspec.Material("biospec-lightly")
    m["epidermis.melanosome_fraction"] = 0.02
    out = tmp_path / "light.toml"
    m.save(out)
    assert skinspec.Material(str(out))["epidermis.melanosome_fraction"] == 0.02
    assert skinspec.Material(out) == m
    m["epidermis.melanosome_fraction"] = 0.04
    with pytest.raises(skinspec.InputError, match="exists"):
        m.save(out)
    assert skinspec.Material(out)["epidermis.melanosome_fraction"] == 0.02
    m.save(out, overwrite=True)
    assert skinspec.Material(out)["epidermis.melanosome_fraction"] == 0.04


def test_copies_and_pickles_are_independent_and_equal():
    m = skinspec.Material("biospec-moderately")
    m["epidermis.melanosome_fraction"] = 0.03
    c = copy.deepcopy(m)
    c["epidermis.melanosome_fraction"] = 0.05
    assert m["epidermis.melanosome_fraction"] == 0.03
    p = pickle.loads(pickle.dumps(m))
    assert p == m and p.overrides == m.overrides


def test_field_listing_matches_the_descriptor_tables():
    rows = skinspec.fields()
    keys = {r["key"] for r in rows}
    assert "LAYER.melanosome_fraction" in keys
    assert all(r["doc"] for r in rows)
    assert "LAYER.melanosome_fraction" in skinspec.absorption_only_fields()
