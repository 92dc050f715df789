#!/usr/bin/env python3
"""The exported skin rendered by pbrt-v4 in a measurement scene, beside `skinspec spectrum --mode rte` (issue 37).

    python3 bench/pbrt_validation.py --pbrt /path/to/pbrt [--skinspec build/skinspec] [--preset biospec-moderately]
        [--set KEY=VALUE ...] [--buckets 360:830:10] [--pixels 24] [--spp 1024] [--threads 2] [--rgb] [--workdir DIR]

Fetches and builds nothing (docs/EXPORT.md, "Checked in pbrt-v4", says how pbrt-v4 was built here). Needs oiiotool
(OpenImageIO's tools, installed by scripts/setup.sh) to read the renders.

The measurement: `skinspec export pbrt` writes the media (every nanometre, so that pbrt's linear interpolation
between samples is the model's own spectrum); this script keeps the media and interfaces and replaces the camera,
light and film by an orthographic camera looking straight down at the slab's centre, a uniform infinite light
(constant spectrum) and pbrt-v4's spectral film (one bucket per --buckets step, box pixel filter, independent
sampler, so that pixels are independent samples). By reciprocity the radiance seen along the normal under uniform
light is the directional-hemispherical reflectance for normal incidence, specular included: what `spectrum` calls R
(geometry sci). A white Lambertian disk under the same light is the reference: R = skin / white per bucket (a
pixel's bucket is the mean of the samples whose wavelength fell in it, 0 with none, so every render takes enough
samples per pixel that no bucket stays empty); its standard error is the pixels' standard deviation over
sqrt(pixels^2). Beside it: `spectrum --mode rte`'s mean over each bucket (two-point Gauss-Legendre), the export's
own statement of what pbrt's phase functions change in R (pbrt-v4 takes HG only: the measured profiles become HG
of their mean cosine at 550 nm; per nanometre, averaged over the bucket), and (pbrt - rte - statement) in combined
standard errors with a chi-square over the buckets: the renderer's transport and the statement are checked together.

--rgb also renders the `--rgb 650,550,450` export and the spectral export with pbrt's RGB film under a D65
uniform light and prints each sRGB channel's ratio (pbrt turns RGB media into smooth spectra of its own).
"""
import argparse
import json
import math
import os
import pathlib
import re
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
HEADER_END = "WorldBegin"


def run(command, cwd=None):
    done = subprocess.run(command, cwd=cwd, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"pbrt_validation: {' '.join(map(str, command))} failed ({done.returncode}):\n{done.stderr.strip()[-800:]}")
    return done.stdout


def bucket_grid(text):
    lo, hi, step = (float(x) for x in text.split(":"))
    count = int(round((hi - lo) / step))
    if count < 1 or abs(lo + count * step - hi) > 1e-9 or lo < 360 or hi > 830:
        sys.exit(f"--buckets {text}: bucket edges FROM:TO:STEP inside pbrt-v4's 360-830 nm, TO - FROM a multiple of STEP")
    return lo, hi, count, [lo + (i + 0.5) * step for i in range(count)]


def world_of(scene_text):
    """The exported scene's world (media, interfaces, bottom), without its light."""
    world = scene_text[scene_text.index(HEADER_END) + len(HEADER_END):]
    return "\n".join(line for line in world.splitlines() if not line.startswith("LightSource"))


def measurement_header(film, spp, pixels, light):
    return f"""LookAt 0 0 10  0 0 0  0 1 0
Camera "orthographic" "float screenwindow" [ -0.5 0.5 -0.5 0.5 ]
Sampler "independent" "integer pixelsamples" [ {spp} ]
Integrator "volpath" "integer maxdepth" [ 100000 ]
PixelFilter "box" "float xradius" [ 0.5 ] "float yradius" [ 0.5 ]
{film} "integer xresolution" [ {pixels} ] "integer yresolution" [ {pixels} ]
WorldBegin
{light}
"""


