#!/usr/bin/env python3
"""Which model predicts measured skin best: fits every spectrum of a measured file (e.g. the NIST subset) under
each combination of model variant, measurement geometry, vessel packaging and free parameters, and prints the
markdown table of docs/SPECTRUM_FIT.md ("Choosing the defaults").

    python3 scripts/fit_study.py MEASURED.csv [--skinspec build/skinspec] [--rays 20000]
"""
import argparse
import json
import statistics
import subprocess
import sys
import time

DEFAULT_FREE = "epidermis.melanosome_fraction,papillary_dermis.blood_fraction,reticular_dermis.blood_fraction,dermis.oxygen_saturation"

# (label, extra arguments)
COMBINATIONS = [
    ("previous model: Rayleigh turn charged the whole crossing", ["--set", "model.rayleigh_turn=whole_crossing"]),
    ("biospec (sampled-depth Rayleigh turn)", []),
    ("biospec-2004", ["--variant", "biospec-2004"]),
    ("biospec-authors-code", ["--variant", "biospec-authors-code"]),
    ("biospec, geometry sce", ["--geometry", "sce"]),
    ("biospec, geometry 0-45", ["--geometry", "0-45"]),
    ("biospec, packaging 10 um in both dermal layers", ["--set", "dermis.vessel_radius_um=10"]),
    ("biospec, packaging papillary 5 um, reticular 20 um",
     ["--set", "papillary_dermis.vessel_radius_um=5", "--set", "reticular_dermis.vessel_radius_um=20"]),
    ("biospec, + reticular vessel radius free", ["--free", DEFAULT_FREE + ",reticular_dermis.vessel_radius_um"]),
    ("biospec, + papillary vessel radius free", ["--free", DEFAULT_FREE + ",papillary_dermis.vessel_radius_um"]),
    ("biospec, + epidermal carotene free", ["--free", DEFAULT_FREE + ",epidermis.carotene_g_per_l"]),
    ("biospec, + bilirubin free", ["--free", DEFAULT_FREE + ",dermis.bilirubin_g_per_l"]),
    ("biospec, + epidermis thickness free", ["--free", DEFAULT_FREE + ",epidermis.thickness_cm"]),
]


PRESET_SETS = [
    ("paper presets (biospec-lightly, -moderately, -heavily)", ["biospec-lightly", "biospec-moderately", "biospec-heavily"]),
    ("measured presets (forearm-nist2017-p10, -p50, -p90)", ["forearm-nist2017-p10", "forearm-nist2017-p50", "forearm-nist2017-p90"]),
]


def read_measured(path):
    rows = [line.strip() for line in open(path) if line.strip() and not line.startswith("#")]
    header = rows[0].split(",")
    table = [[float(x) for x in r.split(",")] for r in rows[1:]]
    wavelengths = [r[0] for r in table]
    return wavelengths, {name: [r[i + 1] for r in table] for i, name in enumerate(header[1:])}


def preset_table(args, model_args, label):
    """Best-of-presets RMS: each measured spectrum against the closest preset (no fit)."""
    wavelengths, measured = read_measured(args.measured)
    grid = ",".join(f"{w:g}" for w in wavelengths)
    print(f"\n{label}: each measured spectrum against its closest preset (no fit), 400-700 nm\n")
    print("| presets | median best RMS | worst best RMS | L* of the presets |")
    print("|---|---|---|---|")
    for set_label, presets in PRESET_SETS:
        cmd = [args.skinspec, "spectrum", "--wavelengths", grid, "--stderr", "0.002", "--json"] + model_args
        for p in presets:
            cmd += ["--preset", p]
        out = subprocess.run(cmd, capture_output=True, text=True, check=True)
        results = json.loads(out.stdout)["results"]
        spectra = {r["material"]: r["R"] for r in results}
        lightness = [f"{r['color']['Lab'][0]:.1f}" for r in results]
        best = []
        for values in measured.values():
            best.append(min((sum((a - b) ** 2 for a, b in zip(values, model)) / len(values)) ** 0.5 for model in spectra.values()))
        print(f"| {set_label} | {statistics.median(best):.4f} | {max(best):.4f} | {', '.join(lightness)} |")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("measured")
    parser.add_argument("--skinspec", default="build/skinspec")
    parser.add_argument("--rays", default="20000")
    args = parser.parse_args()
    preset_table(args, ["--set", "model.rayleigh_turn=whole_crossing"], "Previous model (whole-crossing Rayleigh turn)")
    preset_table(args, [], "Default model (sampled-depth Rayleigh turn)")
    print()
    print("| combination | median RMS | worst RMS | median dE00 | blue 400-450 | 540-580 | 590-600 | red 610-700 | fits on a bound | s per spectrum |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for label, extra in COMBINATIONS:
        start = time.time()
        out = subprocess.run([args.skinspec, "fit-spectrum", args.measured, "--json", "--rays", args.rays] + extra,
                             capture_output=True, text=True)
        if out.returncode != 0:
            print(f"| {label} | failed: {out.stderr.strip()} |")
            continue
        result = json.loads(out.stdout)
        fits = result["fits"]
        per = (time.time() - start) / len(fits)
        bands = {b["band"]: b["mean_residual"] for b in result["mean_residual_by_band"]}
        bounded = sum(1 for f in fits if f["on_bound"])
        de = statistics.median(f["delta_e2000"] for f in fits)
        print(f"| {label} | {result['median_rms']:.4f} | {result['worst_rms']:.4f} | {de:.2f} | "
              + " | ".join(f"{v:+.4f}" for v in bands.values()) + f" | {bounded} of {len(fits)} | {per:.2f} |")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
