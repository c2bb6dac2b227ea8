#!/usr/bin/env bash
# Installs missing packages, builds demlight and its Python package (put on /usr/bin/python3's
# path: docs/python.md), and lights the bundled Mount St. Helens DEM.
# Outputs go to out/demo/ (override with DEMLIGHT_DEMO_OUT=folder).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh demlight _demlight
bin=build/release/cli/demlight
dem=samples/mount_st_helens_1980_usgs.dem
out=${DEMLIGHT_DEMO_OUT:-out/demo}
mkdir -p "$out"
when="2024-06-21T07:30"
zone="America/Los_Angeles"

run() { echo "+ $*"; "$@"; }
run "$bin" info "$dem"
run "$bin" sunpos --time "$when" --tz "$zone" --lat 46.2 --lon -122.18
run "$bin" horizon "$dem" -o "$out/horizon_16.tif" --directions 16
run "$bin" sun "$dem" -o "$out/sun.tif" --time "$when" --tz "$zone"
run "$bin" sky "$dem" -o "$out/sky.tif"
run "$bin" aperture "$dem" -o "$out/aperture.tif"
run "$bin" render "$dem" -o "$out/render.png" --time "$when" --tz "$zone"
run "$bin" timelapse "$dem" -o "$out/day" --date 2024-06-21 --tz "$zone" --step 1h --formats png,gif
echo
echo "demo outputs in $out/:"
ls -l "$out"
