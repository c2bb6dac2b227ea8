#!/usr/bin/env bash
# Compares `demlight sunhours` with GRASS GIS on the same DEM and days, in one run:
#   r.sun (mode 2, daily sums, its own terrain shadowing): beam_rad (Wh/m2/day) and insol_time (h)
#   r.sunhours: sunshine hours on flat terrain (the astronomical day length), NREL SOLPOS
# and writes a markdown report (default docs/compare/grass.md) with the differences and the
# run times of both. README "Comparison with GRASS r.sun / r.sunhours" explains the figures.
#
# Usage: scripts/compare_grass.sh [--dem PATH] [--crop N] [--dates D,D] [--tz ZONE]
#                                 [--fine-step H] [--threads N] [--build DIR] [--out FILE] [--keep]
#   --dem PATH      projected DEM (metres); default ../shared/data/dem/big_tujunga_srtm30m_utm11.tif
#   --crop N        centre crop of N x N cells (default 600; 0 = the whole DEM)
#   --dates D,D     local days YYYY-MM-DD (default 2024-06-21,2024-12-21)
#   --tz ZONE       IANA zone of the place: demlight integrates local midnight to midnight
#                   (default America/Los_Angeles; any zone whose day contains the daylight works)
#   --fine-step H   r.sun step (hours) of the fine run (default 0.1); r.sun's default 0.5 always runs
#   --threads N     threads for r.sun (nprocs) and demlight (default 2)
#   --build DIR     demlight build folder (default build/release; built if missing)
#   --out FILE      report (default docs/compare/grass.md)
#   --keep          keep the work folder (rasters of both tools; its path is printed first)
# Needs: grass (8.x, Debian package grass-core), gdal_translate, python3, /usr/bin/time.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
dem="$root/../shared/data/dem/big_tujunga_srtm30m_utm11.tif"
crop=600
dates="2024-06-21,2024-12-21"
tz="America/Los_Angeles"
fine=0.1
threads=2
build="$root/build/release"
out="$root/docs/compare/grass.md"
keep=0
while [[ $# -gt 0 ]]; do
    case "$1" in
        --dem) dem=$2; shift 2 ;;
        --crop) crop=$2; shift 2 ;;
        --dates) dates=$2; shift 2 ;;
        --tz) tz=$2; shift 2 ;;
        --fine-step) fine=$2; shift 2 ;;
        --threads) threads=$2; shift 2 ;;
        --build) build=$2; shift 2 ;;
        --out) out=$2; shift 2 ;;
        --keep) keep=1; shift ;;
        -h|--help) sed -n '2,/^# Needs/p' "$0"; exit 0 ;;
        *) echo "compare_grass.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
    esac
done
for tool in grass gdal_translate gdalinfo python3 /usr/bin/time; do
    command -v "$tool" >/dev/null || { echo "compare_grass.sh: $tool is not installed" >&2; exit 1; }
done
demlight="$build/cli/demlight"
if [[ ! -x "$demlight" ]]; then
    cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
    cmake --build "$build" --target demlight -j"$threads"
fi

work=$(mktemp -d /tmp/demlight_grass.XXXXXX)
[[ $keep == 1 ]] || trap 'rm -rf "$work"' EXIT
echo "work folder $work" >&2

cut -d' ' -f1-3 /proc/loadavg >"$work/load_start.txt"

# 1. The DEM: a centre crop, and a flat copy (same grid, height 0) for flat open references.
if [[ "$crop" -gt 0 ]]; then
    read -r w h < <(gdalinfo "$dem" | sed -n 's/^Size is \([0-9]*\), \([0-9]*\)/\1 \2/p')
    cw=$((crop < w ? crop : w)); ch=$((crop < h ? crop : h))
    gdal_translate -q -srcwin $(((w - cw) / 2)) $(((h - ch) / 2)) "$cw" "$ch" "$dem" "$work/dem.tif"
else
    gdal_translate -q "$dem" "$work/dem.tif"
fi
gdal_translate -q -ot Float32 -scale 0 1 0 0 -a_nodata none "$work/dem.tif" "$work/flat.tif"

