#!/usr/bin/env python3
"""The exported skin rendered in a measurement scene by pbrt-v4 or Mitsuba 3, beside `skinspec spectrum --mode rte`.

    python3 bench/renderer_validation.py --pbrt /path/to/pbrt [--skinspec build/skinspec] [--preset biospec-moderately]
        [--set KEY=VALUE ...] [--buckets 360:830:10] [--pixels 32] [--spp 1024] [--threads 2] [--seed 1] [--rgb | --rgb-only]
    python3 bench/renderer_validation.py --mitsuba /path/to/mitsuba | --mitsuba-scenes-only [--mitsuba-source DIR] ...
    python3 bench/renderer_validation.py --mitsuba-read --workdir DIR ...   (renders made elsewhere)

Fetches and builds nothing (docs/EXPORT.md, "Checked in the renderers", says how pbrt-v4 was built here); reads
the renders with oiiotool (OpenImageIO's tools, installed by scripts/setup.sh). Run by hand, not by ctest.

The measurement: `skinspec export pbrt|mitsuba` writes the media (every nanometre, so that the renderer's linear
interpolation between samples is the model's own spectrum); this script keeps the media and interfaces and
replaces camera, light and film by an orthographic camera looking straight down at the slab's centre, a uniform
infinite light (constant spectrum) and a spectral film with one box-shaped band per --buckets step (pbrt-v4's
spectral film; Mitsuba 3's specfilm), a box pixel filter and the independent sampler, so that pixels are
independent samples. By reciprocity the radiance seen along the normal under uniform light is the
directional-hemispherical reflectance for normal incidence, specular included: what `spectrum` calls R (geometry
sci). A white Lambertian plane under the same light is the reference: R = skin / white per band; its standard
error is the pixels' standard deviation over sqrt(pixels^2) (pbrt: a pixel's bucket is the mean of the samples whose
wavelength fell in it, 0 with none, so every render takes enough samples that no bucket stays empty). Beside it:
`spectrum --mode rte`'s mean over each band (two-point Gauss-Legendre), the export's own statement of what the
renderer's phase functions change in R (pbrt-v4 takes HG only; Mitsuba 3 tables at 550 nm; per nanometre, averaged
over the band), and (renderer - rte - statement) in combined standard errors with a chi-square over the bands.

--rgb (pbrt) also renders the `--rgb 650,550,450` export and the spectral export with pbrt's RGB film under a D65
uniform light and prints each sRGB channel's ratio (pbrt turns RGB media into smooth spectra of its own).

Mitsuba 3 could not be installed where this was written: --mitsuba-scenes-only writes its measurement scenes and
the commands that render them, --mitsuba-read computes the table from the renders, and --mitsuba-source DIR (a
checkout of mitsuba3) checks every plugin and parameter the scenes use against its sources.
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
import xml.etree.ElementTree as ET

ROOT = pathlib.Path(__file__).resolve().parent.parent


def run(command, cwd=None):
    done = subprocess.run(command, cwd=cwd, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"renderer_validation: {' '.join(map(str, command))} failed ({done.returncode}):\n{done.stderr.strip()[-800:]}")
    return done.stdout


class Bands:
    """Box-shaped bands FROM:TO:STEP nm inside 360-830 nm (what both renderers sample)."""

    def __init__(self, text):
        lo, hi, step = (float(x) for x in text.split(":"))
        self.count = int(round((hi - lo) / step))
        if self.count < 1 or abs(lo + self.count * step - hi) > 1e-9 or lo < 360 or hi > 830:
            sys.exit(f"--buckets {text}: band edges FROM:TO:STEP inside 360-830 nm, TO - FROM a multiple of STEP")
        self.lo, self.hi, self.step = lo, hi, step
        self.centres = [lo + (i + 0.5) * step for i in range(self.count)]
        self.half = step / 2.0


def channel_stats(exr):
    """Per channel (in file order) the mean and standard deviation over the pixels, by oiiotool."""
    text = run(["oiiotool", "--stats", str(exr)])
    avg = re.search(r"Stats Avg: ([^(]*)", text).group(1).split()
    std = re.search(r"Stats StdDev: ([^(]*)", text).group(1).split()
    return [float(a) for a in avg], [float(s) for s in std]


def overrides(args):
    return [x for s in args.set for x in ("--set", s)]


def export(args, renderer, work, name, extra=()):
    """`skinspec export` at 1 nm over the bands; its --json report."""
    return json.loads(run([args.skinspec, "export", renderer, "--preset", args.preset, *overrides(args), *extra,
                           "-o", str(work / name), "--overwrite", "--json"]))


def rte_band_means(args, bands):
    """spectrum --mode rte's mean of R over each band by two-point Gauss-Legendre (exact for cubics), with its error."""
    nodes = [c + sign * bands.half / math.sqrt(3.0) for c in bands.centres for sign in (-1.0, 1.0)]
    rte = json.loads(run([args.skinspec, "spectrum", "--mode", "rte", "--preset", args.preset, *overrides(args),
                          "--wavelengths", ",".join(f"{x:.6f}" for x in nodes), "--stderr", str(args.rte_stderr),
                          "--seed", str(args.seed), "--json"]))["results"][0]
    means = [(rte["R"][2 * i] + rte["R"][2 * i + 1]) / 2.0 for i in range(bands.count)]
    errors = [math.hypot(rte["R_stderr"][2 * i], rte["R_stderr"][2 * i + 1]) / 2.0 for i in range(bands.count)]
    return means, errors


