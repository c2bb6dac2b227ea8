#!/usr/bin/env bash
# demlight insolation against SAGA's Potential Incoming Solar Radiation (saga_cmd ta_lighting 2)
# with its ESRA option (METHOD 3, "Hofierka and Suri") and Linke turbidity, in one run:
#  - flat ground: a flat DEM on the crop's grid (500 m), at local solar noon (SAGA PERIOD 0,
#    MOMENT 12 at the crop's latitude; demlight irradiance --at at SPA's transit) and over each day;
#  - terrain: daily totals on the centre crop of a projected DEM, cell by cell (means, differences,
#    Pearson r of each band), SAGA's direct/diffuse/total against demlight's beam/diffuse/global
#    (albedo 0: SAGA has no ground-reflected part), with both demlight diffuse models;
#  - time: CPU (user + system) of each run, both tools on --threads cores.
# Prints the report (Markdown) on stdout.
#
# Usage: scripts/compare_saga_insolation.sh [--dem PATH] [--crop N] [--days D,D] [--tz ZONE]
#                                           [--linke L] [--threads N] [--build DIR]
# Defaults: big_tujunga_srtm30m_utm11.tif beside the repository (as the r.sun comparison), centre
# crop 400, days 2024-06-21,2024-12-21, America/Los_Angeles, Linke 3, 2 threads, build/release.
# Needs: saga_cmd (Debian: apt-get install saga), gdal_translate, gdal_create, gdalinfo,
# /usr/bin/python3 with numpy and GDAL's Python bindings (Debian: python3-numpy, python3-gdal).
#
# SAGA steps the sun every HOUR_STEP (here 10 min, demlight's default --step) over the local
# solar day and shades with its own ray march (SHADOW 0, "slim"); its diffuse takes its local sky
# view factor (LOCALSVF 1). LOCATION 1 gives every cell its own latitude and longitude.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
dem="$root/../shared/data/dem/big_tujunga_srtm30m_utm11.tif"
crop=400
days="2024-06-21,2024-12-21"
tz="America/Los_Angeles"
linke=3
threads=2
build="$root/build/release"
while [[ $# -gt 0 ]]; do
    case "$1" in
        --dem) dem=$2; shift 2 ;;
        --crop) crop=$2; shift 2 ;;
        --days) days=$2; shift 2 ;;
        --tz) tz=$2; shift 2 ;;
        --linke) linke=$2; shift 2 ;;
        --threads) threads=$2; shift 2 ;;
        --build) build=$2; shift 2 ;;
        -h|--help) sed -n '2,/^# Needs/p' "$0"; exit 0 ;;
        *) echo "compare_saga_insolation.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
    esac
done
for tool in saga_cmd gdal_translate gdal_create gdalinfo /usr/bin/python3 /usr/bin/time; do
    command -v "$tool" >/dev/null || { echo "compare_saga_insolation.sh: $tool is not installed" >&2; exit 1; }
done
demlight="$build/cli/demlight"
[[ -x "$demlight" ]] || { echo "compare_saga_insolation.sh: build demlight first ($demlight)" >&2; exit 1; }
work=$(mktemp -d /tmp/demlight_saga_insolation.XXXXXX)
trap 'rm -rf "$work"' EXIT
export OMP_NUM_THREADS=$threads

read -r w h < <(gdalinfo "$dem" | sed -n 's/^Size is \([0-9]*\), \([0-9]*\)/\1 \2/p')
gdal_translate -q -srcwin $(( (w - crop) / 2 )) $(( (h - crop) / 2 )) "$crop" "$crop" "$dem" "$work/crop.tif"
gdal_translate -q -srcwin 0 0 40 40 "$work/crop.tif" "$work/corner.tif"
gdal_create -q -if "$work/corner.tif" -burn 500 "$work/flat.tif"
centre=$(gdalinfo "$work/flat.tif" | sed -n 's/^Center *( *\([0-9.]*\), *\([0-9.]*\)).*/\1,\2/p')
# The flat DEM's centre in degrees, as demlight places it.
read -r lat lon < <("$demlight" -q horizon "$work/flat.tif" --at-xy "$centre" --azimuth 0 --max-distance 100 |
    /usr/bin/python3 -c "import json, sys; p = json.load(sys.stdin)['point']; print(p['latitude_deg'], p['longitude_deg'])")
