#!/usr/bin/env bash
# Installs missing packages, then runs every test (GoogleTest through ctest) in Release, checks
# cmake --install and the C++ consumer example (scripts/check_install.sh), runs the QGIS
# provider's tests (qgis/tests: qgis_process against the CLI), runs the GoogleTest suite again,
# but for the real-DEM tests, under AddressSanitizer + UBSan (the asan preset, clang), and runs
# each libFuzzer target for FUZZ_SECONDS (default 60). CI runs exactly this; what each stage
# costs on 2 cores and which tests the sanitizer stage leaves to Release: docs/testing.md.
set -euo pipefail
cd "$(dirname "$0")/.."

# Each stage's wall time, for the CI log (docs/testing.md keeps the measured budget).
stage() { echo "== [$(date -u +%H:%M:%S), ${SECONDS} s] $*"; }

stage "Release: build and tests"
scripts/build.sh
ctest --preset release -j2 --timeout 900

stage "Install: cmake --install, the installed CLI, the C++ consumer example"
scripts/check_install.sh

# Debian's python3 (pytest and the QGIS modules are Debian packages), not another one on PATH.
python=/usr/bin/python3
[ -x "$python" ] || python=python3
stage "QGIS provider: qgis_process against the CLI"
PYTHONDONTWRITEBYTECODE=1 "$python" -m pytest -q -rs -p no:cacheprovider qgis/tests

# Under the sanitizers the real-DEM tests (../shared/data/dem) would take a third of the time;
# they run the code the synthetic tests and the bundled samples (Samples/*) run, on larger
# grids, so they run in Release only.
asan_skip='^SharedDems/|^RealDems/|OnARealTile$'

stage "AddressSanitizer + UBSan: build and tests"
cmake --preset asan >/dev/null
cmake --build --preset asan --target demlight demlight_tests demlight_fuzzers
ctest --preset asan -j2 --timeout 900 -E "$asan_skip"

stage "Fuzzing"
scripts/fuzz.sh "${FUZZ_SECONDS:-60}"
stage "done"
