#!/usr/bin/env bash
# Installs missing packages, then runs every test (GoogleTest through ctest, then pytest for the
# Python package) in Release, the GoogleTest ones again on the portable path (DEMLIGHT_SIMD),
# checks cmake --install and the C++ consumer example
# (scripts/check_install.sh), runs the QGIS provider's tests (qgis/tests: qgis_process against
# the CLI), runs the GoogleTest ones again, but for the real-DEM tests, under AddressSanitizer +
# UBSan (the asan preset, clang), and runs each libFuzzer target for FUZZ_SECONDS (default 30).
# CI runs exactly this; what each stage costs on 2 cores and which tests the sanitizer stage
# leaves to Release: docs/testing.md.
set -euo pipefail
cd "$(dirname "$0")/.."

# Each stage's wall time, for the CI log (docs/testing.md keeps the measured budget).
stage() { echo "== [$(date -u +%H:%M:%S), ${SECONDS} s] $*"; }

stage "Release: build and tests"
scripts/build.sh
ctest --preset release -j2 --timeout 900

# The same binaries on the portable path (DEMLIGHT_SIMD=portable, demlight/core/simd.h): what a processor
# without AVX-512 runs. The tests on real DEMs and the README's recipes stay in the pass above:
# the synthetic tests and the samples run every kernel, and the product test that holds both
# paths to the same bits (Samples/TiledProducts) runs on real DEMs there.
stage "Release: tests on the portable path (DEMLIGHT_SIMD=portable)"
portable_skip='^SharedDems/|^RealDems/|OnARealTile$|OnRealTerrain$|^ReadmeRecipes$'
DEMLIGHT_SIMD=portable ctest --preset release -j2 --timeout 900 -E "$portable_skip"

stage "Release: Python tests (pytest, tests/python)"
# Exit code 5 (no tests collected) fails too: the set-up installs everything the tests need.
status=0
/usr/bin/python3 -m pytest -q -p no:cacheprovider tests/python || status=$?
if [ "$status" -eq 5 ]; then echo "pytest collected no tests in tests/python"; exit 1; fi
[ "$status" -eq 0 ] || exit "$status"

stage "Install: cmake --install, the installed CLI, the C++ consumer example"
scripts/check_install.sh

stage "QGIS provider: qgis_process against the CLI (qgis/tests)"
PYTHONDONTWRITEBYTECODE=1 /usr/bin/python3 -m pytest -q -rs -p no:cacheprovider qgis/tests

# Under the sanitizers the real-DEM tests (../shared/data/dem) would take a third of the time;
# they run the code the synthetic tests and the bundled samples (Samples/*) run, on larger
# grids, so they run in Release only. So do the README's recipes (ReadmeRecipes): commands the
# CLI tests already run under the sanitizers, at several times their Release CPU. So do two
# accuracy comparisons over long periods on a sample (binned insolation against 290 per-instant
# irradiance runs; two days of sun hours, exact against interpolated): 256 s of the stage's
# 1068 s of test time, on code that Products.SunhoursAutoInterpolatesOnlyLongPeriodsOnTerrainUnderAuto,
# CliOutputs.SunhoursInterpolatedHorizonsStayCloseToExact and the other InsolationProduct tests
# run under the sanitizers.
asan_skip='^SharedDems/|^RealDems/|OnARealTile$|OnRealTerrain$|^CliOutputs\.SunhoursAutoInterpolatesLongPeriodsOnTerrain$|^ReadmeRecipes$|^SolarRecipes$'

stage "AddressSanitizer + UBSan: build and tests"
cmake --preset asan >/dev/null
cmake --build --preset asan --target demlight demlight_tests demlight_fuzzers
ctest --preset asan -j2 --timeout 900 -E "$asan_skip"

stage "Fuzzing"
scripts/fuzz.sh "${FUZZ_SECONDS:-30}"
stage "done"