saga_version=$(saga_cmd --version 2>&1 | sed -n 's/^SAGA Version: //p' | head -n1)

saga() {  # saga DEM OUTPREFIX ARGS...: direct, diffuse and total grids as GeoTIFFs
    local in=$1 out=$2
    shift 2
    saga_cmd ta_lighting 2 -GRD_DEM="$in" -GRD_DIRECT="${out}_direct.tif" -GRD_DIFFUS="${out}_diffuse.tif" \
        -GRD_TOTAL="${out}_total.tif" -METHOD=3 -GRD_LINKE_DEFAULT="$linke" -UNITS=0 -SHADOW=0 -LOCALSVF=1 "$@" \
        >"${out}.log" 2>&1 || { cat "${out}.log" >&2; exit 1; }
}
mean() { gdalinfo -stats "$1" 2>/dev/null | sed -n 's/^ *STATISTICS_MEAN=//p' | head -n1; }

echo "# demlight insolation against SAGA Potential Incoming Solar Radiation"
echo
echo "SAGA $saga_version \`ta_lighting 2\` (METHOD 3 \"Hofierka and Suri\", Linke $linke, SHADOW 0, LOCALSVF 1, LOCATION 1) against demlight \`insolation\` / \`irradiance\` (Linke $linke, albedo 0: SAGA has no ground-reflected part), on $(basename "$dem") (centre crop $crop × $crop) and on a flat DEM of 500 m on the crop's grid (latitude $(printf '%.3f' "$lat")). OMP_NUM_THREADS=$threads, demlight --threads $threads."
echo
echo "## Flat ground"
echo
transit=$("$demlight" sunpos --time "${days%%,*}T12:00" --tz "$tz" --lat "$lat" --lon "$lon" --json |
    sed -n 's/^ *"transit": "\(.*\)",$/\1/p')
saga "$work/flat.tif" "$work/noon" -LOCATION=0 -LATITUDE="$lat" -PERIOD=0 -DAY="${days%%,*}T00:00:00" -MOMENT=12
ours=$("$demlight" -q irradiance "$work/flat.tif" --at-xy "$centre" --time "$transit" --linke "$linke" --albedo 0 \
    --point-format csv | tail -1)
echo "Solar noon of ${days%%,*} (W/m²):"
echo
echo "| | SAGA | demlight |"
echo "|---|---|---|"
echo "| beam (SAGA direct) | $(printf '%.1f' "$(mean "$work/noon_direct.tif")") | $(printf '%.1f' "$(cut -d, -f6 <<<"$ours")") |"
echo "| diffuse | $(printf '%.1f' "$(mean "$work/noon_diffuse.tif")") | $(printf '%.1f' "$(cut -d, -f7 <<<"$ours")") |"
echo "| global (SAGA total) | $(printf '%.1f' "$(mean "$work/noon_total.tif")") | $(printf '%.1f' "$(cut -d, -f9 <<<"$ours")") |"
echo
echo "Days (kWh/m²):"
echo
echo "| day | SAGA direct / diffuse / total | demlight beam / diffuse / global |"
echo "|---|---|---|"
IFS=, read -ra day_list <<<"$days"
for d in "${day_list[@]}"; do
    saga "$work/flat.tif" "$work/flat_$d" -LOCATION=1 -PERIOD=1 -DAY="${d}T00:00:00" -HOUR_STEP=0.1666667
    ours=$("$demlight" -q insolation "$work/flat.tif" --at-xy "$centre" --date "$d" --tz "$tz" --linke "$linke" \
        --albedo 0 --point-format csv | tail -1)
    printf '| %s | %.3f / %.3f / %.3f | %.3f / %.3f / %.3f |\n' "$d" "$(mean "$work/flat_${d}_direct.tif")" \
        "$(mean "$work/flat_${d}_diffuse.tif")" "$(mean "$work/flat_${d}_total.tif")" "$(cut -d, -f3 <<<"$ours")" \
        "$(cut -d, -f4 <<<"$ours")" "$(cut -d, -f6 <<<"$ours")"