def channel_stats(exr):
    """Per channel (in file order) the mean and standard deviation over the pixels, by oiiotool."""
    text = run(["oiiotool", "--stats", str(exr)])
    avg = re.search(r"Stats Avg: ([^(]*)", text).group(1).split()
    std = re.search(r"Stats StdDev: ([^(]*)", text).group(1).split()
    return [float(a) for a in avg], [float(s) for s in std]


def render(pbrt, scene, threads, seed):
    run([pbrt, "--nthreads", str(threads), "--seed", str(seed), "--quiet", scene.name], cwd=scene.parent)


def spectral_check(args, work):
    lo, hi, count, centres = bucket_grid(args.buckets)
    sets = [x for s in args.set for x in ("--set", s)]
    # Media every nanometre, so that pbrt's linear interpolation between samples is the model's own spectrum.
    export = json.loads(run([args.skinspec, "export", "pbrt", "--preset", args.preset, *sets, "--wavelengths",
                             f"{lo:g}:{hi:g}:1", "-o", str(work / "skin.pbrt"), "--overwrite", "--json"]))
    film = (f'Film "spectral" "string filename" [ "{{}}" ] "integer nbuckets" [ {count} ] "float lambdamin" [ {lo} ] '
            f'"float lambdamax" [ {hi} ] "bool savefp16" false')
    light = 'LightSource "infinite" "spectrum L" [ 360 1 830 1 ]'
    world = world_of((work / "skin.pbrt").read_text())
    skin = work / "measure_skin.pbrt"
    skin.write_text(measurement_header(film.format("measure_skin.exr"), args.spp, args.pixels, light) + world)
    white = work / "measure_white.pbrt"
    white.write_text(measurement_header(film.format("measure_white.exr"), 1024, 4, light)
                     + 'Material "diffuse" "spectrum reflectance" [ 360 1 830 1 ]\nShape "disk" "float radius" [ 1000 ]\n')
    render(args.pbrt, skin, args.threads, args.seed)
    render(args.pbrt, white, args.threads, args.seed)
    skin_avg, skin_std = channel_stats(work / "measure_skin.exr")
    white_avg, _ = channel_stats(work / "measure_white.exr")
    # A bucket's mean of R by two-point Gauss-Legendre (exact for cubics): rte at c -+ h / sqrt(3), h the half width.
    half = (hi - lo) / count / 2.0
    nodes = [c + sign * half / math.sqrt(3.0) for c in centres for sign in (-1.0, 1.0)]
    rte = json.loads(run([args.skinspec, "spectrum", "--mode", "rte", "--preset", args.preset, *sets, "--wavelengths",
                          ",".join(f"{x:.6f}" for x in nodes), "--stderr", str(args.rte_stderr), "--seed", str(args.seed), "--json"]))
    result = rte["results"][0]
    rte_mean = [(result["R"][2 * i] + result["R"][2 * i + 1]) / 2.0 for i in range(count)]
    rte_stderr = [math.hypot(result["R_stderr"][2 * i], result["R_stderr"][2 * i + 1]) / 2.0 for i in range(count)]
    n = args.pixels * args.pixels
    print(f"{args.preset} {' '.join(args.set)}: pbrt-v4 ({args.pixels}x{args.pixels} px, {args.spp} spp) against spectrum --mode rte")
    approx = export["phase_approximation"]
    print(f"export's statement: phase functions as pbrt takes them change R by at most {approx['largest_R_difference']:+.4f} "
          f"(at {approx['at_nm']:g} nm)")
    # The export's own statement per nanometre, averaged over each bucket: what pbrt's phase functions change.
    stated_per_nm = dict(zip(export["wavelengths_nm"], export["phase_approximation"]["R_difference"]))
    stated = []
    for c in centres:
        inside = [d for nm, d in stated_per_nm.items() if c - half <= nm <= c + half]
        stated.append(sum(inside) / len(inside))
    print(f"{'nm':>7} {'pbrt R':>9} {'+-':>7} {'rte R':>9} {'+-':>7} {'diff':>8} {'stated':>8} {'sigmas':>7}")
    worst, chi2 = 0.0, 0.0
    for i, nm in enumerate(centres):
        channel = 3 + i  # R, G, B, then the buckets
        r = skin_avg[channel] / white_avg[channel]
        s = skin_std[channel] / white_avg[channel] / math.sqrt(n)
        r_rte, s_rte = rte_mean[i], rte_stderr[i]
        sigmas = (r - r_rte - stated[i]) / math.hypot(s, s_rte)
        worst = max(worst, abs(sigmas))
        chi2 += sigmas * sigmas
        print(f"{nm:7.1f} {r:9.4f} {s:7.4f} {r_rte:9.4f} {s_rte:7.4f} {r - r_rte:+8.4f} {stated[i]:+8.4f} {sigmas:+7.2f}")
    # P(chi^2_k > chi2) by the Wilson-Hilferty cube-root normal approximation (Johnson, Kotz & Balakrishnan 1994,
    # Eq. 18.24): the buckets are independent, so chi2 tests them together.
    z = ((chi2 / count) ** (1.0 / 3.0) - (1.0 - 2.0 / (9.0 * count))) / math.sqrt(2.0 / (9.0 * count))
    p = 0.5 * math.erfc(z / math.sqrt(2.0))
    print(f"sigmas: (pbrt - rte - stated) / combined standard error; largest {worst:.2f} over {count} buckets; "
          f"chi-square {chi2:.1f} for {count} degrees of freedom (p = {p:.2f})")