def compare(args, bands, report, skin_exr, white_exr, first_band_channel, title):
    skin_avg, skin_std = channel_stats(skin_exr)
    white_avg, _ = channel_stats(white_exr)
    rte, rte_err = rte_band_means(args, bands)
    stated_per_nm = dict(zip(report["wavelengths_nm"], report["phase_approximation"]["R_difference"]))
    n = args.pixels * args.pixels
    approx = report["phase_approximation"]
    print(f"{args.preset} {' '.join(args.set)}: {title} ({args.pixels}x{args.pixels} px, {args.spp} spp) against spectrum --mode rte")
    print(f"export's statement: phase functions as the renderer takes them change R by at most "
          f"{approx['largest_R_difference']:+.4f} (at {approx['at_nm']:g} nm)")
    print(f"{'nm':>7} {'R':>9} {'+-':>7} {'rte R':>9} {'+-':>7} {'diff':>8} {'stated':>8} {'sigmas':>7}")
    worst, chi2 = 0.0, 0.0
    for i, nm in enumerate(bands.centres):
        channel = first_band_channel + i
        r = skin_avg[channel] / white_avg[channel]
        s = skin_std[channel] / white_avg[channel] / math.sqrt(n)
        inside = [d for w, d in stated_per_nm.items() if nm - bands.half <= w <= nm + bands.half]
        stated = sum(inside) / len(inside)
        sigmas = (r - rte[i] - stated) / math.hypot(s, rte_err[i])
        worst = max(worst, abs(sigmas))
        chi2 += sigmas * sigmas
        print(f"{nm:7.1f} {r:9.4f} {s:7.4f} {rte[i]:9.4f} {rte_err[i]:7.4f} {r - rte[i]:+8.4f} {stated:+8.4f} {sigmas:+7.2f}")
    # P(chi^2_k > chi2) by the Wilson-Hilferty cube-root normal approximation (Johnson, Kotz & Balakrishnan 1994,
    # Eq. 18.24): the bands are independent estimates, so chi2 tests them together.
    k = bands.count
    z = ((chi2 / k) ** (1.0 / 3.0) - (1.0 - 2.0 / (9.0 * k))) / math.sqrt(2.0 / (9.0 * k))
    print(f"sigmas: (renderer - rte - stated) / combined standard error; largest {worst:.2f} over {k} bands; "
          f"chi-square {chi2:.1f} for {k} degrees of freedom (p = {0.5 * math.erfc(z / math.sqrt(2.0)):.2f})")


# pbrt-v4 -------------------------------------------------------------------------------------------------------


