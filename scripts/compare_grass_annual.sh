#!/usr/bin/env bash
# demlight insolation against GRASS GIS r.sun mode 2 (daily irradiation) in two parts:
#  1. flat ground, daily totals: synthetic flat DEMs at --lats (longitude 0, UTC days) on --days,
#     r.sun glob_rad against `demlight insolation --at` (the same Linke and albedo);
#  2. an annual total on a real DEM, timed: r.sun for --sample-days days spread over the year,
#     its CPU time extrapolated to 365 days, against one `demlight insolation --year` run, timed
#     before and after the r.sun runs (CPU = user + system, /usr/bin/time).
# Prints a Markdown report on stdout.
#
# Usage: scripts/compare_grass_annual.sh [--dem PATH] [--year Y] [--sample-days N] [--lats L,L,..]
#                                        [--days YYYY-MM-DD,..] [--linke L] [--albedo A]
#                                        [--rsun-step H] [--build DIR] [--flat-only] [--timing-only]
# Defaults: the N44W072 SRTM3 tile beside the repository (1201^2), 2024, 12 sample days (the 21st of
# each month), latitudes 0,30,50,70, days 2024-03-20,2024-06-21,2024-09-22,2024-12-21, Linke 3,
# albedo 0.2, r.sun step 0.5 h (its default) for the timing and 0.05 h for flat ground.
# Needs: grass (8.x, Debian package grass-core), gdal_create, gdal_translate, gdalinfo, python3,
# /usr/bin/python3 with numpy and GDAL's Python bindings, /usr/bin/time.
#
# r.sun runs single-threaded (nprocs=1) and demlight with --threads 1, so the CPU times compare
# one core's work. r.sun's day is the solar day; at longitude 0 the UTC day differs from it by the
# equation of time (at most 16 minutes, at night except in polar day).
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
dem="$root/../shared/data/dem/N44W072.hgt"
year=2024
sample_days=12
lats="0,30,50,70"
days="2024-03-20,2024-06-21,2024-09-22,2024-12-21"
linke=3
albedo=0.2
rsun_step=0.5
flat_step=0.05
build="$root/build/release"
flat=1
timing=1
while [[ $# -gt 0 ]]; do
    case "$1" in
        --dem) dem=$2; shift 2 ;;
        --year) year=$2; shift 2 ;;
        --sample-days) sample_days=$2; shift 2 ;;
        --lats) lats=$2; shift 2 ;;
        --days) days=$2; shift 2 ;;
        --linke) linke=$2; shift 2 ;;
        --albedo) albedo=$2; shift 2 ;;
        --rsun-step) rsun_step=$2; shift 2 ;;
        --build) build=$2; shift 2 ;;
        --flat-only) timing=0; shift ;;
        --timing-only) flat=0; shift ;;
        -h|--help) sed -n '2,/^# Needs/p' "$0"; exit 0 ;;
        *) echo "compare_grass_annual.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
    esac
done
for tool in grass gdal_create gdal_translate python3 /usr/bin/time; do
    command -v "$tool" >/dev/null || { echo "compare_grass_annual.sh: $tool is not installed" >&2; exit 1; }
done
demlight="$build/cli/demlight"
[[ -x "$demlight" ]] || { echo "compare_grass_annual.sh: build demlight first ($demlight)" >&2; exit 1; }
work=$(mktemp -d /tmp/demlight_grass_annual.XXXXXX)
trap 'rm -rf "$work"' EXIT
grass_version=$(grass --version 2>&1 | awk '/GRASS GIS/ && !found { print; found = 1 }')
doy() { date -u -d "$1" +%j | sed 's/^0*//'; }

if [[ $flat == 1 ]]; then
    echo "## Flat ground, daily totals"
    echo
    echo "$grass_version r.sun mode 2 (\`step=$flat_step\`, \`linke_value=$linke albedo_value=$albedo\`, slope 0) against \`demlight insolation --at\` (\`--step 2m\`, the same Linke and albedo), open flat ground at 500 m, longitude 0, UTC days. Global horizontal irradiation, Wh/m²/day."
    echo
    echo "| latitude | day | r.sun | demlight | difference |"
    echo "|---|---|---|---|---|"
    IFS=, read -ra lat_list <<<"$lats"
    IFS=, read -ra day_list <<<"$days"
    for lat in "${lat_list[@]}"; do
        # 3 x 3 cells of 1e-5 degree: one sun over the DEM (as scripts/compare_grass_irradiance.sh).
        tif="$work/flat_$lat.tif"
        gdal_create -q -of GTiff -ot Float32 -outsize 3 3 -bands 1 -burn 500 -a_srs EPSG:4326 \
            -a_ullr -0.000015 "$(python3 -c "print($lat + 0.000015)")" 0.000015 "$(python3 -c "print($lat - 0.000015)")" "$tif"
        {
            echo "r.in.gdal --q input=$tif output=dem"
            echo "g.region raster=dem"
            for d in "${day_list[@]}"; do
                echo "r.sun --q elevation=dem slope_value=0 aspect_value=0 day=$(doy "$d") step=$flat_step linke_value=$linke albedo_value=$albedo nprocs=1 glob_rad=g$(doy "$d")"
                echo "echo \"$d \$(r.what --q map=g$(doy "$d") coordinates=0,$lat | cut -d'|' -f4)\""
            done
        } >"$work/flat_job.sh"
        grass --tmp-location "$tif" --exec bash "$work/flat_job.sh" 2>/dev/null | grep -E '^[0-9]{4}-' >"$work/flat_$lat.txt"
        while read -r d rsun; do
            ours=$("$demlight" -q insolation "$tif" --at "$lat,0" --date "$d" --tz UTC --step 2m --linke "$linke" \
                --albedo "$albedo" --point-format csv | tail -1 | cut -d, -f6)
            python3 -c "r=$rsun; o=$ours*1000; rel=f'({(o-r)/r*100:+.2f} %)' if r > 0 else '(no sun)'; print(f'| {$lat} | $d | {r:.1f} | {o:.1f} | {o-r:+.1f} {rel} |')"
        done <"$work/flat_$lat.txt"
    done
    echo
