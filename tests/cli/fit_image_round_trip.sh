#!/usr/bin/env bash
# fit-image round trip through the command line: an albedo texture made by `export lut` (the model solved at each
# texel's melanosome and blood fractions, 6 x 4 texels between fit-image's table nodes) is fitted back; every pixel is
# fitted, each pixel's fields are its texel's (within their stated uncertainty), the median fields are the texture's, and
# an edit writes the re-rendered albedo. The same texels as a
# four-band multispectral image (export lut's spectra at 450, 550, 575 and 650 nm, cut out by oiiotool) with their
# band sensitivities: fitted back the same.
set -u
program="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
common=(--mode biospec-adding-doubling --channels 8)
"$program" export lut "${common[@]}" --melanin 0.02:0.2:6:log --blood 0.004:0.04:4:log --space "Linear Rec.709" -o "$work/albedo.exr" --spectra "$work/spectra.exr" --delta-e 0.5 > /dev/null 2>&1 ||
    { echo "export lut failed"; exit 1; }
"$program" fit-image "$work/albedo.exr" "${common[@]}" --melanin 0.005:0.4:12:log --blood 0.002:0.08:8:log --noise 0.002 --json -o "$work/maps.exr" \
    --edit epidermis.melanosome_fraction=*0.5 --edited "$work/lighter.png" > "$work/summary.json" 2> "$work/stderr.txt" ||
    { echo "fit-image failed"; cat "$work/stderr.txt"; exit 1; }
[ -s "$work/maps.exr" ] || { echo "no maps written"; exit 1; }
[ -s "$work/lighter.png" ] || { echo "no edited albedo written"; exit 1; }
oiiotool "$work/spectra.exr" --ch "T.450nm,T.550nm,T.575nm,T.650nm" -o "$work/bands.exr" || { echo "oiiotool failed"; exit 1; }
printf 'wavelength_nm,b450,b550,b575,b650\n445,0,0,0,0\n450,1,0,0,0\n455,0,0,0,0\n545,0,0,0,0\n550,0,1,0,0\n555,0,0,0,0\n570,0,0,0,0\n575,0,0,1,0\n580,0,0,0,0\n645,0,0,0,0\n650,0,0,0,1\n655,0,0,0,0\n' > "$work/bands.csv"
"$program" fit-image "$work/bands.exr" --bands "$work/bands.csv" "${common[@]}" --melanin 0.005:0.4:12:log --blood 0.002:0.08:8:log --json \
    -o "$work/band_maps.exr" > "$work/band_summary.json" 2> "$work/stderr.txt" || { echo "fit-image --bands failed"; cat "$work/stderr.txt"; exit 1; }
oiiotool --dumpdata "$work/maps.exr" > "$work/maps.txt" || { echo "oiiotool --dumpdata failed"; exit 1; }
python3 - "$work/maps.txt" <<'PY' || exit 1
import re, sys
# Pixel by pixel: texel (i, j) was made at melanosome fraction 0.02 * 10^(i/5) and blood fraction 0.004 * 10^(j/3)
# (export lut's axes above); each fitted value must be within 4 of its stated standard uncertainty of them (the
# uncertainty from --noise 0.002), status 0 (fitted). Channels: residual, status, blood, its stderr, melanin, its stderr.
checked = 0
for line in open(sys.argv[1]):
    m = re.match(r"\s*Pixel \((\d+), (\d+)\): (.*)", line)
    if not m:
        continue
    i, j = int(m[1]), int(m[2])
    _, status, blood, blood_se, melanin, melanin_se = (float(x) for x in m[3].split())
    truth_m, truth_b = 0.02 * 10 ** (i / 5), 0.004 * 10 ** (j / 3)
    assert status == 0, (i, j, status)
    assert abs(melanin - truth_m) <= 4 * melanin_se, ("melanosome fraction", i, j, melanin, melanin_se, truth_m)
    assert abs(blood - truth_b) <= 4 * blood_se, ("blood fraction", i, j, blood, blood_se, truth_b)
    checked += 1
assert checked == 24, checked
print(f"fit-image round trip: each of {checked} pixels within 4 standard uncertainties of its texel's melanosome and blood fractions")
PY
python3 - "$work/summary.json" "$work/band_summary.json" <<'PY'
import json, sys
# The texture's values: 0.02..0.2 log (6) and 0.004..0.04 log (4); a median is one of them or between two.
m = [0.02 * 10 ** (i / 5) for i in range(6)]
b = [0.004 * 10 ** (j / 3) for j in range(4)]
for name in sys.argv[1:]:
    s = json.load(open(name))
    assert s["pixels"]["fitted"] == 24, s["pixels"]
    for field, values in (("epidermis.melanosome_fraction", m), ("dermis.blood_fraction", b)):
        got = s[field]["median"]
        assert values[0] <= got <= values[-1] and min(abs(got / v - 1) for v in values) < 0.05, (field, got, values)
    print(f"fit-image round trip ({len(s['channels'])} channels): 24 of 24 pixels fitted; medians",
          s["epidermis.melanosome_fraction"]["median"], s["dermis.blood_fraction"]["median"])
PY
