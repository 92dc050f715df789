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


def profile_csv(program, preset, wavelengths, extra, work):
    """R(r) per wavelength (1/mm^2) of `skinspec profile` on 0-5 mm by 0.01 mm: {nm: [values]}."""
    out = os.path.join(work, "profile.csv")
    subprocess.run([program, "profile", "--preset", preset, "--wavelengths", wavelengths, "--radii", "0:5:0.01", "--output", out, "--overwrite"]
                   + extra, check=True, capture_output=True)
    rows = [line.split(",") for line in open(out).read().splitlines() if line and not line.startswith("#")]
    header = rows[0]
    curves = {}
    for nm in wavelengths.split(","):
        column = header.index(f"R_{nm}nm_per_mm2")
        curves[nm] = [float(r[column]) for r in rows[1:]]
    return [float(r[0]) for r in rows[1:]], curves


def svg_figure(path, title, series):
    """A log-scale line plot: `series` is [(label, colour, dash, width, radii_mm, values_per_mm2)]."""
    w, h, left, right, top, bottom = 900, 560, 80, 250, 40, 50
    x_max, y_lo, y_hi = 5.0, -6.0, 2.0
    def x_of(r):
        return left + (w - left - right) * r / x_max
    def y_of(v):
        return top + (h - top - bottom) * (y_hi - math.log10(v)) / (y_hi - y_lo)
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="DejaVu Sans, sans-serif" font-size="12">',
           f'<rect width="{w}" height="{h}" fill="white"/>', f'<text x="{left}" y="24" font-size="14">{title}</text>']
    for e in range(int(y_lo), int(y_hi) + 1):
        y = y_of(10.0 ** e)
        out.append(f'<line x1="{left}" y1="{y:.1f}" x2="{w - right}" y2="{y:.1f}" stroke="#ddd"/>')
        out.append(f'<text x="{left - 8}" y="{y + 4:.1f}" text-anchor="end">1e{e}</text>')
    for r in range(0, 6):
        x = x_of(r)
        out.append(f'<line x1="{x:.1f}" y1="{top}" x2="{x:.1f}" y2="{h - bottom}" stroke="#ddd"/>')
        out.append(f'<text x="{x:.1f}" y="{h - bottom + 18}" text-anchor="middle">{r}</text>')
    out.append(f'<text x="{(left + w - right) / 2}" y="{h - 10}" text-anchor="middle">radius r (mm)</text>')
    out.append(f'<text x="18" y="{(top + h - bottom) / 2}" transform="rotate(-90 18 {(top + h - bottom) / 2})" text-anchor="middle">'
               'R(r) (1/mm^2)</text>')
    for k, (label, colour, dash, width, radii, values) in enumerate(series):
        points = " ".join(f"{x_of(r):.1f},{y_of(v):.1f}" for r, v in zip(radii, values) if 0.0 < r <= x_max and v > 10.0 ** y_lo)
        out.append(f'<polyline points="{points}" fill="none" stroke="{colour}" stroke-width="{width}" stroke-dasharray="{dash}"/>')
        y = top + 14 * k + 10
        out.append(f'<line x1="{w - right + 10}" y1="{y}" x2="{w - right + 40}" y2="{y}" stroke="{colour}" stroke-width="{width}" stroke-dasharray="{dash}"/>')
        out.append(f'<text x="{w - right + 46}" y="{y + 4}">{label}</text>')
    out.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--mcml", required=True, help="MCML 1.2 built outside the repository")
    parser.add_argument("--skinspec", default=os.path.join(os.path.dirname(__file__), "..", "build", "skinspec"))
    parser.add_argument("--photons", type=int, default=2_000_000)
    parser.add_argument("--presets", default="biospec-lightly,biospec-moderately,biospec-heavily,biospec-very-heavily")
    parser.add_argument("--wavelengths", default="450,550,650")
    parser.add_argument("--figure", help="FILE.svg: R(r) of the first preset: the default exact profile, matched-multipole, and MCML "
                                         "and the walk on the exported file")
    a = parser.parse_args()
    program = os.path.abspath(a.skinspec)
    work = tempfile.mkdtemp(prefix="skinspec_mcml_profiles_")
    print(f"MCML 1.2 ({a.mcml}) against `skinspec mcml` on `skinspec export mcml` files, {a.photons} photons per wavelength each; "
          "rings of 0.01 mm whose centre is in 0.05-5 mm")
    print(f"{'preset':<22}{'nm':>5}{'rings':>7}{'within 3 sigma':>16}{'chi2/ring':>11}{'max |z|':>9}"
          f"{'resolved':>10}{'within':>16}{'chi2/ring':>11}{'max |z|':>9}{'R MCML':>10}{'R walk':>10}")
    figure = []
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
            if a.figure and preset == a.presets.split(",")[0]:
                # 1/cm^2 -> 1/mm^2; the last ring (everything beyond the reach, as MCML tallies it) left out.
                rings = [(i + 0.5) * dr_mm for i in range(len(theirs) - 1)]
                figure.append((f"{nm} nm MCML, exported file", nm, "6,3", 1.2, rings, [v / 100.0 for v in theirs[:-1]]))
                figure.append((f"{nm} nm walk, exported file", nm, "2,2", 1.2, rings, [v / 100.0 for v in ours[:-1]]))
        sys.stdout.flush()
    if a.figure:
        preset = a.presets.split(",")[0]
        radii, exact = profile_csv(program, preset, a.wavelengths, ["--stderr", "0.0005"], work)
        _, diffusion = profile_csv(program, preset, a.wavelengths, ["--mode", "matched-multipole"], work)
        colours = dict(zip(a.wavelengths.split(","), ["#2060d0", "#20a040", "#d03020", "#806000", "#800080"]))
        series = []
        for nm in a.wavelengths.split(","):
            series.append((f"{nm} nm exact (default)", colours[nm], "none", 2.2, radii, exact[nm]))
            series.append((f"{nm} nm matched-multipole", colours[nm], "1,3", 1.6, radii, diffusion[nm]))
        series += [(label, colours[nm], dash, width, r, v) for label, nm, dash, width, r, v in figure]
        svg_figure(a.figure, f"{preset}: R(r), exact transport, diffusion and MCML", series)
        print(f"wrote {a.figure}")


if __name__ == "__main__":
    main()
