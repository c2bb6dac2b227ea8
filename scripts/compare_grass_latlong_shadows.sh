#!/usr/bin/env bash
# Where the tile's annual means of r.sun and demlight part (docs/compare/grass_irradiance.md,
# "Why the tile's means differ"): GRASS GIS r.sun mode 2 on one day of a latitude/longitude DEM,
# with its terrain shadows and without (-p), and the same on the DEM reprojected to a projected
# CRS, against `demlight insolation --diffuse-model rsun` on both. Prints a Markdown table of the
# DEM means (kWh/m2 per day, cells valid in each output) on stdout.
#
# Usage: scripts/compare_grass_latlong_shadows.sh [--dem PATH] [--date YYYY-MM-DD] [--tz ZONE]
#                                                 [--t-srs CRS] [--res M] [--build DIR]
# Defaults: the N44W072 SRTM3 tile beside the repository, 2024-06-21, America/New_York (its
# midnights are night, as r.sun's solar day's are), EPSG:32619 (UTM 19N) at 70 m, bilinear;
# Linke 3, albedo 0.2, r.sun step 0.5 h, r.slope.aspect -e slopes, nprocs=1.
# Needs: grass (8.x, Debian package grass-core), gdalwarp, gdal_translate, gdalinfo, python3.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
dem="$root/../shared/data/dem/N44W072.hgt"
date=2024-06-21
tz=America/New_York
t_srs=EPSG:32619
res=70
build="$root/build/release"
while [[ $# -gt 0 ]]; do
    case "$1" in
        --dem) dem=$2; shift 2 ;;
        --date) date=$2; shift 2 ;;
        --tz) tz=$2; shift 2 ;;
        --t-srs) t_srs=$2; shift 2 ;;
        --res) res=$2; shift 2 ;;
        --build) build=$2; shift 2 ;;
        -h|--help) sed -n '2,/^# Needs/p' "$0"; exit 0 ;;
        *) echo "compare_grass_latlong_shadows.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
    esac
done
for tool in grass gdalwarp gdal_translate gdalinfo python3; do
    command -v "$tool" >/dev/null || { echo "compare_grass_latlong_shadows.sh: $tool is not installed" >&2; exit 1; }
done
demlight="$build/cli/demlight"
[[ -x "$demlight" ]] || { echo "compare_grass_latlong_shadows.sh: build demlight first ($demlight)" >&2; exit 1; }
work=$(mktemp -d /tmp/demlight_latlong_shadows.XXXXXX)
trap 'rm -rf "$work"' EXIT

day=$(python3 -c "import datetime; print(datetime.date.fromisoformat('$date').timetuple().tm_yday)")
gdal_translate -q -ot Float32 "$dem" "$work/geo.tif"
gdalwarp -q -t_srs "$t_srs" -tr "$res" "$res" -r bilinear -dstnodata -32768 "$work/geo.tif" "$work/proj.tif"

# The mean of band `band` of a GeoTIFF over its valid cells.
mean_of() { gdalinfo -stats "$1" 2>/dev/null | awk -v b="$2" '/^Band /{n++} n==b && /STATISTICS_MEAN=/{sub(/.*=/,""); print; exit}'; }

for crs in geo proj; do
    {
        echo "r.in.gdal --q input=$work/$crs.tif output=dem"
        echo "g.region raster=dem"
        echo "r.slope.aspect --q -e elevation=dem slope=slope aspect=aspect"
        for flag in shadow noshadow; do
            p=""; [[ $flag == noshadow ]] && p="-p"
            echo "r.sun --q $p elevation=dem slope=slope aspect=aspect day=$day step=0.5 linke_value=3 albedo_value=0.2 nprocs=1 glob_rad=g beam_rad=b --overwrite"
            echo "echo \"$flag \$(r.univar -g map=g | sed -n 's/^mean=//p') \$(r.univar -g map=b | sed -n 's/^mean=//p')\""
        done
    } >"$work/job_$crs.sh"
    grass --tmp-location "$work/$crs.tif" --exec bash "$work/job_$crs.sh" 2>/dev/null | grep -E '^(no)?shadow ' >"$work/rsun_$crs.txt"
    "$demlight" -q insolation "$work/$crs.tif" -o "$work/ours_$crs.tif" --date "$date" --tz "$tz" --linke 3 \
        --albedo 0.2 --diffuse-model rsun --threads 2
    echo "ours $(mean_of "$work/ours_$crs.tif" 4) $(mean_of "$work/ours_$crs.tif" 1)" >>"$work/rsun_$crs.txt"
done

echo "$(basename "$dem") on $date (r.sun day $day), Linke 3, albedo 0.2; mean over the DEM's valid cells, kWh/m2 per day:"
echo
echo "| DEM | run | global | beam | global against r.sun -p |"
echo "|---|---|---|---|---|"
for crs in geo proj; do
    label=$([[ $crs == geo ]] && echo "latitude/longitude" || echo "$t_srs, $res m")
    python3 - "$work/rsun_$crs.txt" "$label" <<'PY'
import sys
rows = {}
for line in open(sys.argv[1]):
    name, g, b = line.split()
    scale = 1 if name == "ours" else 1000  # r.sun writes Wh/m2, demlight kWh/m2
    rows[name] = (float(g) / scale, float(b) / scale)
names = {"shadow": "r.sun (its shadows)", "noshadow": "r.sun -p (no shadows)", "ours": "demlight (its horizons)"}
for key in ("shadow", "noshadow", "ours"):
    g, b = rows[key]
    print(f"| {sys.argv[2]} | {names[key]} | {g:.3f} | {b:.3f} | {(g / rows['noshadow'][0] - 1) * 100:+.2f} % |")
PY
done
