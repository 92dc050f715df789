#!/usr/bin/env bash
# Regenerates docs/images/fit_image_astronaut.png (docs/FIT_IMAGE.md, "A real image"): skinspec fit-image on NASA's
# public-domain portrait of Eileen Collins as Debian's python3-skimage ships it (downloaded with apt-get download,
# not installed), the panels composed with oiiotool (openimageio-tools).
#   scripts/fit_image_example.sh [build/skinspec]
set -euo pipefail
program="$(realpath "${1:-build/skinspec}")"
root="$(cd "$(dirname "$0")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"
apt-get download python3-skimage > /dev/null
dpkg-deb -x python3-skimage_*.deb extracted
cp extracted/usr/lib/python3/dist-packages/skimage/data/astronaut.png .
"$program" fit-image astronaut.png -o maps.exr --white 1.4,1.7,1.7 --noise 0.01 --melanin 0.001:0.45:28:log \
    --edit epidermis.melanosome_fraction=*3 --edited darker.png
# Fitted pixels white (status 0), the fields in inferno from 0 to 0.05.
oiiotool maps.exr --ch status --mulc -1 --addc 1 --clamp:min=0 --ch 0,0,0 -o fitted.png
oiiotool maps.exr --ch epidermis.melanosome_fraction --mulc 20 --colormap inferno -o melanin.png
oiiotool maps.exr --ch dermis.blood_fraction --mulc 20 --colormap inferno -o blood.png
for f in astronaut fitted melanin blood darker; do oiiotool "$f.png" --cut 128x160+160+40 --resize 160x200 -o "${f}_face.png"; done
mkdir -p "$root/docs/images"
oiiotool astronaut_face.png fitted_face.png melanin_face.png blood_face.png darker_face.png --mosaic 5x1 -o "$root/docs/images/fit_image_astronaut.png"
echo "wrote $root/docs/images/fit_image_astronaut.png"
