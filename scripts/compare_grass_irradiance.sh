#!/usr/bin/env bash
# Compares `demlight irradiance` with GRASS GIS r.sun mode 1 (instantaneous irradiance, W/m2) on
# synthetic flat DEMs, one per latitude: both tools' sun, extraterrestrial irradiance and beam,
# diffuse and global irradiance on open flat ground at the same instant, as a markdown table.
# (scripts/compare_grass.sh compares the daily products, sunhours and r.sun mode 2.)
#
# Usage: scripts/compare_grass_irradiance.sh [--lats L,L,..] [--times T,T,..] [--height M]
#                                            [--linke L] [--build DIR] [--golden]
#   --lats      latitudes of the flat DEMs, at longitude 0 (default 0,30,50,70)
#   --times     instants in UTC, ISO 8601 with Z (default 2024-06-21T10:30:00Z,
#               2024-06-21T05:00:00Z,2024-12-21T12:00:00Z)
#   --height    height of the flat DEMs (metres; default 500)
#   --linke     Linke turbidity of both tools (default 3)
#   --build     demlight build folder (default build/release)
#   --golden    instead: r.sun's own sun and irradiance for the cases of tests/irradiance_test.cpp
#               (kRsun), as CSV, for checking demlight's formulas against r.sun's at r.sun's sun
#   --terrain DEM  instead: both tools on a real projected DEM (a centre crop of --crop cells) at
#               each of --local-times in --tz, cell by cell: r.sun with r.slope.aspect -e slopes
#               and its own shadows against `demlight irradiance --diffuse-model rsun` and
#               `visible-sky` (statistics of demlight minus r.sun per band, shadow agreement)
#   --crop N    with --terrain: centre crop (default 400; 0 = the whole DEM)
#   --local-times T,T  with --terrain: local clock times (default 2024-12-21T09:00,2024-06-21T13:00)
#   --tz ZONE   with --terrain: zone of the DEM (default America/Los_Angeles)
# Needs: grass (8.x, Debian package grass-core), gdal_create, gdallocationinfo, python3.
#
# r.sun runs with civil_time=0 and a longitude raster, so its time= is UTC read as civil time at
# longitude 0; r.sun then finds the solar time from its own equation-of-time approximation. A
# 3 x 3 DEM of 1e-5 degree cells keeps one sun over the DEM, so r.info's solar altitude (r.sun
# reports the last cell's) is the sun of the compared cell. r.sun 8.2.1 reads a single
# aspect_value clockwise from north (270 faced west in the --golden runs), unlike its manual;
# aspect rasters from r.slope.aspect (counterclockwise from east) it converts itself.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
lats="0,30,50,70"
times="2024-06-21T10:30:00Z,2024-06-21T05:00:00Z,2024-12-21T12:00:00Z"
height=500
linke=3
build="$root/build/release"
golden=0
terrain=""
crop=400
local_times="2024-12-21T09:00,2024-06-21T13:00"
tz="America/Los_Angeles"
while [[ $# -gt 0 ]]; do
    case "$1" in
        --lats) lats=$2; shift 2 ;;
        --times) times=$2; shift 2 ;;
        --height) height=$2; shift 2 ;;
        --linke) linke=$2; shift 2 ;;
        --build) build=$2; shift 2 ;;
        --golden) golden=1; shift ;;
        --terrain) terrain=$2; shift 2 ;;
        --crop) crop=$2; shift 2 ;;
        --local-times) local_times=$2; shift 2 ;;
        --tz) tz=$2; shift 2 ;;
        -h|--help) sed -n '2,/^# Needs/p' "$0"; exit 0 ;;
        *) echo "compare_grass_irradiance.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
    esac
done
for tool in grass gdal_create gdallocationinfo python3; do
    command -v "$tool" >/dev/null || { echo "compare_grass_irradiance.sh: $tool is not installed" >&2; exit 1; }
done
work=$(mktemp -d /tmp/demlight_grass_irr.XXXXXX)
trap 'rm -rf "$work"' EXIT

# A 3 x 3 flat DEM of `cell` degree cells centred on (0, lat) at height z.
flat_dem() {  # path lat z cell
    local half
    half=$(python3 -c "print(1.5 * $4)")
    gdal_create -q -of GTiff -ot Float32 -outsize 3 3 -bands 1 -burn "$3" -a_srs EPSG:4326 \
        -a_ullr "-$half" "$(python3 -c "print($2 + $half)")" "$half" "$(python3 -c "print($2 - $half)")" "$1"
}

