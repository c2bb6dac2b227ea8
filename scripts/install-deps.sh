#!/usr/bin/env bash
# Installs the Debian 12 packages demlight needs, only those that are missing (clang and its
# runtime libraries: the asan preset and the libFuzzer targets; help2man: the man page; fonts-dejavu-core:
# the text of quicklook's pictures; ffmpeg:
# timelapse --formats mp4 and its tests; qgis,
# python3-qgis and python3-pytest: the QGIS provider's tests, qgis/tests; python3-venv and
# python3-pip: the tests that pip-install demlight into fresh virtual environments).
# Runs apt-get as root, or through sudo when not root.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libgdal-dev gdal-bin libgeographiclib-dev libopenimageio-dev openimageio-tools libglm-dev
  libgtest-dev libgmock-dev libcli11-dev libhowardhinnant-date-dev libtbb-dev
  nlohmann-json3-dev libdeflate-dev libtiff-dev libzstd-dev tzdata gnuplot-nox ffmpeg python3 help2man fonts-dejavu-core
  pybind11-dev python3-dev python3-numpy python3-dask python3-distributed python3-rioxarray python3-pytest
  python3-venv python3-pip
  clang libclang-rt-dev
  qgis python3-qgis
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "demlight: installing missing Debian packages: ${missing[*]}"
sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
