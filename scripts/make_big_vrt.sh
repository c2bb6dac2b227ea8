#!/usr/bin/env bash
# Writes a VRT larger than memory for the tiling benchmark (docs/performance.md, "A DEM larger
# than memory"): one real 1-arc-second tile repeated N x N times at 3600-cell steps, cut to
# SIZE x SIZE cells. Usage: scripts/make_big_vrt.sh TILE.tif OUT.vrt [SIZE=40000]
# e.g. scripts/make_big_vrt.sh ../shared/data/dem/N48W125_srtm1.tif big40k.vrt
set -euo pipefail
tile=${1:?usage: make_big_vrt.sh TILE.tif OUT.vrt [SIZE]}
out=${2:?usage: make_big_vrt.sh TILE.tif OUT.vrt [SIZE]}
size=${3:-40000}
step=3600
tile_abs=$(realpath "$tile")
read -r x0 y0 px <<<"$(gdalinfo -json "$tile_abs" | python3 -c '
import json, sys
g = json.load(sys.stdin)["geoTransform"]
print(g[0], g[3], g[1])')"
srs=$(gdalsrsinfo -o wkt "$tile_abs" | tr -d '\n' | sed 's/&/\&amp;/g; s/</\&lt;/g; s/>/\&gt;/g; s/"/\&quot;/g')
n=$(( (size + step - 1) / step ))
{
  echo "<VRTDataset rasterXSize=\"$size\" rasterYSize=\"$size\">"
  echo "  <SRS>$srs</SRS>"
  echo "  <GeoTransform>$x0, $px, 0, $y0, 0, -$px</GeoTransform>"
  echo "  <VRTRasterBand dataType=\"Int16\" band=\"1\">"
  echo "    <NoDataValue>-32768</NoDataValue>"
  for ((j = 0; j < n; ++j)); do
    for ((i = 0; i < n; ++i)); do
      echo "    <SimpleSource><SourceFilename relativeToVRT=\"0\">$tile_abs</SourceFilename><SourceBand>1</SourceBand>"
      echo "      <SrcRect xOff=\"0\" yOff=\"0\" xSize=\"$step\" ySize=\"$step\"/><DstRect xOff=\"$((i * step))\" yOff=\"$((j * step))\" xSize=\"$step\" ySize=\"$step\"/></SimpleSource>"
    done
  done
  echo "  </VRTRasterBand>"
  echo "</VRTDataset>"
} > "$out"
gdalinfo "$out" | grep -E '^Size is'
