#!/usr/bin/env python3
"""Generate skinspec's own data tables in data/ from the raw public sources in ../shared/data-sources.

Usage: scripts/make_data.py [--sources DIR] [--reference DIR] [--out DIR]

Every table is written in the one skinspec table format (docs/DATA_FORMAT.md):

    # skinspec-table: 1
    # title: ...
    # source: ...                 provenance of the raw numbers
    # generated_by: scripts/make_data.py
    # units: column [unit]; ...
    # domain_nm: first last        tabulated range
    # outside_domain: error|zero|hold
    # note: ...                    (optional, repeatable)
    wavelength_nm,column,...
    360,...

The generated files are committed, so a fresh clone needs nothing from ../shared. Only the Python
standard library is used.
"""

import argparse
import math
import pathlib
import sys

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent
GENERATOR = "scripts/make_data.py"


def read_columns(path, skip_header=True, delimiter=None):
    """Rows of floats from a whitespace- or comma-separated file; '#' lines and a text header skipped."""
    rows = []
    for line in pathlib.Path(path).read_text(encoding="utf-8").splitlines():
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        fields = line.split(delimiter) if delimiter else line.replace(",", " ").split()
        try:
            rows.append([float(f) for f in fields])
        except ValueError:
            if rows or not skip_header:
                raise
    return rows


def fmt(value):
    return f"{value:.10g}"


def write_table(path, title, source, units, columns, rows, outside, notes=()):
    lo, hi = rows[0][0], rows[-1][0]
    lines = [
        "# skinspec-table: 1",
        f"# title: {title}",
        f"# source: {source}",
        f"# generated_by: {GENERATOR}",
        f"# units: {units}",
        f"# domain_nm: {fmt(lo)} {fmt(hi)}",
        f"# outside_domain: {outside}",
    ]
    lines += [f"# note: {n}" for n in notes]
    lines.append(",".join(columns))
    lines += [",".join(fmt(v) for v in row) for row in rows]
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    print(f"wrote {path.relative_to(ROOT)} ({len(rows)} rows)")


def window(rows, lo=360, hi=830):
    return [r for r in rows if lo <= r[0] <= hi]


# --- CIE observers and illuminants -----------------------------------------------------------------

def make_cie(src, out):
    cmfs = window(read_columns(src / "cie_cmfs_2deg_10deg.txt"))
    cie_source = ("CIE colour matching functions, CIE 015:2018 / CIE data sets (CC BY-SA 4.0, "
                  "DOI 10.25039/CIE.DS.xvudnb9b); raw file cie_cmfs_2deg_10deg.txt")
    write_table(out / "cie" / "observer_cie1931_2deg.csv",
                "CIE 1931 2-degree standard observer colour matching functions",
                cie_source, "wavelength_nm [nm]; xbar, ybar, zbar [dimensionless]",
                ["wavelength_nm", "xbar", "ybar", "zbar"],
                [[r[0], r[1], r[2], r[3]] for r in cmfs], "zero",
                ["zero outside 360-830 nm, where the CIE tables end (values there are below 1e-4 of peak)"])
    write_table(out / "cie" / "observer_cie1964_10deg.csv",
                "CIE 1964 10-degree supplementary standard observer colour matching functions",
                cie_source, "wavelength_nm [nm]; xbar, ybar, zbar [dimensionless]",
                ["wavelength_nm", "xbar", "ybar", "zbar"],
                [[r[0], r[4], r[5], r[6]] for r in cmfs], "zero",
                ["zero outside 360-830 nm, where the CIE tables end (values there are below 1e-4 of peak)"])
    for name, raw in (("d65", "cie_illuminant_d65.csv"), ("d50", "cie_illuminant_d50.csv"),
                      ("a", "cie_illuminant_a.csv")):
        rows = window(read_columns(src / raw))
        write_table(out / "cie" / f"illuminant_{name}.csv",
                    f"CIE standard illuminant {name.upper()} relative spectral power distribution",
                    f"CIE data sets (CC BY-SA 4.0); raw file {raw}, cut to 360-830 nm",
                    "wavelength_nm [nm]; power [relative, 100 at 560 nm]",
                    ["wavelength_nm", "power"], rows, "error")
    write_table(out / "cie" / "illuminant_e.csv",
                "CIE equal-energy illuminant E", "definition (CIE 015:2018 Sec. 11.1): constant power",
                "wavelength_nm [nm]; power [relative, 100 everywhere]",
                ["wavelength_nm", "power"], [[float(w), 100.0] for w in range(360, 831)], "error")


# --- OpenColorIO config --------------------------------------------------------------------------------

D65_XY = (0.3127, 0.3290)          # ITU-R BT.709-6 / IEC 61966-2-1 white
ACES_WHITE_XY = (0.32168, 0.33767)  # SMPTE ST 2065-1
BRADFORD = [[0.8951, 0.2664, -0.1614], [-0.7502, 1.7135, 0.0367], [0.0389, -0.0685, 1.0296]]