def pbrt_world(scene_text):
    """The exported scene's world (media, interfaces, bottom), without its light."""
    world = scene_text[scene_text.index("WorldBegin") + len("WorldBegin"):]
    return "\n".join(line for line in world.splitlines() if not line.startswith("LightSource"))


def pbrt_header(film, spp, pixels, light):
    return f"""LookAt 0 0 10  0 0 0  0 1 0
Camera "orthographic" "float screenwindow" [ -0.5 0.5 -0.5 0.5 ]
Sampler "independent" "integer pixelsamples" [ {spp} ]
Integrator "volpath" "integer maxdepth" [ 100000 ]
PixelFilter "box" "float xradius" [ 0.5 ] "float yradius" [ 0.5 ]
{film} "integer xresolution" [ {pixels} ] "integer yresolution" [ {pixels} ]
WorldBegin
{light}
"""


def pbrt_render(args, scene):
    run([args.pbrt, "--nthreads", str(args.threads), "--seed", str(args.seed), "--quiet", scene.name], cwd=scene.parent)


def pbrt_spectral(args, bands, work):
    report = export(args, "pbrt", work, "skin.pbrt", ["--wavelengths", f"{bands.lo:g}:{bands.hi:g}:1"])
    film = (f'Film "spectral" "string filename" [ "{{}}" ] "integer nbuckets" [ {bands.count} ] "float lambdamin" '
            f'[ {bands.lo} ] "float lambdamax" [ {bands.hi} ] "bool savefp16" false')
    light = 'LightSource "infinite" "spectrum L" [ 360 1 830 1 ]'
    skin, white = work / "measure_skin.pbrt", work / "measure_white.pbrt"
    skin.write_text(pbrt_header(film.format("measure_skin.exr"), args.spp, args.pixels, light) + pbrt_world((work / "skin.pbrt").read_text()))
    white.write_text(pbrt_header(film.format("measure_white.exr"), 1024, 4, light)
                     + 'Material "diffuse" "spectrum reflectance" [ 360 1 830 1 ]\nShape "disk" "float radius" [ 1000 ]\n')
    pbrt_render(args, skin)
    pbrt_render(args, white)
    compare(args, bands, report, work / "measure_skin.exr", work / "measure_white.exr", 3, "pbrt-v4")  # R, G, B, buckets


def pbrt_rgb(args, work):
    film = 'Film "rgb" "string filename" [ "{}" ] "bool savefp16" false'
    light = 'LightSource "infinite" "spectrum L" "stdillum-D65"'
    values = {}
    for name, extra in (("spectral", []), ("rgb", ["--rgb", "650,550,450"])):
        export(args, "pbrt", work, f"{name}.pbrt", extra)
        scene = work / f"measure_{name}.pbrt"
        scene.write_text(pbrt_header(film.format(f"measure_{name}.exr"), args.spp, args.pixels, light)
                         + pbrt_world((work / f"{name}.pbrt").read_text()))
        pbrt_render(args, scene)
        avg, std = channel_stats(work / f"measure_{name}.exr")
        values[name] = (avg[:3], [s / math.sqrt(args.pixels * args.pixels) for s in std[:3]])
    print("sRGB (linear) of the slab under D65: spectral export | --rgb export | ratio")
    for c, label in enumerate("RGB"):
        a, sa = values["spectral"][0][c], values["spectral"][1][c]
        b, sb = values["rgb"][0][c], values["rgb"][1][c]
        print(f"  {label}: {a:.4f} +- {sa:.4f} | {b:.4f} +- {sb:.4f} | {b / a:.3f}")


# Mitsuba 3 -----------------------------------------------------------------------------------------------------


def mitsuba_band_name(nm):
    return f"b{nm * 10:05.0f}"  # channels come out in alphabetical order: zero-padded tenths of nm keep them in order