fi

if [[ $timing == 1 ]]; then
    info=$(gdalinfo "$dem")
    read -r w h < <(sed -n 's/^Size is \([0-9]*\), \([0-9]*\)/\1 \2/p' <<<"$info")
    gdal_translate -q "$dem" "$work/dem.tif"
    ours_time() {
        /usr/bin/time -f '%U %S %e' -o "$work/t_ours_$1.txt" "$demlight" -q insolation "$work/dem.tif" \
            -o "$work/year_$1.tif" --year "$year" --tz UTC --linke "$linke" --albedo "$albedo" \
            --diffuse-model rsun --threads 1
    }
    ours_time 1
    # The sample days: evenly spread over the year, the 21st of each month for 12.
    days_of_year=$(python3 -c "
n = $sample_days
import datetime
days = [datetime.date($year, m, 21) for m in range(1, 13)] if n == 12 else \
       [datetime.date($year, 1, 1) + datetime.timedelta(days=int((i + 0.5) * 365 / n)) for i in range(n)]
print(' '.join(str(d.timetuple().tm_yday) for d in days))")
    {
        echo "r.in.gdal --q input=$work/dem.tif output=dem"
        echo "g.region raster=dem"
        echo "r.slope.aspect --q -e elevation=dem slope=slope aspect=aspect"
        for d in $days_of_year; do
            echo "/usr/bin/time -f '$d %U %S %e' -a -o $work/t_rsun.txt r.sun --q elevation=dem slope=slope aspect=aspect day=$d step=$rsun_step linke_value=$linke albedo_value=$albedo nprocs=1 glob_rad=g$d"
            echo "echo \"mean $d \$(r.univar -g map=g$d | sed -n 's/^mean=//p')\""
        done
    } >"$work/year_job.sh"
    grass --tmp-location "$work/dem.tif" --exec bash "$work/year_job.sh" 2>/dev/null | grep '^mean ' >"$work/rsun_means.txt"
    ours_time 2
    ours_mean=$(/usr/bin/python3 -c "
from osgeo import gdal
import numpy as np
ds = gdal.Open('$work/year_1.tif')  # kept while its band is read
print(np.nanmean(ds.GetRasterBand(4).ReadAsArray().astype(float)))")
    python3 - "$work" "$sample_days" "$w" "$h" "$ours_mean" "$rsun_step" "$grass_version" "$year" <<'EOF'
import sys
work, n, w, h, ours_mean, step, version, year = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4], float(sys.argv[5]), sys.argv[6], sys.argv[7], sys.argv[8]
rsun = [line.split() for line in open(f"{work}/t_rsun.txt")]
cpu = [float(u) + float(s) for _, u, s, _ in rsun]
means = [float(line.split()[2]) for line in open(f"{work}/rsun_means.txt")]
ours = [open(f"{work}/t_ours_{k}.txt").read().split() for k in (1, 2)]
ours_cpu = [float(u) + float(s) for u, s, _ in ours]
year_cpu = sum(cpu) / len(cpu) * 365
print("## Annual total, timed")
print()
print(f"{w} x {h} cells; {version} r.sun mode 2 (`step={step}`, its default; `nprocs=1`) on {len(cpu)} days of {year}, "
      f"against `demlight insolation --year {year} --tz UTC --diffuse-model rsun --threads 1` (default 10 min step, "
      "64 sectors, 2° bands). CPU time = user + system.")
print()
print("| run | CPU time (s) |")
print("|---|---|")
print(f"| r.sun, one day (mean of {len(cpu)}; min {min(cpu):.1f}, max {max(cpu):.1f}) | {sum(cpu) / len(cpu):.1f} |")
print(f"| r.sun, 365 days (extrapolated) | {year_cpu:.0f} |")
print(f"| demlight, the year (before / after the r.sun runs) | {ours_cpu[0]:.1f} / {ours_cpu[1]:.1f} |")
print(f"| ratio, r.sun's year / demlight's | {year_cpu / max(ours_cpu):.0f}x to {year_cpu / min(ours_cpu):.0f}x |")
print()
print(f"Global irradiation, mean over the DEM: r.sun's sample days scaled to 365 days {sum(means) / len(means) * 365 / 1000:.0f} "
      f"kWh/m²; demlight's year {ours_mean:.0f} kWh/m².")
EOF
fi
