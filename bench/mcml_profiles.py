#!/usr/bin/env python3
"""R(r) of skin in MCML 1.2 against skinspec's volumetric walk on the same MCML input (docs/PROFILES.md, issue 61 item 5).

    python3 bench/mcml_profiles.py --mcml /path/to/mcml [--skinspec build/skinspec] [--photons 2000000]
                                   [--presets biospec-moderately,...] [--wavelengths 450,550,650]

Fetches and builds nothing: MCML 1.2 is built outside the repository (docs/PERFORMANCE.md says how). For each preset,
`skinspec export mcml` writes its volumetric description as one MCML run per wavelength (rings of 0.01 mm to 5 mm;
HG of the same mean cosine for the measured phase functions and no bottom reflector: what MCML can hold, stated in the
file). MCML runs that file once; `skinspec mcml` runs the same file with the same photon count, with standard errors
per ring (batch means). MCML prints none: its estimator is the walk's (MCML's weights, absorption per interaction,
roulette), so its standard error per ring is taken as the walk's at the same photon count, and the combined standard
error of a ring is sqrt(2) times the walk's. Every ring whose centre lies in 0.05-5 mm is compared:
z = (MCML - walk) / combined standard error. Printed per preset and wavelength: the rings compared, how many lie within
3 combined standard errors, chi-square per ring (mean z^2: 1 when the two agree to their noise) and the largest |z|,
the same over the rings the walk resolves to 20 % (its relative standard error below 0.2: where a few heavy photons
do not make a ring's value, which the proxy error does not cover), and the two diffuse reflectances.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile


def mco_rd_r(path):
    """Rd_r (1/cm^2 per ring) and the diffuse R from an MCML 1.2 .mco file."""
    with open(path) as f:
        lines = f.read().splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("Rd_r"))
    values = []
    for line in lines[start + 1:]:
        if not line.strip():
            break
        values.append(float(line.split()[0]))
    rat = next(i for i, line in enumerate(lines) if line.startswith("RAT"))
    diffuse = float(lines[rat + 2].split()[0])
    return values, diffuse


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--mcml", required=True, help="MCML 1.2 built outside the repository")
    parser.add_argument("--skinspec", default=os.path.join(os.path.dirname(__file__), "..", "build", "skinspec"))
    parser.add_argument("--photons", type=int, default=2_000_000)
    parser.add_argument("--presets", default="biospec-lightly,biospec-moderately,biospec-heavily,biospec-very-heavily")
    parser.add_argument("--wavelengths", default="450,550,650")
    a = parser.parse_args()
    program = os.path.abspath(a.skinspec)
    work = tempfile.mkdtemp(prefix="skinspec_mcml_profiles_")
    print(f"MCML 1.2 ({a.mcml}) against `skinspec mcml` on `skinspec export mcml` files, {a.photons} photons per wavelength each; "
          "rings of 0.01 mm whose centre is in 0.05-5 mm")
    print(f"{'preset':<22}{'nm':>5}{'rings':>7}{'within 3 sigma':>16}{'chi2/ring':>11}{'max |z|':>9}"
          f"{'resolved':>10}{'within':>16}{'chi2/ring':>11}{'max |z|':>9}{'R MCML':>10}{'R walk':>10}")
    for preset in a.presets.split(","):
        mci = os.path.join(work, f"{preset}.mci")
        subprocess.run([program, "export", "mcml", "--preset", preset, "--wavelengths", a.wavelengths, "--photons", str(a.photons), "-o", mci,
                        "--overwrite"], check=True, capture_output=True)
        subprocess.run([os.path.abspath(a.mcml), os.path.basename(mci)], cwd=work, check=True, capture_output=True)
        walk_json = os.path.join(work, f"{preset}.json")
        os.makedirs(os.path.join(work, "walk"), exist_ok=True)
        subprocess.run([program, "mcml", mci, "--output-dir", os.path.join(work, "walk"), "--output", walk_json, "--overwrite"], check=True,
                       capture_output=True)
        walk = json.load(open(walk_json))["runs"]
        for nm, run in zip(a.wavelengths.split(","), walk):
            ours, ours_se = run["R_r_per_cm2"], run["R_r_per_cm2_stderr"]
            theirs, theirs_r = mco_rd_r(os.path.join(work, f"{preset}_{nm}nm.mco"))
            dr_mm = 0.01
            z, resolved = [], []
            for i, (x, y, s) in enumerate(zip(theirs, ours, ours_se)):
                centre = (i + 0.5) * dr_mm
                if centre < 0.05 or centre > 5.0 or i == len(theirs) - 1 or s <= 0.0:
                    continue
                z.append((x - y) / (math.sqrt(2.0) * s))
                if s < 0.2 * y:
                    resolved.append(z[-1])

            def summary(values):
                if not values:
                    return f"{0:>7}{'-':>16}{'-':>11}{'-':>9}"
                within = sum(1 for v in values if abs(v) <= 3.0)
                return (f"{len(values):>7}{within:>10} ({100.0 * within / len(values):.1f} %){sum(v * v for v in values) / len(values):>8.2f}"
                        f"{max(abs(v) for v in values):>9.2f}")
            print(f"{preset:<22}{nm:>5}{summary(z)}   {summary(resolved)}{theirs_r:>10.5f}{run['R_diffuse']:>10.5f}")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