PRIMARIES = {  # (red, green, blue) xy chromaticities and white xy
    "Rec.709": (((0.64, 0.33), (0.30, 0.60), (0.15, 0.06)), D65_XY),        # ITU-R BT.709-6
    "P3-D65": (((0.680, 0.320), (0.265, 0.690), (0.150, 0.060)), D65_XY),   # SMPTE EG 432-1
    "Rec.2020": (((0.708, 0.292), (0.170, 0.797), (0.131, 0.046)), D65_XY),  # ITU-R BT.2020-2
    "AP1": (((0.713, 0.293), (0.165, 0.830), (0.128, 0.044)), ACES_WHITE_XY),  # SMPTE ST 2065-1 / S-2014-004
    "AP0": (((0.7347, 0.2653), (0.0, 1.0), (0.0001, -0.0770)), ACES_WHITE_XY),  # SMPTE ST 2065-1
}


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def matvec(a, v):
    return [sum(a[i][k] * v[k] for k in range(3)) for i in range(3)]


def inverse(m):
    (a, b, c), (d, e, f), (g, h, i) = m
    det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    return [[(e * i - f * h) / det, (c * h - b * i) / det, (b * f - c * e) / det],
            [(f * g - d * i) / det, (a * i - c * g) / det, (c * d - a * f) / det],
            [(d * h - e * g) / det, (b * g - a * h) / det, (a * e - b * d) / det]]


def xy_to_xyz(xy):
    x, y = xy
    return [x / y, 1.0, (1.0 - x - y) / y]


def rgb_to_xyz(name):
    """SMPTE RP 177-1993 Eq. 3-6: RGB -> XYZ from primaries and white, white mapped to Y = 1."""
    prims, white = PRIMARIES[name]
    p = [[xy_to_xyz(c)[row] for c in prims] for row in range(3)]
    s = matvec(inverse(p), xy_to_xyz(white))
    return [[p[r][c] * s[c] for c in range(3)] for r in range(3)]


def bradford(src_xy, dst_xy):
    """von Kries adaptation in the Bradford cone space (Lam 1985; CIE 160:2004 Sec. 5)."""
    src = matvec(BRADFORD, xy_to_xyz(src_xy))
    dst = matvec(BRADFORD, xy_to_xyz(dst_xy))
    scale = [[dst[i] / src[i] if i == j else 0.0 for j in range(3)] for i in range(3)]
    return matmul(inverse(BRADFORD), matmul(scale, BRADFORD))


def to_xyz_d65(name):
    m = rgb_to_xyz(name)
    white = PRIMARIES[name][1]
    return m if white == D65_XY else matmul(bradford(white, D65_XY), m)


def ocio_matrix(m):
    flat = [m[0][0], m[0][1], m[0][2], 0, m[1][0], m[1][1], m[1][2], 0,
            m[2][0], m[2][1], m[2][2], 0, 0, 0, 0, 1]
    return "[" + ", ".join(f"{v:.12g}" for v in flat) + "]"