def rgb_check(args, work):
    sets = [x for s in args.set for x in ("--set", s)]
    film = 'Film "rgb" "string filename" [ "{}" ] "bool savefp16" false'
    light = 'LightSource "infinite" "spectrum L" "stdillum-D65"'
    values = {}
    for name, extra in (("spectral", []), ("rgb", ["--rgb", "650,550,450"])):
        run([args.skinspec, "export", "pbrt", "--preset", args.preset, *sets, *extra, "-o", str(work / f"{name}.pbrt"), "--overwrite"])
        scene = work / f"measure_{name}.pbrt"
        scene.write_text(measurement_header(film.format(f"measure_{name}.exr"), args.spp, args.pixels, light)
                         + world_of((work / f"{name}.pbrt").read_text()))
        render(args.pbrt, scene, args.threads, args.seed)
        avg, std = channel_stats(work / f"measure_{name}.exr")
        values[name] = (avg[:3], [s / math.sqrt(args.pixels * args.pixels) for s in std[:3]])
    print("sRGB (linear) of the slab under D65: spectral export | --rgb export | ratio")
    for c, label in enumerate("RGB"):
        a, sa = values["spectral"][0][c], values["spectral"][1][c]
        b, sb = values["rgb"][0][c], values["rgb"][1][c]
        print(f"  {label}: {a:.4f} +- {sa:.4f} | {b:.4f} +- {sb:.4f} | {b / a:.3f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pbrt", required=True)
    parser.add_argument("--skinspec", default=str(ROOT / "build" / "skinspec"))
    parser.add_argument("--preset", default="biospec-moderately")
    parser.add_argument("--set", action="append", default=[], help="KEY=VALUE override for both (repeatable)")
    parser.add_argument("--buckets", default="360:830:10", help="bucket edges FROM:TO:STEP nm inside 360-830")
    parser.add_argument("--pixels", type=int, default=24)
    parser.add_argument("--spp", type=int, default=1024)
    parser.add_argument("--threads", type=int, default=os.cpu_count())
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--rte-stderr", type=float, default=0.001)
    parser.add_argument("--rgb", action="store_true", help="also the --rgb export against the spectral one")
    parser.add_argument("--workdir", type=pathlib.Path)
    args = parser.parse_args()
    work = args.workdir or pathlib.Path(tempfile.mkdtemp(prefix="pbrt_validation_"))
    work.mkdir(parents=True, exist_ok=True)
    spectral_check(args, work)
    if args.rgb:
        rgb_check(args, work)
    print(f"files in {work}")


if __name__ == "__main__":
    main()
