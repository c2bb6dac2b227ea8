#!/usr/bin/env bash
# The speed-against-accuracy chart: builds demlight_tradeoff_bench, runs every method and parameter
# set on the default DEMs and draws the speed-vs-accuracy chart with gnuplot; then times
# --quality auto against full on the sample DEMs (and the shared ones when present).
# Usage: scripts/bench.sh [--quick] [--out DIR] [--dem PATH ...]   (default --out docs/bench)
#   BUILD_DIR=DIR selects the build folder (default build/tradeoff).
# Writes DIR/tradeoff.csv, DIR/tradeoff_<dem>.png per DEM, DIR/tradeoff_run.txt (the log),
# DIR/auto_vs_full.csv and DIR/auto_vs_full_run.txt (the log with a markdown table).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
build=${BUILD_DIR:-build/tradeoff}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j2 --target demlight_tradeoff_bench

out=docs/bench
args=()
dems=()
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out="$2"; shift 2 ;;
    --dem) dems+=("$2"); shift 2 ;;
    *) args+=("$1"); shift ;;
  esac
done
shared=../shared/data/dem
avf_dems=()
if [ ${#dems[@]} -eq 0 ]; then
  dems=(samples/mount_st_helens_1980_usgs.dem)
  for f in "$shared/N44W072.hgt" "$shared/svalbard_longyearbyen_npi_dtm20.tif"; do
    [ -f "$f" ] && dems+=("$f")   # cropped to the centre by the bench
  done
  avf_dems=(samples/mount_st_helens_1980_usgs.dem samples/rocky_mountain_np_dem.tif samples/luxembourg_elev_terra.tif)
  for f in "$shared/N44W072.hgt" "$shared/big_tujunga_srtm30m_utm11.tif" \
           "$shared/svalbard_longyearbyen_npi_dtm20.tif" "$shared/everest_N27E086_srtm3.tif"; do
    [ -f "$f" ] && avf_dems+=("$f")   # cropped to 600 x 600 cells at most
  done
else
  avf_dems=("${dems[@]}")
fi
mkdir -p "$out"
demargs=()
for d in "${dems[@]}"; do demargs+=(--dem "$d"); done
"$build/bench/demlight_tradeoff_bench" "${demargs[@]}" --out "$out" ${args[@]+"${args[@]}"} | tee "$out/tradeoff_run.txt"
for d in "${dems[@]}"; do
  name=$(basename "${d%.*}")
  gnuplot -e "csv='$out/tradeoff.csv'; dem='$name'; out='$out/tradeoff_$name.png'" bench/tradeoff_chart.gnuplot
  echo "wrote $out/tradeoff_$name.png"
done
avfargs=()
for d in "${avf_dems[@]}"; do avfargs+=(--dem "$d"); done
"$build/bench/demlight_tradeoff_bench" --auto-vs-full "${avfargs[@]}" --out "$out" ${args[@]+"${args[@]}"} |
  tee "$out/auto_vs_full_run.txt"