def make_ocio(out):
    def space(name, family, encoding, description, to_ref, isdata=False):
        body = [f"  - !<ColorSpace>",
                f"    name: {name}",
                f"    family: {family}",
                f"    equalitygroup: \"\"",
                f"    bitdepth: 32f",
                f"    description: \"{description}\"",
                f"    isdata: {'true' if isdata else 'false'}",
                f"    encoding: {encoding}",
                f"    allocation: uniform"]
        if to_ref:
            body.append(f"    to_scene_reference: {to_ref}")
        return "\n".join(body)

    def linear(prim):
        return f"!<MatrixTransform> {{matrix: {ocio_matrix(to_xyz_d65(prim))}}}"

    def encoded(prim):
        curve = "!<ExponentWithLinearTransform> {gamma: 2.4, offset: 0.055}"
        return f"!<GroupTransform> {{children: [{curve}, {linear(prim)}]}}"

    spaces = [
        space("CIE-XYZ-D65", "Reference", "scene-linear",
              "CIE 1931 XYZ, D65 white at Y = 1; the reference space of this config", None),
        space("Linear Rec.709", "Scene-linear", "scene-linear",
              "Linear ITU-R BT.709 primaries, D65 white (linear sRGB)", linear("Rec.709")),
        space("sRGB", "Display-encoded", "sdr-video",
              "IEC 61966-2-1 sRGB: BT.709 primaries, D65, piecewise sRGB encoding", encoded("Rec.709")),
        space("Linear Display P3", "Scene-linear", "scene-linear",
              "Linear P3 primaries, D65 white (SMPTE EG 432-1)", linear("P3-D65")),
        space("Display P3", "Display-encoded", "sdr-video",
              "Apple Display P3: P3 primaries, D65, sRGB piecewise encoding", encoded("P3-D65")),
        space("Linear Rec.2020", "Scene-linear", "scene-linear",
              "Linear ITU-R BT.2020 primaries, D65 white", linear("Rec.2020")),
        space("ACEScg", "ACES", "scene-linear",
              "ACEScg: AP1 primaries, ACES white; Bradford-adapted to and from the D65 reference",
              linear("AP1")),
        space("ACES2065-1", "ACES", "scene-linear",
              "ACES2065-1: AP0 primaries, ACES white; Bradford-adapted to and from the D65 reference",
              linear("AP0")),
        space("Raw", "Utility", "data", "Data: no colour transform", None, isdata=True),
    ]
    text = f"""# skinspec OpenColorIO config. Generated by {GENERATOR}; do not edit by hand.
# Reference space: CIE-XYZ-D65 (CIE 1931 XYZ, white D65 at Y = 1). Matrices are computed from the published
# primaries and white points (SMPTE RP 177-1993); spaces with the ACES white are Bradford-adapted to D65.
ocio_profile_version: 2

environment: {{}}
search_path: ""
strictparsing: true
luma: [0.2126, 0.7152, 0.0722]
description: skinspec colour management (CIE-XYZ-D65 reference)

roles:
  aces_interchange: ACES2065-1
  cie_xyz_d65_interchange: CIE-XYZ-D65
  color_picking: sRGB
  color_timing: sRGB
  compositing_log: sRGB
  data: Raw
  default: sRGB
  matte_paint: sRGB
  reference: CIE-XYZ-D65
  rendering: Linear Rec.709
  scene_linear: Linear Rec.709
  texture_paint: sRGB

file_rules:
  - !<Rule> {{name: Default, colorspace: default}}

displays:
  sRGB:
    - !<View> {{name: Standard, colorspace: sRGB}}
    - !<View> {{name: Raw, colorspace: Raw}}
  Display P3:
    - !<View> {{name: Standard, colorspace: Display P3}}
    - !<View> {{name: Raw, colorspace: Raw}}

active_displays: [sRGB, Display P3]
active_views: [Standard, Raw]

colorspaces:
""" + "\n\n".join(spaces) + "\n"
    path = out / "ocio" / "config.ocio"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    print(f"wrote {path.relative_to(ROOT)}")

    # Published primaries and white of the RGB spaces, for image headers (OpenEXR 'chromaticities').
    lines = [f"# Chromaticities (CIE 1931 xy) of the RGB spaces of config.ocio. Generated by {GENERATOR}.",
             "# red, green, blue, white as published (ACES spaces keep the ACES white: values are Bradford-adapted",
             "# to the D65 reference inside the config, as the ACES convention expects).", ""]
    for space, prim in (("Linear Rec.709", "Rec.709"), ("sRGB", "Rec.709"), ("Linear Display P3", "P3-D65"),
                        ("Display P3", "P3-D65"), ("Linear Rec.2020", "Rec.2020"), ("ACEScg", "AP1"),
                        ("ACES2065-1", "AP0")):
        (r, g, b), w = PRIMARIES[prim]
        flat = [r[0], r[1], g[0], g[1], b[0], b[1], w[0], w[1]]
        lines.append(f'"{space}" = [{", ".join(f"{v:g}" for v in flat)}]')
    chroma = out / "ocio" / "chromaticities.toml"
    chroma.write_text("\n".join(lines) + "\n", encoding="utf-8")
    print(f"wrote {chroma.relative_to(ROOT)}")


# --- chromophores and tissue optics ---------------------------------------------------------------------

def clamp_negative(rows, column=1):
    count = sum(1 for r in rows if r[column] < 0.0)
    return [r[:column] + [max(r[column], 0.0)] + r[column + 1:] for r in rows], count


TAIL_START_NM = 250  # the hyperspectral range (docs/HYPERSPECTRAL.md)
TAIL_END_NM = 2500
TAIL_STEP_NM = 10
MELANIN_TAIL_FIT_NM = (600, 830)
HEMOGLOBIN_TAIL_FIT_NM = (960, 1000)
SALOMATINA_SHORT_FIT_NM = (369, 500)
SALOMATINA_LONG_FIT_NM = (500, 1610)


def least_squares_line(xs, ys):
    """Intercept and slope of y = a + b x."""
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    return my - slope * mx, slope


def log_log_fit(rows, fit_nm):
    """ln A and slope of ln(value) = ln A + slope ln(lambda), least squares over the rows inside fit_nm."""
    fit = [r for r in rows if fit_nm[0] <= r[0] <= fit_nm[1]]
    return least_squares_line([math.log(r[0]) for r in fit], [math.log(r[1]) for r in fit])


