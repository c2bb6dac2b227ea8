#!/usr/bin/env bash
# Packs the demlight Processing provider as a QGIS plugin zip (docs/qgis.md): the folder
# demlight_processing/ with its metadata.txt, as QGIS's Plugins > Manage and Install Plugins >
# Install from ZIP takes it.
#   qgis/package.sh [OUT.zip]      (default: build/demlight_processing-VERSION.zip)
# The zip holds no path of this machine: the installed plugin finds the CLI in the provider's
# setting (Settings > Options > Processing > Providers > demlight), $DEMLIGHT_EXECUTABLE or PATH.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
version="$(sed -n 's/^version=//p' "$here/demlight_processing/metadata.txt")"
out="${1:-$here/../build/demlight_processing-$version.zip}"
mkdir -p "$(dirname "$out")"
out="$(cd "$(dirname "$out")" && pwd)/$(basename "$out")"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
cp -r "$here/demlight_processing" "$scratch/"
rm -rf "$scratch/demlight_processing/__pycache__" "$scratch/demlight_processing/executable"
(cd "$scratch" && /usr/bin/env python3 - "$out" <<'PY'
import os, sys, zipfile
out = sys.argv[1]
tmp = out + ".part"
with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
    for folder, dirs, files in os.walk("demlight_processing"):
        dirs.sort()
        for name in sorted(files):
            z.write(os.path.join(folder, name))
os.replace(tmp, out)
PY
)
echo "wrote $out (install it in QGIS: Plugins > Manage and Install Plugins > Install from ZIP)"
