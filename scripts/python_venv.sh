#!/usr/bin/env bash
# Makes skinspec importable in a Python virtual environment: creates DIR with Debian's interpreter and
# --system-site-packages (numpy from python3-numpy stays visible) unless DIR is a virtual environment already, then
# installs the package built by scripts/setup.sh into it, with its own copy of data/ (docs/PYTHON.md).
#   scripts/python_venv.sh ~/venvs/skin [--without-pip]    then: . ~/venvs/skin/bin/activate; python -c "import skinspec"
set -euo pipefail
if [ $# -lt 1 ]; then
  echo "usage: scripts/python_venv.sh DIR [--without-pip]" >&2
  exit 2
fi
venv="$1"
shift
cd "$(dirname "$0")/.."
build="$PWD/build"
if [ ! -f "$build/CMakeCache.txt" ]; then
  echo "python_venv: no build in $build: run scripts/setup.sh first" >&2
  exit 2
fi
python="$(sed -n 's/^Python3_EXECUTABLE:FILEPATH=//p' "$build/CMakeCache.txt")"
python="${python:-/usr/bin/python3}"
if [ ! -x "$venv/bin/python" ]; then
  "$python" -m venv --system-site-packages "$@" "$venv"
elif [ "$("$venv/bin/python" -c 'import sys; print(sys.version_info[:2])')" != "$("$python" -c 'import sys; print(sys.version_info[:2])')" ]; then
  echo "python_venv: $venv runs another Python than the module was built for ($python)" >&2
  exit 2
fi
# cmake puts the package in PREFIX/lib/python3.X/dist-packages; a .pth file in the environment's own site-packages
# puts that folder on its path.
cmake --install "$build" --component python --prefix "$venv" > /dev/null
packages="$("$venv/bin/python" -c 'import sysconfig; print(sysconfig.get_path("platlib"))')"
installed="$(cd "$venv" && ls -d "$PWD"/lib/python3*/dist-packages)"
echo "$installed" > "$packages/skinspec.pth"
echo "python_venv: skinspec installed in $venv ($installed); activate with: . $venv/bin/activate"
