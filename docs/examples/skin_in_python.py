"""A worked example of skinspec from Python (docs/PYTHON.md): spectra for three pigmentations, a melanin sweep
replayed from one set of paths, a fit of a measured-like spectrum, and a plot when matplotlib is installed.

    PYTHONPATH=build/python /usr/bin/python3 docs/examples/skin_in_python.py [OUTPUT_DIR]
"""
import os
import sys
import time

import numpy as np

import skinspec

out_dir = sys.argv[1] if len(sys.argv) > 1 else "."
nm = np.arange(400, 701, 10)

# 1. Three pigmentation levels of the BioSpec skin, each wavelength to a standard error of 0.002.
print("1. spectra of three pigmentations (BioSpec walk, stderr 0.002)")
spectra = {}
for preset in ("biospec-lightly", "biospec-moderately", "biospec-heavily"):
    s = skinspec.spectrum(preset, nm, stderr=0.002, seed=1)
    c = skinspec.color(s.wavelength_nm, s.R)
    spectra[preset] = s
    print(f"   {preset:20s} R(450) {s.R[5]:.3f} +- {s.R_stderr[5]:.3f}  R(650) {s.R[25]:.3f}  "
          f"L*a*b* {c.Lab[0]:5.1f} {c.Lab[1]:5.1f} {c.Lab[2]:5.1f}  sRGB {np.round(c.rgb['sRGB'], 3)}  {s.seconds:.2f} s")

# 2. A melanin sweep: melanosome fraction only changes absorption, so the walk traces its paths once and re-weights
#    them for every value; the arrays come back shaped (values, wavelengths).
print("2. melanin sweep (replayed from one set of paths)")
melanin = np.geomspace(0.01, 0.4, 12)
start = time.monotonic()
sweep = skinspec.spectrum("biospec-moderately", nm, stderr=0.002, vary={"epidermis.melanosome_fraction": melanin})
lab = skinspec.color(sweep.wavelength_nm, sweep.R).Lab
print(f"   {len(melanin)} spectra in {time.monotonic() - start:.2f} s; R shape {sweep.R.shape}")
for f, l in zip(melanin[::3], lab[::3]):
    print(f"   melanosome fraction {f:.3f}: L* {l[0]:5.1f}")
print(f"   colour difference lightest-darkest: CIEDE2000 {skinspec.delta_e2000(lab[0], lab[-1]):.1f}")

# 3. A fit: noisy reflectance of a skin with known melanin and blood, fitted back by the BioSpec walk.
print("3. fit of a noisy spectrum with known parameters")
truth = skinspec.Material("biospec-moderately")
truth.update({"epidermis.melanosome_fraction": 0.08, "papillary_dermis.blood_fraction": 0.02})
measured = skinspec.spectrum(truth, nm, rays=20000, seed=11).R + np.random.default_rng(2).normal(0.0, 0.003, nm.size)
fit = skinspec.fit_spectrum(nm, np.clip(measured, 0.0, 1.0), free=["epidermis.melanosome_fraction", "papillary_dermis.blood_fraction"])
for key, value in fit.parameters.items():
    print(f"   {key:32s} {value:.4f} +- {fit.parameter_stderr[key]:.4f} (true {truth[key]})")
print(f"   RMS {fit.rms:.4f}, CIEDE2000 to the measured colour {fit.delta_e2000:.2f}")

# 4. A plot when matplotlib is there (python3-matplotlib).
try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("4. matplotlib is not installed: no plot")
else:
    fig, ax = plt.subplots(figsize=(6, 4))
    for preset, s in spectra.items():
        rgb = np.clip(skinspec.color(s.wavelength_nm, s.R).rgb["sRGB"], 0, 1)
        ax.plot(s.wavelength_nm, s.R, color=rgb, label=preset)
        ax.fill_between(s.wavelength_nm, s.R - 2 * s.R_stderr, s.R + 2 * s.R_stderr, color=rgb, alpha=0.3)
    ax.set_xlabel("wavelength (nm)")
    ax.set_ylabel("reflectance R")
    ax.legend()
    path = os.path.join(out_dir, "skin_in_python.png")
    fig.savefig(path, dpi=120)
    print(f"4. wrote {path}")
