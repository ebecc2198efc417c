#!/usr/bin/env bash
# Installs neopipe's Python module: the Debian packages it needs (scripts/setup.sh), a Release build
# of the module only (build/python/neopipe), and a copy of that package directory into Python's
# user site-packages, or into DIR when given. Then `python3 -c "import neopipe"` works anywhere.
#   ./scripts/install_python.sh [DIR]
# There is no PyPI here, so no pip: pybind11, numpy and the rest come from Debian.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
# The interpreter Debian's numpy belongs to: a python3 earlier on PATH (pyenv, a venv without
# numpy) would build a module that cannot import it. PYTHON=... chooses another one.
python="${PYTHON:-}"
if [ -z "$python" ]; then
  for candidate in python3 /usr/bin/python3; do
    if "$candidate" -c "import numpy" 2> /dev/null; then
      python="$(command -v "$candidate")"
      break
    fi
  done
fi
[ -n "$python" ] || { echo "install_python: no python3 that imports numpy (Debian: python3-numpy)" >&2; exit 1; }
launcher=()
if command -v ccache > /dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR="$PWD"
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DNEOPIPE_BUILD_PYTHON=ON -DPython3_EXECUTABLE="$python" "${launcher[@]}"
cmake --build build --target neopipe_python -j "$(nproc)"
dest="${1:-$("$python" -c "import site; print(site.getusersitepackages())")}"
mkdir -p "$dest"
rm -rf "$dest/neopipe"
cp -r build/python/neopipe "$dest/"
# From another directory, so the repository's python/neopipe (sources, no _core) is not the one found.
(cd / && PYTHONPATH="$dest" "$python" -c "import neopipe; print('neopipe', neopipe.__file__)")
echo "install_python: installed into $dest (for $python)"