done
echo
echo "## Terrain, daily totals"
echo
for d in "${day_list[@]}"; do
    /usr/bin/time -f '%U %S' -o "$work/t_saga_$d.txt" \
        saga_cmd ta_lighting 2 -GRD_DEM="$work/crop.tif" -GRD_DIRECT="$work/saga_${d}_direct.tif" \
        -GRD_DIFFUS="$work/saga_${d}_diffuse.tif" -GRD_TOTAL="$work/saga_${d}_total.tif" -METHOD=3 \
        -GRD_LINKE_DEFAULT="$linke" -UNITS=0 -SHADOW=0 -LOCALSVF=1 -LOCATION=1 -PERIOD=1 -DAY="${d}T00:00:00" \
        -HOUR_STEP=0.1666667 >"$work/saga_$d.log" 2>&1 || { cat "$work/saga_$d.log" >&2; exit 1; }
    for model in visible-sky rsun; do
        /usr/bin/time -f '%U %S' -o "$work/t_${model}_$d.txt" "$demlight" -q insolation "$work/crop.tif" \
            -o "$work/ours_${model}_$d.tif" --date "$d" --tz "$tz" --linke "$linke" --albedo 0 \
            --diffuse-model "$model" --threads "$threads"
    done
    /usr/bin/python3 - "$work" "$d" <<'EOF'
import sys
import numpy as np
from osgeo import gdal
work, day = sys.argv[1], sys.argv[2]
def band(path, k=1):
    ds = gdal.Open(path)  # kept while its band is read: GDAL frees a band with its dataset
    b = ds.GetRasterBand(k)
    a = b.ReadAsArray().astype(np.float64)
    nd = b.GetNoDataValue()
    if nd is not None:
        a[a == nd] = np.nan
    return a
saga = {n: band(f"{work}/saga_{day}_{n}.tif") for n in ("direct", "diffuse", "total")}
cpu = lambda name: sum(float(v) for v in open(f"{work}/t_{name}_{day}.txt").read().split())
print(f"{day}, kWh/m², demlight minus SAGA over cells valid in both (SAGA leaves the crop's outer ring empty):")
print()
print("| demlight diffuse model | band | demlight mean | SAGA mean | mean diff. | MAE | r |")
print("|---|---|---|---|---|---|---|")
for model in ("visible-sky", "rsun"):
    ours = {"direct": band(f"{work}/ours_{model}_{day}.tif", 1), "diffuse": band(f"{work}/ours_{model}_{day}.tif", 2),
            "total": band(f"{work}/ours_{model}_{day}.tif", 4)}
    for n, label in (("direct", "beam / direct"), ("diffuse", "diffuse"), ("total", "global / total")):
        a, b = ours[n], saga[n]
        ok = np.isfinite(a) & np.isfinite(b)
        a, b = a[ok], b[ok]
        r = np.corrcoef(a, b)[0, 1]
        print(f"| {model} | {label} | {a.mean():.3f} | {b.mean():.3f} | {a.mean() - b.mean():+.3f} | "
              f"{np.abs(a - b).mean():.3f} | {r:.4f} |")
print()
print(f"CPU time (user + system): SAGA {cpu('saga'):.1f} s; demlight {cpu('visible-sky'):.2f} s (visible-sky), "
      f"{cpu('rsun'):.2f} s (rsun); SAGA / demlight {cpu('saga') / cpu('visible-sky'):.0f}x and "
      f"{cpu('saga') / cpu('rsun'):.0f}x.")
print()
EOF
done