# r.sun mode 1 at the DEM's centre: prints "altitude azimuth g0 incidence beam diffuse reflected global".
rsun_at() {  # dem lat rsun-arguments...
    local dem=$1 lat=$2
    shift 2
    cat >"$work/job.sh" <<EOF
set -e
export GRASS_VERBOSE=0
r.in.gdal --q -o input=$dem output=dem
g.region raster=dem
r.mapcalc --q expression="lon = x()"
r.sun --q elevation=dem $* beam_rad=b diff_rad=d refl_rad=r glob_rad=g incidout=i
r.what map=i,b,d,r,g coordinates=0,$lat
r.info -h map=b
EOF
    local out
    out=$(grass --tmp-location EPSG:4326 --exec bash "$work/job.sh" 2>/dev/null)
    python3 - "$out" <<'EOF'
import re, sys
text = sys.argv[1]
def grab(label):
    m = re.search(re.escape(label) + r":\s*([-0-9.]+)", text)
    return m.group(1) if m else "nan"
row = next(l for l in text.splitlines() if l.startswith("0|"))
vals = [v if v not in ("", "*") else "nan" for v in row.split("|")[3:8]]
print(grab("Solar altitude (deg)"), grab("Solar azimuth (deg)"), grab("Extraterrestrial irradiance (W/m^2)"), *vals)
EOF
}

if [[ $golden == 1 ]]; then
    # lat z day solar-time linke slope aspect albedo: the rows of kRsun in tests/irradiance_test.cpp.
    echo "lat,elevation_m,day,solar_time_h,linke,slope_deg,aspect_deg,albedo,altitude_deg,azimuth_deg,g0_wm2,incidence_deg,beam,diffuse,reflected,global"
    while read -r lat z day t l s a alb; do
        flat_dem "$work/g.tif" "$lat" "$z" 0.000001
        read -r -a v < <(rsun_at "$work/g.tif" "$lat" slope_value="$s" aspect_value="$a" day="$day" time="$t" \
            linke_value="$l" albedo_value="$alb")
        echo "$lat,$z,$day,$t,$l,$s,$a,$alb,$(IFS=,; echo "${v[*]}")"
    done <<'EOF'
50 500 173 10.5 3 0 270 0.2
50 500 173 10.5 3 30 270 0.2
50 500 173 4.5 3 30 45 0.2
50 500 173 7.0 3 60 90 0.2
0 0 80 12.0 2 0 270 0.2
30 2000 355 9.0 5 20 180 0.3
70 100 173 23.0 4 0 270 0.2
EOF
    exit 0
fi

demlight="$build/cli/demlight"
[[ -x "$demlight" ]] || { echo "compare_grass_irradiance.sh: build demlight first ($demlight)" >&2; exit 1; }
grass_version=$(grass --version 2>&1 | awk '/GRASS GIS/ && !found { print; found = 1 }')