def mitsuba_measurement(scene, bands, spp, pixels, seed, exported_world):
    """An orthographic sensor, a specfilm with one box band per bucket, a constant emitter; the exported world."""
    sensor = ET.SubElement(scene, "sensor", type="orthographic")
    transform = ET.SubElement(sensor, "transform", name="to_world")
    ET.SubElement(transform, "scale", x="0.5", y="0.5")  # the camera sees [-1, 1]^2 scaled: 1 mm x 1 mm
    ET.SubElement(transform, "lookat", origin="0, 0, 10", target="0, 0, 0", up="0, 1, 0")
    sampler = ET.SubElement(sensor, "sampler", type="independent")
    ET.SubElement(sampler, "integer", name="sample_count", value=str(spp))
    ET.SubElement(sampler, "integer", name="seed", value=str(seed))
    film = ET.SubElement(sensor, "film", type="specfilm")
    ET.SubElement(film, "integer", name="width", value=str(pixels))
    ET.SubElement(film, "integer", name="height", value=str(pixels))
    ET.SubElement(film, "string", name="component_format", value="float32")
    ET.SubElement(film, "rfilter", type="box")
    for c in bands.centres:
        lo, hi = c - bands.half, c + bands.half
        # A box: 1 inside, 0 a thousandth of a nanometre outside (not below 360 or above 830 nm, Mitsuba's range).
        points = ([f"{lo - 0.001:g}:0"] if lo > 360 else []) + [f"{lo:g}:1", f"{hi:g}:1"] + ([f"{hi + 0.001:g}:0"] if hi < 830 else [])
        ET.SubElement(film, "spectrum", name=mitsuba_band_name(c), value=", ".join(points))
    emitter = ET.SubElement(scene, "emitter", type="constant")
    ET.SubElement(emitter, "spectrum", name="radiance", value="1")
    for element in exported_world:
        scene.append(element)
    return scene


def mitsuba_scenes(args, bands, work):
    report = export(args, "mitsuba", work, "skin.xml", ["--wavelengths", f"{bands.lo:g}:{bands.hi:g}:1"])
    exported = ET.parse(work / "skin.xml").getroot()
    world = [e for e in exported if e.tag not in ("sensor", "emitter")]
    skin = mitsuba_measurement(ET.Element("scene", version=exported.get("version")), bands, args.spp, args.pixels, args.seed, world)
    white_plane = ET.Element("shape", type="rectangle")
    transform = ET.SubElement(white_plane, "transform", name="to_world")
    ET.SubElement(transform, "scale", value="1000")
    bsdf = ET.SubElement(white_plane, "bsdf", type="diffuse")
    ET.SubElement(bsdf, "spectrum", name="reflectance", value="1")
    integrator = [e for e in world if e.tag == "integrator"]
    white = mitsuba_measurement(ET.Element("scene", version=exported.get("version")), bands, 1024, 4, args.seed, integrator + [white_plane])
    for name, tree in (("measure_skin.xml", skin), ("measure_white.xml", white)):
        ET.ElementTree(tree).write(work / name, xml_declaration=True, encoding="utf-8")
    return report, [skin, white]


def mitsuba_check_against_source(trees, source):
    """Every plugin type a scene uses exists in the mitsuba3 sources, and every parameter it sets is named there (in
    the plugin or in its base class, src/render/<kind>.cpp: a shape's interior and exterior media, a sensor's
    to_world)."""
    source = pathlib.Path(source)
    kinds = {"sensor": "sensors", "film": "films", "sampler": "samplers", "rfilter": "rfilters", "emitter": "emitters",
             "integrator": "integrators", "medium": "media", "phase": "phase", "shape": "shapes", "bsdf": "bsdfs"}
    problems, checked = [], 0
    for tree in trees:
        for element in tree.iter():
            if element.tag not in kinds:
                continue
            plugin = source / "src" / kinds[element.tag] / f"{element.get('type')}.cpp"
            if not plugin.exists():
                problems.append(f"{element.tag} type '{element.get('type')}': no {plugin.relative_to(source)}")
                continue
            base = source / "src" / "render" / f"{element.tag}.cpp"
            text = plugin.read_text(errors="replace") + (base.read_text(errors="replace") if base.exists() else "")
            for child in element:
                name = child.get("name")
                if name and child.tag not in kinds and not (element.tag == "film" and child.tag == "spectrum"):
                    checked += 1
                    if f'"{name}"' not in text and f" - {name}" not in text and f"{name}," not in text:
                        problems.append(f"{element.tag} '{element.get('type')}': parameter '{name}' not in {plugin.relative_to(source)}")
    print(f"mitsuba3 sources: {checked} parameters of the measurement scenes checked, "
          + ("all named by their plugins" if not problems else f"{len(problems)} problem(s):\n  " + "\n  ".join(problems)))


