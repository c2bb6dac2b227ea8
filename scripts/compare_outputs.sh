#!/usr/bin/env bash
# Runs every command of two demlight binaries on the samples and three shared DEMs and compares
# their outputs: band checksums and values (the md5 of each band's raw bytes), descriptions,
# units, nodata and DEMLIGHT_* metadata of every raster (DEMLIGHT_COMMAND and DEMLIGHT_INPUT
# excepted, band order ignored), the other files byte for byte. For refactors that must keep
# outputs identical.
#   scripts/compare_outputs.sh OLD_BIN NEW_BIN [WORK_DIR]
# IGNORE_KEYS="DEMLIGHT_PLAN ..." leaves out metadata items a change means to alter. Copy a
# binary elsewhere first if you rebuild while this runs.
set -uo pipefail
cd "$(dirname "$0")/.."
old=$1; new=$2; work=${3:-$(mktemp -d)}
S=$PWD/samples; D=$PWD/../shared/data/dem
dems="lux:$S/luxembourg_elev_terra.tif rocky:$S/rocky_mountain_np_dem.tif helens:$S/mount_st_helens_1980_usgs.dem"
for e in tujunga:$D/big_tujunga_srtm30m_utm11.tif olinda:$D/olinda_dem_utm25s.tif n44:$D/N44W072.hgt; do
  [ -f "${e#*:}" ] && dems="$dems $e"
done
T=2024-06-21T15:30:00Z
runAll() {  # BIN ROOT
  local bin=$1 root=$2
  for e in $dems; do
    local n=${e%%:*} f=${e#*:} o=$root/${e%%:*} a=$work/aux/${e%%:*}
    mkdir -p "$o" "$work/aux"
    if [ ! -f "$a.rgb.tif" ]; then
      gdal_translate -q -ot Float32 -b 1 -b 1 -b 1 -scale 0 5000 0 1 "$f" "$a.rgb.tif" -a_nodata none
      gdal_translate -q -ot Byte -b 1 -b 1 -b 1 -scale 0 5000 0 255 "$f" "$a.rgb8.tif" -a_nodata none
      gdal_translate -q -ot Float32 -scale 0 5000 0.3 1 "$f" "$a.cloud.tif" -a_nodata none
    fi
    r() { "$bin" -q "$@" >/dev/null 2>>"$o/stderr.txt" || echo "FAIL $n: $*" >> "$o/stderr.txt"; }
    r horizon "$f" -o "$o/h4.tif" --directions 4
    r horizon "$f" -o "$o/haz.tif" --azimuth 37.5 200
    [ "$n" = lux ] && r horizon "$f" -o "$o/href.tif" --azimuth 100 --method reference
    r sun "$f" -o "$o/sun.tif" --time $T
    r sun "$f" -o "$o/sunap.tif" --time $T --model aperture --directions 8
    r sun "$f" -o "$o/sunfull.tif" --time 2024-06-21T14:00:00Z --quality full
    r sky "$f" -o "$o/sky.tif"
    r sky "$f" -o "$o/skyp.tif" --patches sectors:4,bands:0,30,90 --albedo 0.4 --directions 8
    r sky "$f" -o "$o/skyh.tif" --model hemisphere
    r sky "$f" -o "$o/skyar.tif" --albedo-raster "$a.cloud.tif" --directions 8
    r aperture "$f" -o "$o/ap.tif"
    r light "$f" -o "$o/light.tif" --time $T
    r light "$f" -o "$o/lightc.tif" --time $T --color-raster "$a.rgb.tif" --sun-color 1,0.9,0.8 --cloud-shadow "$a.cloud.tif"
    r light "$f" -o "$o/lighth.tif" --time $T --model aperture-smooth --sky-model hemisphere --albedo 0.3
    r light "$f" -o "$o/lightn.tif" --time $T --sky-model none --albedo-raster "$a.cloud.tif"
    r render "$f" -o "$o/render.png" --time $T
    r render "$f" -o "$o/render8.png" --time $T --color-raster "$a.rgb8.tif" --exposure 1.5
    r timelapse "$f" -o "$o/tl" --start 2024-06-21T14:00:00Z --end 2024-06-21T16:00:00Z --step 1h --fit-degree 2
    r timelapse "$f" -o "$o/tli" --start 2024-06-21T14:00:00Z --end 2024-06-21T15:00:00Z --step 30m --horizon-mode interpolated:16 --formats tif
    r sunhours "$f" -o "$o/sh.tif" --date 2024-06-21 --tz UTC --step 30
    r sequence "$o/tl/sequence_fit.tif" -o "$o/seq.tif" --time 2024-06-21T15:10:00Z
    "$bin" info "$f" > "$o/info.txt" 2>&1; "$bin" info "$f" --json > "$o/info.json" 2>&1
  done
}
runAll "$old" "$work/old"; runAll "$new" "$work/new"
canon() {  # one line per band (sorted) and per DEMLIGHT_* item, without run-specific items
  gdalinfo -checksum "$1" | IGNORE_KEYS="${IGNORE_KEYS:-}" python3 -c '
import os, re, sys
ignored = tuple(k + "=" for k in os.environ["IGNORE_KEYS"].split())
meta, bands, cur = [], [], None
for line in sys.stdin:
    s = line.strip()
    if re.match(r"DEMLIGHT_(COMMAND|INPUT|TRUNCATION_MASK)=", s) or (ignored and s.startswith(ignored)): continue
    if line.startswith("Band "): cur = []; bands.append(cur); continue
    if cur is not None and line.startswith("  ") and not s.startswith("Block="): cur.append(s); continue
    if s.startswith(("DEMLIGHT_", "Size is", "Origin", "Pixel Size")): meta.append(s)
print("\n".join(sorted(meta) + sorted(" | ".join(b) for b in bands)))'
  # gdalinfo's checksum sums each Float32 value's integer part (0.5 and 0.9 give the same): the
  # values themselves, band by band (sorted like the bands), as the md5 of their raw bytes.
  local n i raw
  n=$(gdalinfo "$1" | grep -c '^Band ')
  raw=$(mktemp -d)
  for i in $(seq 1 "$n"); do
    gdal_translate -q -b "$i" -of ENVI "$1" "$raw/b.bin" && echo "values md5 $(md5sum < "$raw/b.bin" | cut -c1-32)"
  done | sort
  rm -rf "$raw"
}
same=0; differ=0
for f in $(cd "$work/old" && find . -type f ! -name stderr.txt | sort); do
  if [ ! -f "$work/new/$f" ]; then echo "MISSING $f"; differ=$((differ + 1)); continue; fi
  case $f in
    *.tif) if diff <(canon "$work/old/$f") <(canon "$work/new/$f") > "$work/diff.txt"; then same=$((same + 1));
           else differ=$((differ + 1)); echo "DIFF $f"; sed 's/^/    /' "$work/diff.txt" | cut -c1-200 | head -6; fi;;
    *) if cmp -s "$work/old/$f" "$work/new/$f"; then same=$((same + 1)); else differ=$((differ + 1)); echo "BYTES $f"; fi;;
  esac
done
for f in $(cd "$work/new" && find . -type f ! -name stderr.txt | sort); do [ -f "$work/old/$f" ] || echo "NEW $f"; done
echo "$same files the same, $differ different (outputs in $work)"
