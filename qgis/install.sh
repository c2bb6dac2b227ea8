#!/usr/bin/env bash
# Installs the demlight Processing provider into a QGIS profile and enables it (docs/qgis.md).
#   qgis/install.sh [--profile NAME] [--executable PATH] [--link]
# --profile     QGIS profile (default: default). The profiles folder is $QGIS_CUSTOM_CONFIG_PATH/profiles
#               when that is set (as QGIS itself reads it), else ~/.local/share/QGIS/QGIS3/profiles.
# --executable  the demlight CLI the provider runs (default: build/release/cli/demlight when built,
#               else demlight on PATH); recorded in the installed plugin.
# --link        symlink the plugin folder instead of copying it (for working on the provider;
#               the executable is then not recorded: set DEMLIGHT_EXECUTABLE or PATH).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
profile=default
executable=""
link=0
while [ $# -gt 0 ]; do
  case "$1" in
    --profile) profile="$2"; shift 2 ;;
    --executable) executable="$2"; shift 2 ;;
    --link) link=1; shift ;;
    -h|--help) sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "qgis/install.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done

if [ -z "$executable" ]; then
  if [ -x "$here/../build/release/cli/demlight" ]; then
    executable="$here/../build/release/cli/demlight"
  else
    executable="$(command -v demlight || true)"
  fi
fi
if [ -z "$executable" ] || [ ! -x "$executable" ]; then
  echo "qgis/install.sh: no demlight executable (build it with scripts/build.sh, or pass --executable PATH)" >&2
  exit 1
fi
executable="$(cd "$(dirname "$executable")" && pwd)/$(basename "$executable")"

profiles="${QGIS_CUSTOM_CONFIG_PATH:-$HOME/.local/share/QGIS/QGIS3}/profiles"
plugins="$profiles/$profile/python/plugins"
target="$plugins/demlight_processing"
mkdir -p "$plugins"
rm -rf "$target"
if [ "$link" -eq 1 ]; then
  ln -s "$here/demlight_processing" "$target"
else
  cp -r "$here/demlight_processing" "$target"
  rm -rf "$target/__pycache__"
  echo "$executable" > "$target/executable"
fi
echo "installed the demlight provider into $target (CLI: $executable)"

# Enable it: qgis_process loads only enabled plugins. Debian 12's /usr/bin/qgis_process wrapper
# passes an option 3.22 rejects (docs/qgis.md), so use the program it wraps when there is one.
qgis_process="$(command -v qgis_process.bin || command -v qgis_process || true)"
if [ -z "$qgis_process" ]; then
  echo "qgis_process not found: enable 'demlight' in QGIS's Plugins > Manage and Install Plugins"
  exit 0
fi
export QT_QPA_PLATFORM="${QT_QPA_PLATFORM:-offscreen}"
if [ "$profile" != default ]; then
  echo "enable the plugin in QGIS (profile $profile): qgis_process enables plugins in the default profile"
  exit 0
fi
"$qgis_process" plugins enable demlight_processing 2>&1 | grep -v -e "^QStandardPaths" -e "DeprecationWarning" || true

# Debian 12's wrapper adds QGIS_OPTS from /etc/default/qgis (--noversioncheck), which
# qgis_process 3.22 refuses ("Command --noversioncheck not known!"): say what works instead.
if [ "$qgis_process" != "$(command -v qgis_process || true)" ] && [ -r /etc/default/qgis ] &&
   grep -q -- "--noversioncheck" /etc/default/qgis; then
  echo "note: Debian's qgis_process wrapper fails here (it passes --noversioncheck, which qgis_process"
  echo "      refuses); run the program it wraps instead, e.g.:"
  echo "      $qgis_process run demlight:sun -- INPUT=dem.tif TIME=2024-06-21T09:00 TZ=Europe/Zurich OUTPUT=sun.tif"
fi