if [[ -n "$terrain" ]]; then
    if [[ "$crop" -gt 0 ]]; then
        read -r w h < <(gdalinfo "$terrain" | sed -n 's/^Size is \([0-9]*\), \([0-9]*\)/\1 \2/p')
        cw=$((crop < w ? crop : w)); ch=$((crop < h ? crop : h))
        gdal_translate -q -srcwin $(((w - cw) / 2)) $(((h - ch) / 2)) "$cw" "$ch" "$terrain" "$work/dem.tif"
    else
        gdal_translate -q "$terrain" "$work/dem.tif"
    fi
    IFS=, read -r -a lt_list <<<"$local_times"
    {
        echo 'set -e'
        echo 'export GRASS_VERBOSE=0'
        echo "r.in.gdal --q input=$work/dem.tif output=dem"
        echo 'g.region raster=dem'
        echo 'r.slope.aspect --q -e elevation=dem slope=slope aspect=aspect'
        echo 'r.latlong --q -l input=dem output=lon'
        for lt in "${lt_list[@]}"; do
            tag=${lt//[-:T]/}
            doy=$(date -d "${lt/T/ }" +%-j)
            hours=$(date -d "${lt/T/ }" +%H:%M | awk -F: '{ printf "%.6f", $1 + $2 / 60 }')
            offset=$(TZ="$tz" date -d "${lt/T/ }" +%z |
                awk '{ printf "%g", (substr($1, 1, 1) == "-" ? -1 : 1) * (substr($1, 2, 2) + substr($1, 4, 2) / 60) }')
            echo "r.sun --q elevation=dem slope=slope aspect=aspect long=lon civil_time=$offset day=$doy time=$hours linke_value=$linke albedo_value=0.2 beam_rad=b$tag diff_rad=d$tag refl_rad=r$tag glob_rad=g$tag"
            for m in b d r g; do echo "r.out.gdal --q -f input=$m$tag output=$work/rsun_$m$tag.tif type=Float32 nodata=-9999"; done
        done
    } >"$work/terrain_job.sh"
    grass --tmp-location "$work/dem.tif" --exec bash "$work/terrain_job.sh" >"$work/grass.log" 2>&1 ||
        { cat "$work/grass.log" >&2; exit 1; }
    for lt in "${lt_list[@]}"; do
        tag=${lt//[-:T]/}
        for model in rsun visible-sky; do
            "$demlight" -q irradiance "$work/dem.tif" -o "$work/dl_${model}_$tag.tif" --time "$lt" --tz "$tz" \
                --linke "$linke" --albedo 0.2 --diffuse-model "$model" --threads 2
        done
    done
    python3 - "$work" "$local_times" "$tz" "$terrain" "$crop" "$grass_version" "$linke" "$root/scripts" <<'EOF'
import math, sys
work, times, tz, dem, crop, grass, linke, scripts = sys.argv[1:9]
sys.path.insert(0, scripts)
from compare_grass_report import compare, read_band, row
where = f"centre crop {crop} x {crop}" if crop != "0" else "whole"
print(f"demlight irradiance vs {grass} r.sun mode 1 on {dem.split('/')[-1]} ({where}), Linke {linke},"
      f" albedo 0.2, {tz}; W/m2, demlight minus r.sun over cells valid in both. r.sun: r.slope.aspect -e"
      " slopes, its own shadows and sun; demlight: its normals, sun-disk visibility and SPA sun.")
for lt in times.split(","):
    tag = lt.replace("-", "").replace(":", "").replace("T", "")
    theirs = [read_band(f"{work}/rsun_{m}{tag}.tif") for m in "bdrg"]
    for model in ("rsun", "visible-sky"):
        ours = [read_band(f"{work}/dl_{model}_{tag}.tif", band=b) for b in (1, 2, 3, 4)]
        print(f"\n{lt} {tz}, demlight --diffuse-model {model}:\n")
        print("| band | unit | demlight mean | r.sun mean | mean diff. | median diff. | MAE | p99 abs. | max abs. | r |")
        print("|---|---|---|---|---|---|---|---|---|---|")
        for name, o, t in zip(("beam", "diffuse", "reflected", "global"), ours, theirs):
            print(row(name, "W/m2", compare(o, t)))
        both = [(a > 0, c > 0) for a, c in zip(ours[0], theirs[0]) if math.isfinite(a) and math.isfinite(c)]
        differ = sum(1 for a, c in both if a != c)
        print(f"\nsunlit (beam > 0) in one tool only: {differ} of {len(both)} cells ({100 * differ / len(both):.2f} %)")
EOF
    exit 0
fi
IFS=, read -r -a lat_list <<<"$lats"
IFS=, read -r -a time_list <<<"$times"
rows="$work/rows.txt"
: >"$rows"
for t in "${time_list[@]}"; do
    doy=$(date -u -d "$t" +%-j)
    hours=$(date -u -d "$t" +%H:%M:%S | awk -F: '{ printf "%.6f", $1 + $2 / 60 + $3 / 3600 }')
    for lat in "${lat_list[@]}"; do
        dem="$work/flat_$lat.tif"
        flat_dem "$dem" "$lat" "$height" 0.00001
        read -r -a g < <(rsun_at "$dem" "$lat" long=lon civil_time=0 slope_value=0 day="$doy" time="$hours" \
            linke_value="$linke" albedo_value=0.2)
        "$demlight" -q irradiance "$dem" -o "$work/dl.tif" --time "$t" --linke "$linke" --albedo 0.2 --threads 1
        d=()
        for b in 1 2 3 4; do d+=("$(gdallocationinfo -valonly -b "$b" "$work/dl.tif" 1 1)"); done
        meta=$(gdalinfo "$work/dl.tif")
        del=$(sed -n 's/.*DEMLIGHT_SUN_ELEVATION_DEG=//p' <<<"$meta")
        dg0=$(sed -n 's/.*DEMLIGHT_EXTRATERRESTRIAL_WM2=//p' <<<"$meta")
        echo "$t $lat ${g[*]} $del $dg0 ${d[*]}" >>"$rows"
    done
done

python3 - "$rows" "$grass_version" "$height" "$linke" <<'EOF'
import math, sys
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
print(f"demlight irradiance vs {sys.argv[2]} r.sun mode 1 (civil_time=0), flat open ground at {sys.argv[3]} m,"
      f" longitude 0, Linke {sys.argv[4]}, albedo 0.2; W/m2 at the DEM's centre cell.\n")
print("| instant (UTC) | lat | sun elev. r.sun / demlight (deg) | G0 r.sun / demlight | beam r.sun / demlight |"
      " diffuse r.sun / demlight | global r.sun / demlight | global diff. |")
print("|---|---|---|---|---|---|---|---|")
for r in rows:
    t, lat = r[0], r[1]
    alt, az, g0, inc, b, d, rf, gl = map(float, r[2:10])
    del_, dg0, db, dd, dr, dgl = map(float, r[10:16])
    if not (alt > 0 or del_ > 0):
        print(f"| {t} | {lat} | {alt:.3f} / {del_:.3f} | | | | | sun down |")
        continue
    b, d, gl = (0.0 if math.isnan(v) else v for v in (b, d, gl))
    diff = dgl - gl
    rel = f"{100 * diff / gl:+.2f} %" if gl > 0 else "n/a"
    print(f"| {t} | {lat} | {alt:.3f} / {del_:.3f} | {g0:.1f} / {dg0:.1f} | {b:.1f} / {db:.1f} | {d:.1f} / {dd:.1f} |"
          f" {gl:.1f} / {dgl:.1f} | {diff:+.1f} ({rel}) |")
EOF
