#!/usr/bin/env bash
# The DEM-larger-than-memory benchmark (docs/performance.md, "A DEM larger than memory"): one
# whole tiled run of PRODUCT on a SIZE^2 VRT (scripts/make_big_vrt.sh; 40 000^2 by default), measured with
# /usr/bin/time -v, while the one-piece yardstick on the 3601^2 tile the VRT repeats runs in turn
# beside it, so that both see the same machine. Prints peak RSS, wall, CPU (user + sys) and CPU
# per cell of each, the yardstick as the median of its runs, and their ratio (the tiling overhead).
#
# Usage: scripts/bench_big_dem.sh sky|sun [OUT_DIR] [extra demlight options...]
#   e.g. scripts/bench_big_dem.sh sky /tmp/big --memory-limit 4000
# Environment: DEMLIGHT (the binary; default build/release/cli/demlight), TILE (default
# ../shared/data/dem/N48W125_srtm1.tif), TIME (the sun's instant; default 2024-06-21T18:00:00Z),
# SIZE (the VRT's side in cells; default 40000; e.g. SIZE=100000 for a 10^10-cell DEM).
set -euo pipefail
cd "$(dirname "$0")/.."
product=${1:?usage: bench_big_dem.sh sky|sun [OUT_DIR] [options...]}
shift
out=out/bench_big
if [[ $# -gt 0 && $1 != -* ]]; then out=$1; shift; fi  # OUT_DIR, unless the options start
demlight=$(realpath "${DEMLIGHT:-build/release/cli/demlight}")
tile=$(realpath "${TILE:-../shared/data/dem/N48W125_srtm1.tif}")
instant=${TIME:-2024-06-21T18:00:00Z}
size=${SIZE:-40000}
vrt="$out/big$size.vrt"
mkdir -p "$out"
[ -f "$vrt" ] || scripts/make_big_vrt.sh "$tile" "$vrt" "$size"
args=()
[ "$product" = sun ] && args=(--time "$instant")

# CPU seconds (user + sys), wall seconds and peak RSS (kB) of one run, from /usr/bin/time -v.
measure() {
  local log=$1; shift
  /usr/bin/time -v "$@" 2>"$log" >/dev/null || { cat "$log" >&2; exit 1; }
  awk -F': ' '/User time/ {u=$2} /System time/ {s=$2} /Maximum resident/ {m=$2}
              /Elapsed \(wall/ {n=split($2, p, ":"); w=0; for (i=1; i<=n; ++i) w=w*60+p[i]}
              END {printf "%.2f %.1f %d\n", u+s, w, m}' "$log"
}

measure "$out/whole.log" "$demlight" "$product" "$vrt" "${args[@]}" "$@" -o "$out/${product}$size.tif" \
  >"$out/whole.txt" &
whole=$!
: >"$out/one.txt"
while kill -0 "$whole" 2>/dev/null; do
  measure "$out/one.log" "$demlight" -q "$product" "$tile" "${args[@]}" -o "$out/one.tif" >>"$out/one.txt"
done
wait "$whole"
# At least three yardstick runs, even when the whole run ended first.
while [ "$(wc -l <"$out/one.txt")" -lt 3 ]; do
  measure "$out/one.log" "$demlight" -q "$product" "$tile" "${args[@]}" -o "$out/one.tif" >>"$out/one.txt"
done

read -r cpu wall rss <"$out/whole.txt"
cells=$((size * size))
one_cells=$((3601 * 3601))
sort -n "$out/one.txt" | awk -v n="$(wc -l <"$out/one.txt")" 'NR == int((n + 1) / 2) {print}' >"$out/one_median.txt"
read -r ocpu owall orss <"$out/one_median.txt"
grep -m1 "tiles of up to" "$out/whole.log" || true
awk -v c="$cpu" -v w="$wall" -v r="$rss" -v n="$cells" -v oc="$ocpu" -v ow="$owall" -v orr="$orss" \
    -v on="$one_cells" -v runs="$(wc -l <"$out/one.txt")" -v p="$product" 'BEGIN {
  printf "| run | peak RSS | wall | CPU (user + sys) | CPU per cell |\n|---|---|---|---|---|\n"
  printf "| %s, %d^2, tiled | %.2f GB | %.0f s | %.0f s | %.0f ns |\n", p, sqrt(n), r * 1024 / 1e9, w, c, c / n * 1e9
  printf "| %s, 3601^2 tile, one piece (median of %d) | %.0f MB | %.1f s | %.2f s | %.0f ns |\n", p, runs,
         orr * 1024 / 1e6, ow, oc, oc / on * 1e9
  printf "tiling overhead (CPU per cell): %.2fx\n", (c / n) / (oc / on)
}'