def tail_wavelengths(after_nm, end_nm):
    first = (int(after_nm) // TAIL_STEP_NM + 1) * TAIL_STEP_NM
    return [float(w) for w in range(first, end_nm + 1, TAIL_STEP_NM)]


def with_power_law_tail(rows, fit_nm, end_nm):
    """rows, then eps = A lambda^-b above them: A, b by least squares in log-log over fit_nm."""
    log_a, slope = log_log_fit(rows, fit_nm)
    tail = [[w, math.exp(log_a + slope * math.log(w))] for w in tail_wavelengths(rows[-1][0], end_nm)]
    return rows + tail, f"{math.exp(log_a):.4g} lambda^{slope:.4f}"


def with_exponential_tail(rows, fit_nm, end_nm):
    """rows, then each column continued as eps(last) exp(-(lambda - last) / L), L by least squares of ln eps over fit_nm."""
    fit = [r for r in rows if fit_nm[0] <= r[0] <= fit_nm[1]]
    last = rows[-1]
    lengths = []
    for c in range(1, len(last)):
        _, slope = least_squares_line([r[0] for r in fit], [math.log(r[c]) for r in fit])
        lengths.append(-1.0 / slope)
    tail = [[w] + [last[c] * math.exp(-(w - last[0]) / lengths[c - 1]) for c in range(1, len(last))]
            for w in tail_wavelengths(last[0], end_nm)]
    return rows + tail, [f"column {c}: L = {lengths[c - 1]:.1f} nm" for c in range(1, len(last))]


def with_anchored_power_law_tails(rows, short_fit_nm, long_fit_nm, start_nm, end_nm):
    """rows with a power law a (lambda/500)^-b below and above, b by least squares in log-log over each fit range,
    a so that the law meets the table's end value (continuous)."""
    laws = []

    def law(fit_nm, anchor):
        _, slope = log_log_fit(rows, fit_nm)
        amplitude = anchor[1] / (anchor[0] / 500.0) ** slope
        laws.append(f"{fit_nm[0]}-{fit_nm[1]} nm: a = {amplitude:.4g} mm^-1, b = {-slope:.4f}")
        return lambda w: amplitude * (w / 500.0) ** slope

    below, above = law(short_fit_nm, rows[0]), law(long_fit_nm, rows[-1])
    head = [[float(w), below(w)] for w in range(start_nm, int(math.ceil(rows[0][0])), TAIL_STEP_NM) if w < rows[0][0]]
    tail = [[w, above(w)] for w in tail_wavelengths(rows[-1][0], end_nm)]
    return head + rows + tail, laws


def make_chromophores(src, out):
    d = out / "chromophores"
    for name, raw, title, source in (
            ("eumelanin", "eumelanin_sarna.txt", "Eumelanin",
             "Sarna T., Swartz H.M. (1988), The physical properties of melanins, digitised by OMLC; "
             "raw file eumelanin_sarna.txt (column ext)"),
            ("pheomelanin", "pheomelanin_sarna.txt", "Pheomelanin",
             "Sarna T., Swartz H.M. (1988), digitised by OMLC; raw file pheomelanin_sarna.txt (column ext)")):
        measured = [[r[0], r[1]] for r in read_columns(src / raw)]
        rows, law = with_power_law_tail(measured, MELANIN_TAIL_FIT_NM, TAIL_END_NM)
        write_table(d / f"{name}.csv", f"{title} mass extinction coefficient (Sarna & Swartz)", source,
                    "wavelength_nm [nm]; mass_extinction [cm^-1 / (mg/mL)]",
                    ["wavelength_nm", "mass_extinction"], rows, "error",
                    (["BioSpec uses this as mu_a = eps * c without ln(10) (docs/MATERIALS.md)"] if name == "eumelanin" else [])
                    + [f"measured to {fmt(measured[-1][0])} nm; rows above it are the power law {law}, least squares "
                       f"in log-log over the table's {MELANIN_TAIL_FIT_NM[0]}-{MELANIN_TAIL_FIT_NM[1]} nm (Jacques "
                       "1996 models melanin as lambda^-3.33..-3.48: the same form)",
                       "no value below the measured range: asking there is an error"])
    measured = read_columns(src / "hemoglobin_prahl.txt")
    rows, laws = with_exponential_tail(measured, HEMOGLOBIN_TAIL_FIT_NM, TAIL_END_NM)
    write_table(d / "hemoglobin.csv", "Molar extinction of oxy- and deoxy-haemoglobin (decadic)",
                "S. Prahl (OMLC) compilation of W.B. Gratzer and N. Kollias; raw file hemoglobin_prahl.txt",
                "wavelength_nm [nm]; oxy, deoxy [cm^-1 / M, decadic]",
                ["wavelength_nm", "oxy", "deoxy"], rows, "error",
                ["per mole of haemoglobin tetramer; mu_a = ln(10) eps c / M with M = 64,500 (Prahl) or 66,500 g/mol",
                 f"measured to {fmt(measured[-1][0])} nm; rows above it continue each column's decay over "
                 f"{HEMOGLOBIN_TAIL_FIT_NM[0]}-{HEMOGLOBIN_TAIL_FIT_NM[1]} nm as an exponential ({'; '.join(laws)}): "
                 "a modelling assumption, not a measurement (its share of skin's absorption: docs/HYPERSPECTRAL.md); "
                 "blood's water is not in these tables: it is counted by the layer's water_fraction"])
    for name, raw, title, solvent in (
            ("beta_carotene", "beta_carotene_photochemcad.txt", "Beta-carotene", "hexane"),
            ("bilirubin", "bilirubin_photochemcad.txt", "Bilirubin", "chloroform")):
        rows, negatives = clamp_negative(read_columns(src / raw))
        write_table(d / f"{name}.csv", f"{title} molar extinction in {solvent} (decadic)",
                    f"PhotochemCAD 2.1a (Du et al. 1998; Dixon et al. 2005) via OMLC; raw file {raw}",
                    "wavelength_nm [nm]; molar_extinction [cm^-1 / M, decadic]",
                    ["wavelength_nm", "molar_extinction"], rows, "zero",
                    [f"{negatives} noisy negative values of the raw table set to 0",
                     "zero outside the table: the absorption band lies in 350-550 nm and the raw tail past "
                     "~620 nm is noise around 0, so 0 above 700 nm is the measured value, not a guess; "
                     "below the table (UV-C) the model is not used"])
    rows = [r for r in read_columns(src / "water_segelstein.txt") if 200 <= r[0] <= 2500]
    write_table(d / "water.csv", "Absorption coefficient of pure water (Segelstein)",
                "Segelstein D. (1981), M.Sc. thesis, University of Missouri-Kansas City, via OMLC; "
                "raw file water_segelstein.txt cut to 200-2500 nm",
                "wavelength_nm [nm]; mu_a [cm^-1]", ["wavelength_nm", "mu_a"], rows, "error")
    rows = [[float(w), 0.244 + 85.3 * pow(2.718281828459045, -(w - 154.0) / 66.2)] for w in range(250, TAIL_END_NM + 1)]
    write_table(d / "baseline_tissue.csv", "Baseline absorption of bloodless skin tissue (Jacques)",
                "formula mu_base = 0.244 + 85.3 exp(-(lambda - 154) / 66.2) cm^-1 (S. Jacques, OMLC 'Skin optics' "
                "summary 1998; used by BioSpec, Krishnaswamy & Baranoski 2004), tabulated at 1 nm",
                "wavelength_nm [nm]; mu_a [cm^-1]", ["wavelength_nm", "mu_a"], rows, "error",
                ["linear interpolation between 1 nm samples is within 3e-5 (relative) of the formula",
                 "fitted to bloodless skin in the visible; above 1000 nm the formula's constant 0.244 cm^-1 is kept "
                 "as the protein background, water and lipid are separate terms (docs/HYPERSPECTRAL.md)"])
    rows = [[r[0], r[1] / 100.0] for r in read_columns(src / "fat_vanveen.txt")]
    write_table(d / "lipid.csv", "Absorption coefficient of mammalian fat (van Veen et al.)",
                "van Veen R.L.P., Sterenborg H.J.C.M., Pifferi A., Torricelli A., Cubeddu R. (2005), J. Biomed. Opt. "
                "10(5):054004 (pork lard), as distributed by OMLC; raw file fat_vanveen.txt (1/m), converted to 1/cm",
                "wavelength_nm [nm]; mu_a [cm^-1]", ["wavelength_nm", "mu_a"], rows, "error",
                ["no value outside the measured 429-1098 nm: a layer with lipid_fraction > 0 is refused there"])


def make_tissue(src, out):
    for short, name in (("EP", "epidermis"), ("DE", "dermis"), ("HY", "hypodermis")):
        measured = [[r[0], r[3]] for r in read_columns(src / f"salomatina_{short}.txt")]
        rows, laws = with_anchored_power_law_tails(measured, SALOMATINA_SHORT_FIT_NM, SALOMATINA_LONG_FIT_NM,
                                                   TAIL_START_NM, TAIL_END_NM)
        write_table(out / "tissue" / f"salomatina_{name}.csv",
                    f"Measured ex-vivo human {name} reduced scattering (Salomatina)",
                    f"Salomatina E. et al. (2006), J. Biomed. Opt. 11(6):064026; raw file salomatina_{short}.txt "
                    "(column mu_s'; its mu_a and the standard deviations are left in the raw file)",
                    "wavelength_nm [nm]; mu_s_reduced [mm^-1]", ["wavelength_nm", "mu_s_reduced_per_mm"], rows, "error",
                    [f"measured {fmt(measured[0][0])}-{fmt(measured[-1][0])} nm; outside, mu_s' = a (lambda / 500 nm)^-b "
                     f"with b fitted (least squares in log-log) over {SALOMATINA_SHORT_FIT_NM[0]}-"
                     f"{SALOMATINA_SHORT_FIT_NM[1]} nm below and {SALOMATINA_LONG_FIT_NM[0]}-{SALOMATINA_LONG_FIT_NM[1]} "
                     f"nm above, a set so the law meets the table's end value ({'; '.join(laws)})",
                     "the table's 1000-1600 nm part alone is flat (water-band cross-talk of the inversion), so the "
                     "long tail takes the exponent of 500-1600 nm"])
    measured = [[r[0], r[1]] for r in read_columns(src / "salomatina_HY.txt")]
    write_table(out / "tissue" / "salomatina_hypodermis_absorption.csv",
                "Measured ex-vivo human hypodermis absorption (Salomatina)",
                "Salomatina E. et al. (2006), J. Biomed. Opt. 11(6):064026; raw file salomatina_HY.txt (column mu_a)",
                "wavelength_nm [nm]; mu_a [mm^-1]", ["wavelength_nm", "mu_a_per_mm"], measured, "error",
                ["the measured rows only: no law outside them (the bottom boundary 'hypodermis' is refused there, "
                 "docs/HYPERSPECTRAL.md)"])


BIOSPEC_PRESETS = (  # name, melanosome volume fraction (Krishnaswamy & Baranoski 2004; docs/MATERIALS.md)
    ("biospec-lightly", 0.019, "lightly pigmented"),
    ("biospec-moderately", 0.052, "moderately pigmented"),
    ("biospec-heavily", 0.12, "heavily pigmented"),
    ("biospec-very-heavily", 0.42, "very heavily pigmented"),
)


def make_biospec_presets(out):
    for name, melanosomes, label in BIOSPEC_PRESETS:
        text = f"""# BioSpec layered skin, {label} (melanosome volume fraction {melanosomes}).
# Krishnaswamy & Baranoski 2004, as specified in docs/MATERIALS.md. Generated by {GENERATOR};
# copy it and edit freely: every key carries its unit in its name, ranges are checked on load.
kind = "layered"
name = "{name}"
description = "BioSpec skin, {label} (melanosome fraction {melanosomes})"

[model]
variant = "biospec"                  # or "biospec-2004", "biospec-authors-code"; any switch below overrides it
hemoglobin_molar_mass_g_per_mol = 66500
volumetric_matched_to_biospec = true  # rte, adding-doubling, exports: the volumetric description derived from the BioSpec one

[surface]
above_refractive_index = 1.0         # air
fold_aspect_ratio = 0.75             # skin-fold perturbation of surface reflection, (0, 1]

[bottom]
boundary = "diffuse_reflector"       # the hypodermis (R = 1); "exit" tallies transmittance instead
below_refractive_index = 1.0

[[layers]]
name = "stratum_corneum"
thickness_cm = 0.001
refractive_index = 1.55
scattering = "measured_stratum_corneum"
carotene_g_per_l = 2.1e-4
water_fraction = 0.25               # Warner et al. 1988, J Invest Dermatol 90:218: 15-35 % in the SC (docs/HYPERSPECTRAL.md)
reduced_scattering_table = "salomatina_epidermis"
volumetric_scattering = "from_reduced_scattering"  # rte, adding-doubling: mu_s = mu_s' / (1 - g), the same mu_s' as diffusion
volumetric_phase = "measured_stratum_corneum"     # Bruls & van der Leun 1984 profile as the phase function (g 0.95-0.96)

[[layers]]
name = "epidermis"
thickness_cm = 0.01
refractive_index = 1.40
scattering = "measured_epidermis"
melanosome_fraction = {melanosomes}
eumelanin_mg_per_ml = 80
pheomelanin_mg_per_ml = 12
carotene_g_per_l = 2.1e-4
water_fraction = 0.6                # Warner et al. 1988: ~60-70 % in the viable epidermis
reduced_scattering_table = "salomatina_epidermis"
volumetric_scattering = "from_reduced_scattering"  # rte, adding-doubling: mu_s = mu_s' / (1 - g), the same mu_s' as diffusion
volumetric_phase = "measured_epidermis"           # Bruls & van der Leun 1984 profile as the phase function (g 0.88-0.90)

[[layers]]
name = "papillary_dermis"
thickness_cm = 0.02
refractive_index = 1.36
scattering = "rayleigh_cosine"
blood_fraction = 0.012
oxygen_saturation = 0.75
hemoglobin_g_per_l = 150
bilirubin_g_per_l = 0.05
carotene_g_per_l = 7e-5
water_fraction = 0.7                # dermis 60-75 % (Jacques 2013, Phys Med Biol 58:R37; docs/HYPERSPECTRAL.md)
reduced_scattering_table = "salomatina_dermis"
volumetric_scattering = "from_reduced_scattering"  # rte, adding-doubling: mu_s = mu_s' / (1 - g), the same mu_s' as diffusion
volumetric_g = 0.8                  # van Gemert et al. 1989, IEEE TBME 36:1146: g = 0.62 + 0.29e-3 lambda/nm (0.74-0.82)

[[layers]]
name = "reticular_dermis"
thickness_cm = 0.18
refractive_index = 1.38
scattering = "rayleigh_cosine"
blood_fraction = 0.0091
oxygen_saturation = 0.75
hemoglobin_g_per_l = 150
bilirubin_g_per_l = 0.05
carotene_g_per_l = 7e-5
water_fraction = 0.65               # dermis 60-75 %
reduced_scattering_table = "salomatina_dermis"
volumetric_scattering = "from_reduced_scattering"  # rte, adding-doubling: mu_s = mu_s' / (1 - g), the same mu_s' as diffusion
volumetric_g = 0.8                  # van Gemert et al. 1989, IEEE TBME 36:1146: g = 0.62 + 0.29e-3 lambda/nm (0.74-0.82)
"""
        path = out / "materials" / f"{name}.toml"
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
        print(f"wrote {path.relative_to(ROOT)}")


def make_jensen_materials(reference, out):
    """Homogeneous RGB-band materials of Jensen et al. 2001 Fig. 5(b) as material presets (TOML)."""
    lines = [l for l in reference.read_text(encoding="utf-8").splitlines() if l and not l.startswith("#")]
    header = lines[0].split(",")
    for line in lines[1:]:
        row = dict(zip(header, line.split(",")))
        name = row["material"]
        text = f"""# Homogeneous material '{name}' for the diffusion modes: Jensen, Marschner, Levoy & Hanrahan 2001,
# "A practical model for subsurface light transport", Fig. 5(b) (measured, R G B bands of a 3-CCD camera).
# Generated by {GENERATOR} from shared/reference/jensen2001_measured_materials.csv.
kind = "homogeneous"
name = "jensen2001-{name}"
description = "Jensen et al. 2001 measured material: {name}"
relative_refractive_index = {row['eta']}
bands = ["R", "G", "B"]
reduced_scattering_per_mm = [{row['sigma_s_prime_r']}, {row['sigma_s_prime_g']}, {row['sigma_s_prime_b']}]
absorption_per_mm = [{row['sigma_a_r']}, {row['sigma_a_g']}, {row['sigma_a_b']}]
published_diffuse_reflectance = [{row['rd_r']}, {row['rd_g']}, {row['rd_b']}]
"""
        path = out / "materials" / f"jensen2001-{name}.toml"
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    print(f"wrote {len(lines) - 1} Jensen 2001 materials to data/materials/")


# --- measured angular scattering profiles ---------------------------------------------------------------

def make_profiles(reference, out):
    """Bruls & van der Leun 1984 cumulative profiles, transposed to one row per wavelength."""
    lines = [l for l in reference.read_text(encoding="utf-8").splitlines() if l and not l.startswith("#")]
    header = lines[0].split(",")
    rows = [[float(v) for v in l.split(",")] for l in lines[1:]]
    angles = [r[0] for r in rows]
    columns = ["wavelength_nm"] + [f"cumulative_percent_within_{a:g}deg" for a in angles]
    for tissue, prefix in (("stratum_corneum", "sc_"), ("epidermis", "ep_")):
        table = []
        for c, name in enumerate(header):
            if name.startswith(prefix):
                table.append([float(name[len(prefix):])] + [r[c] for r in rows])
        write_table(out / "scattering" / f"bruls_vanderleun_{tissue}.csv",
                    f"Cumulative forward-scattering profile of human {tissue.replace('_', ' ')} (Bruls & van der Leun 1984)",
                    "Bruls W.A.G., van der Leun J.C. (1984), Photochem. Photobiol. 40(2):231-242; 436/546 nm = Table 1 "
                    "of Baranoski et al. 2005, other wavelengths as used by the BioSpec implementations; "
                    "from shared/reference/bruls_vanderleun_1984_cumulative.csv",
                    "wavelength_nm [nm]; cumulative_percent_within_<angle>deg [% of transmitted radiation within the "
                    "polar angle, 100 at 62.5 deg]", columns, table, "hold",
                    ["rows are wavelengths; between them profiles are interpolated linearly in wavelength, outside "
                     "they are held (clamped): 546 nm is used for all longer wavelengths"])


def make_van_gemert(out):
    """HG asymmetry factors fitted by van Gemert et al. 1989 to the Bruls & van der Leun profiles."""
    # van Gemert M.J.C., Jacques S.L., Sterenborg H.J.C.M., Star W.M. (1989), IEEE Trans. Biomed. Eng.
    # 36(12):1146-1154, as quoted in Table 2 of Baranoski, Krishnaswamy & Kimmel 2005.
    rows = [[436.0, 0.900, 0.748], [546.0, 0.917, 0.781]]
    write_table(out / "scattering" / "hg_asymmetry_van_gemert_1989.csv",
                "Henyey-Greenstein asymmetry factors of stratum corneum and epidermis (van Gemert et al. 1989)",
                "van Gemert et al. (1989) IEEE Trans. Biomed. Eng. 36(12):1146-1154, via Table 2 of Baranoski, "
                "Krishnaswamy & Kimmel 2005", "wavelength_nm [nm]; stratum_corneum_g, epidermis_g [dimensionless]",
                ["wavelength_nm", "stratum_corneum_g", "epidermis_g"], rows, "hold",
                ["linear in wavelength between 436 and 546 nm, clamped (held) outside"])


def make_phantom_background(out):
    """Default background for the phantom-sheet images: a checkerboard with lettering (made with oiiotool)."""
    import shutil
    import subprocess
    path = out / "images" / "phantom_background.png"
    if not shutil.which("oiiotool"):
        print(f"skipped {path.relative_to(ROOT)} (oiiotool not installed)")
        return
    path.parent.mkdir(parents=True, exist_ok=True)
    subprocess.run(["oiiotool", "--pattern", "checker:width=32:height=32:color1=0.08,0.08,0.1:color2=0.92,0.9,0.85",
                    "512x512", "3", "--text:x=36:y=300:size=120:color=0.75,0.12,0.1:font=DejaVuSans-Bold", "SKIN",
                    "-d", "uint8", "-o", str(path)], check=True)
    print(f"wrote {path.relative_to(ROOT)}")


# --- example spectrum -----------------------------------------------------------------------------------

def make_example(out):
    """A smooth synthetic reflectance (not a measurement) for the `color` command's built-in default."""
    import math
    rows = []
    for w in range(380, 781, 5):
        # logistic rise from 0.25 to 0.60 centred at 590 nm: the general shape of light skin reflectance
        rows.append([float(w), 0.25 + 0.35 / (1.0 + math.exp(-(w - 590.0) / 18.0))])
    write_table(out / "spectra" / "example_reflectance.csv",
                "Synthetic example reflectance (logistic 0.25 -> 0.60, midpoint 590 nm, width 18 nm)",
                "synthetic: R(lambda) = 0.25 + 0.35 / (1 + exp(-(lambda - 590) / 18)); not a measurement",
                "wavelength_nm [nm]; reflectance [fraction, 0-1]",
                ["wavelength_nm", "reflectance"], rows, "hold")


# --- reference values for the benchmarks and validations ------------------------------------------------

def make_reference_slabs(reference, out):
    """Prahl's adding-doubling slabs (not spectral: no wavelength column and no domain, DATA_FORMAT.md)."""
    rows = [l for l in reference.read_text(encoding="utf-8").splitlines() if l and not l.startswith("#")]
    lines = [
        "# skinspec-table: 1",
        "# title: Total reflectance and transmittance of Henyey-Greenstein slabs by adding-doubling (Prahl)",
        "# source: shared/reference/adding_doubling_slabs.csv (Prahl's adding-doubling, 64/56 quadrature points, "
        "about 1e-3 relative)",
        f"# generated_by: {GENERATOR}",
        "# units: a = albedo mu_s/(mu_a+mu_s), b = optical thickness (mu_a+mu_s) d, g, n_slab [dimensionless]; "
        "rd, tt, a_abs [fraction of the incident power]",
        "# note: normally incident collimated beam, surroundings n = 1 on both sides, no glass slides",
        "# note: rd excludes the specular surface reflection ((n-1)/(n+1))^2; tt = unscattered + diffuse",
    ] + rows
    path = out / "reference" / "adding_doubling_slabs.csv"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    print(f"wrote {path.relative_to(ROOT)} ({len(rows) - 1} rows)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--sources", type=pathlib.Path, default=ROOT.parent / "shared" / "data-sources")
    parser.add_argument("--reference", type=pathlib.Path, default=ROOT.parent / "shared" / "reference")
    parser.add_argument("--out", type=pathlib.Path, default=ROOT / "data")
    args = parser.parse_args()
    if not args.sources.is_dir():
        sys.exit(f"make_data.py: raw source folder {args.sources} not found (use --sources DIR)")
    make_cie(args.sources, args.out)
    make_ocio(args.out)
    make_example(args.out)
    make_chromophores(args.sources, args.out)
    make_tissue(args.sources, args.out)
    make_profiles(args.reference / "bruls_vanderleun_1984_cumulative.csv", args.out)
    make_van_gemert(args.out)
    make_phantom_background(args.out)
    make_biospec_presets(args.out)
    make_jensen_materials(args.reference / "jensen2001_measured_materials.csv", args.out)
    make_reference_slabs(args.reference / "adding_doubling_slabs.csv", args.out)


if __name__ == "__main__":
    main()
