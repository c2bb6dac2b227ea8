#!/usr/bin/env bash
# Installs missing packages, builds everything and runs every test (GoogleTest through ctest).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
ctest --preset release -j2 --timeout 900