# 2. GRASS: one temporary location from the DEM's own CRS, every module in one session.
IFS=, read -r -a days <<<"$dates"
{
    echo 'set -e'
    echo 'export GRASS_VERBOSE=0'
    echo "r.in.gdal --q input=$work/dem.tif output=dem"
    echo 'g.region raster=dem'
    # -e: slope and aspect on the outer ring too. Without it the ring is null, r.sun treats it as
    # nodata, and a shadow ray that crosses a nodata cell leaves the cell lit for the rest of the
    # day (the "null ring" row of the report measures that).
    echo 'r.slope.aspect --q -e elevation=dem slope=slope aspect=aspect'
    echo 'r.slope.aspect --q elevation=dem slope=slope_null aspect=aspect_null'
    for d in "${days[@]}"; do
        doy=$(date -u -d "$d" +%-j)
        y=${d:0:4}; m=$((10#${d:5:2})); dd=$((10#${d:8:2}))
        tag=${d//-/}
        # The r.sun runs: default step, Linke 0 (no atmosphere: geometry only, comparable in
        # units); the fine step, Linke 0; the default r.sun a user runs (Linke 3, step 0.5); the
        # fine step with the null ring; and the flat open reference for the Linke 3 pattern
        # (horizontal, no shadows).
        for run in "s05_l0 0.5 0" "fine_l0 $fine 0" "s05_l3 0.5 3"; do
            read -r name step linke <<<"$run"
            echo "/usr/bin/time -f '$tag $name %e %U' -a -o $work/times.txt r.sun --q elevation=dem slope=slope aspect=aspect day=$doy step=$step linke_value=$linke nprocs=$threads beam_rad=beam_${name}_$tag insol_time=insol_${name}_$tag"
            echo "r.out.gdal --q -f input=beam_${name}_$tag output=$work/beam_${name}_$tag.tif type=Float32 nodata=-9999"
            echo "r.out.gdal --q -f input=insol_${name}_$tag output=$work/insol_${name}_$tag.tif type=Float32 nodata=-9999"
        done
        echo "/usr/bin/time -f '$tag fine_null %e %U' -a -o $work/times.txt r.sun --q elevation=dem slope=slope_null aspect=aspect_null day=$doy step=$fine linke_value=0 nprocs=$threads insol_time=insol_fine_null_$tag"
        echo "r.out.gdal --q -f input=insol_fine_null_$tag output=$work/insol_fine_null_$tag.tif type=Float32 nodata=-9999"
        echo "r.sun --q -p elevation=dem slope_value=0 day=$doy step=0.5 linke_value=3 nprocs=$threads beam_rad=flat_l3_$tag insol_time=flat_insol_$tag"
        echo "r.out.gdal --q -f input=flat_l3_$tag output=$work/flat_l3_$tag.tif type=Float32 nodata=-9999"
        echo "r.out.gdal --q -f input=flat_insol_$tag output=$work/flat_insol_$tag.tif type=Float32 nodata=-9999"
        echo "/usr/bin/time -f '$tag rsunhours %e %U' -a -o $work/times.txt r.sunhours --q year=$y month=$m day=$dd sunhour=daylen_$tag"
        echo "r.out.gdal --q -f input=daylen_$tag output=$work/daylen_$tag.tif type=Float32 nodata=-9999"
    done
} >"$work/grass_job.sh"
grass_version=$(grass --version 2>&1 | awk '/GRASS GIS/ && !found { print; found = 1 }')
echo "running $grass_version..." >&2
grass --tmp-location "$work/dem.tif" --exec bash "$work/grass_job.sh" >"$work/grass.log" 2>&1 ||
    { cat "$work/grass.log" >&2; exit 1; }

# 3. demlight on the same days: the DEM, and the flat copy for the flat open reference.
for d in "${days[@]}"; do
    tag=${d//-/}
    /usr/bin/time -f "$tag demlight %e %U" -a -o "$work/times.txt" \
        "$demlight" -q sunhours "$work/dem.tif" -o "$work/dl_$tag.tif" --date "$d" --tz "$tz" --threads "$threads"
    "$demlight" -q sunhours "$work/flat.tif" -o "$work/dlflat_$tag.tif" --date "$d" --tz "$tz" --threads "$threads"
    # Run times at r.sun's two steps (30 min, and the fine step in minutes).
    for step in 30 "$(python3 -c "print('%g' % ($fine * 60))")"; do
        /usr/bin/time -f "$tag demlight_$step %e %U" -a -o "$work/times.txt" \
            "$demlight" -q sunhours "$work/dem.tif" -o "$work/dl_step.tif" --date "$d" --tz "$tz" --threads "$threads" --step "$step"
    done
done

cut -d' ' -f1-3 /proc/loadavg >"$work/load_end.txt"
mkdir -p "$(dirname "$out")"
python3 "$root/scripts/compare_grass_report.py" --work "$work" --dates "$dates" --tz "$tz" \
    --fine-step "$fine" --threads "$threads" --dem "$dem" --crop "$crop" --demlight "$demlight" \
    --grass-version "$grass_version" >"$out"
cat "$out"
echo "wrote $out" >&2
