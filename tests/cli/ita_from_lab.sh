#!/usr/bin/env bash
# The ITA and skin-tone category `spectrum` reports, against the published formulas applied to the colour it reports
# (not against an earlier output): Lab from XYZ and the white (CIE 015:2018 Eq. 8.1-8.3), ITA = atan((L* - 50) / b*)
# in degrees (Chardon, Cretois & Hourseau 1991), the category by Del Bino et al. 2006's thresholds (very light > 55,
# light > 41, intermediate > 28, tan > 10, brown > -30, dark below).
set -u
program="$1"
for preset in biospec-lightly biospec-moderately biospec-heavily biospec-very-heavily; do
    "$program" spectrum --mode adding-doubling --preset "$preset" --json 2> /dev/null
done | python3 -c '
import json, math, sys
decoder, text, checked = json.JSONDecoder(), sys.stdin.read(), 0
while text.strip():
    document, end = decoder.raw_decode(text.lstrip())
    text = text.lstrip()[end:]
    for result in document["results"]:
        c = result["color"]
        f = lambda t: t ** (1 / 3) if t > (6 / 29) ** 3 else t / (3 * (6 / 29) ** 2) + 4 / 29
        fx, fy, fz = (f(v / w) for v, w in zip(c["XYZ"], c["white_XYZ"]))
        lab = (116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz))
        assert all(abs(a - b) < 1e-9 for a, b in zip(lab, c["Lab"])), (result["material"], lab, c["Lab"])
        ita = math.degrees(math.atan((lab[0] - 50) / lab[2]))
        assert abs(ita - c["ITA_deg"]) < 1e-9, (result["material"], ita, c["ITA_deg"])
        category = next(name for bound, name in ((55, "very light"), (41, "light"), (28, "intermediate"), (10, "tan"), (-30, "brown"),
                                                 (-1e9, "dark")) if ita > bound)
        assert category == c["skin_tone_category"], (result["material"], ita, category, c["skin_tone_category"])
        name = result["material"]
        print(f"{name}: Lab {lab[0]:.2f} {lab[1]:.2f} {lab[2]:.2f}, ITA {ita:.2f} deg ({category}) as reported")
        checked += 1
assert checked == 4, checked
'
