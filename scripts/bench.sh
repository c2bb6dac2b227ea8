#!/usr/bin/env bash
# `demlight bench` (issue 6): builds demlight_tradeoff_bench, runs every method and parameter set
# on the default DEMs, and draws the speed-vs-accuracy chart with gnuplot.
# Usage: scripts/bench.sh [--quick] [--out DIR] [--dem PATH ...]   (default --out docs/bench)
# Writes DIR/tradeoff.csv, DIR/tradeoff_<dem>.png per DEM and DIR/tradeoff_run.txt (the log).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
build=build/tradeoff
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
if [ ${#dems[@]} -eq 0 ]; then
  dems=(samples/mount_st_helens_1980_usgs.dem)
  shared=../shared/data/dem
  for f in "$shared/N44W072.hgt" "$shared/svalbard_longyearbyen_npi_dtm20.tif"; do
    [ -f "$f" ] && dems+=("$f")   # cropped to the centre by the bench
  done
fi
mkdir -p "$out"
demargs=()
for d in "${dems[@]}"; do demargs+=(--dem "$d"); done
"$build/bench/demlight_tradeoff_bench" "${demargs[@]}" --out "$out" "${args[@]}" | tee "$out/tradeoff_run.txt"
for d in "${dems[@]}"; do
  name=$(basename "${d%.*}")
  gnuplot -e "csv='$out/tradeoff.csv'; dem='$name'; out='$out/tradeoff_$name.png'" bench/tradeoff_chart.gnuplot
  echo "wrote $out/tradeoff_$name.png"
done
