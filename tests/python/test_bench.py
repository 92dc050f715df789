"""skinspec.bench: the benchmark report from Python (python/bench_binding.cpp), the same fields and, run for run,
the same values as `skinspec bench --quick --json` (times differ: they are measured)."""
import pytest

import skinspec


def test_bench_reports_what_the_command_reports(cli):
    ours = skinspec.bench(quick=True, seed=3)
    theirs = cli("bench", "--quick", "--seed", "3")
    assert list(ours.keys()) == list(theirs.keys())
    assert [c["name"] for c in ours["cases"]] == [c["name"] for c in theirs["cases"]]
    for a, b in zip(ours["cases"], theirs["cases"]):
        assert a["reference"] == b["reference"]
        assert [(p["solver"], p["rays"], p["value"]) for p in a["points"]] == [(p["solver"], p["rays"], p["value"]) for p in b["points"]]
    assert [(r["material"], r["solver"], r["max_abs_error"]) for r in ours["skin_in_every_mode"]] == \
        [(r["material"], r["solver"], r["max_abs_error"]) for r in theirs["skin_in_every_mode"]]


def test_bench_refuses_a_tolerance_outside_its_range():
    with pytest.raises(skinspec.InputError, match=r"tolerance_percent = 100 % is outside \(0, 100\)"):
        skinspec.bench(quick=True, tolerance_percent=100)
