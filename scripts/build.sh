#!/usr/bin/env bash
# Configures and builds demlight (Release) into build/release. Usage: scripts/build.sh [target...]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset release >/dev/null
if [ $# -gt 0 ]; then
  cmake --build --preset release -- "$@"
else
  cmake --build --preset release
fi