def mitsuba(args, bands, work):
    report, trees = mitsuba_scenes(args, bands, work)
    (work / "export.json").write_text(json.dumps(report))
    if args.mitsuba_source:
        mitsuba_check_against_source(trees, args.mitsuba_source)
    commands = [[args.mitsuba or "mitsuba", "-m", "scalar_spectral", "-t", str(args.threads), "-o", f"{name}.exr", f"{name}.xml"]
                for name in ("measure_skin", "measure_white")]
    if args.mitsuba_scenes_only:
        print(f"wrote the measurement scenes in {work}; render them there with\n  "
              + "\n  ".join(" ".join(c) for c in commands)
              + f"\nthen: python3 bench/renderer_validation.py --mitsuba-read --workdir {work} (same --preset, --set, --buckets)")
        return
    for command in commands:
        run(command, cwd=work)
    mitsuba_compare(args, bands, work, report)


def mitsuba_compare(args, bands, work, report):
    # specfilm writes one channel per band, in the bands' (alphabetical) order.
    compare(args, bands, report, work / "measure_skin.exr", work / "measure_white.exr", 0, "Mitsuba 3")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    renderer = parser.add_mutually_exclusive_group(required=True)
    renderer.add_argument("--pbrt", help="a pbrt-v4 executable")
    renderer.add_argument("--mitsuba", help="a Mitsuba 3 executable (variant scalar_spectral)")
    renderer.add_argument("--mitsuba-scenes-only", action="store_true", help="write the Mitsuba 3 scenes and the commands")
    renderer.add_argument("--mitsuba-read", action="store_true", help="compute the table from Mitsuba 3 renders in --workdir")
    parser.add_argument("--mitsuba-source", help="a mitsuba3 source checkout: check the scenes' plugins and parameters")
    parser.add_argument("--skinspec", default=str(ROOT / "build" / "skinspec"))
    parser.add_argument("--preset", default="biospec-moderately")
    parser.add_argument("--set", action="append", default=[], help="KEY=VALUE override for the export and rte (repeatable)")
    parser.add_argument("--buckets", default="360:830:10", help="band edges FROM:TO:STEP nm inside 360-830")
    parser.add_argument("--pixels", type=int, default=32)
    parser.add_argument("--spp", type=int, default=1024)
    parser.add_argument("--threads", type=int, default=os.cpu_count())
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--rte-stderr", type=float, default=0.0005)
    parser.add_argument("--rgb", action="store_true", help="pbrt: also the --rgb export against the spectral one")
    parser.add_argument("--rgb-only", action="store_true", help="pbrt: only the --rgb export against the spectral one")
    parser.add_argument("--workdir", type=pathlib.Path)
    args = parser.parse_args()
    if args.mitsuba_read and not args.workdir:
        sys.exit("--mitsuba-read needs --workdir (the folder with the renders)")
    work = args.workdir or pathlib.Path(tempfile.mkdtemp(prefix="renderer_validation_"))
    work.mkdir(parents=True, exist_ok=True)
    bands = Bands(args.buckets)
    if args.pbrt:
        if not args.rgb_only:
            pbrt_spectral(args, bands, work)
        if args.rgb or args.rgb_only:
            pbrt_rgb(args, work)
    elif args.mitsuba_read:
        mitsuba_compare(args, bands, work, json.loads((work / "export.json").read_text()))
    else:
        mitsuba(args, bands, work)
    print(f"files in {work}")


if __name__ == "__main__":
    main()
