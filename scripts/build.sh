#!/usr/bin/env bash
# Configures and builds demlight (Release) into build/release, and puts its Python package on the
# path of Debian's /usr/bin/python3 (a demlight.pth in its site-packages naming
# build/release/python; docs/python.md). Usage: scripts/build.sh [target...]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset release >/dev/null
if [ $# -gt 0 ]; then
  cmake --build --preset release -- "$@"
else
  cmake --build --preset release
fi

if [ -d build/release/python/demlight ]; then
  site=$(/usr/bin/python3 -c 'import site; print(site.getsitepackages()[0])')
  package="$PWD/build/release/python"
  if [ "$(cat "$site/demlight.pth" 2>/dev/null)" != "$package" ]; then
    sudo=""
    [ "$(id -u)" -ne 0 ] && sudo="sudo"
    $sudo mkdir -p "$site"
    echo "$package" | $sudo tee "$site/demlight.pth" >/dev/null
    echo "demlight: $site/demlight.pth puts $package on /usr/bin/python3's path"
  fi
fi
