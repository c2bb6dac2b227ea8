#!/usr/bin/env bash
# Installs a built tree (default build/release) into a temporary prefix with cmake --install,
# runs the installed CLI, and configures, builds and runs the C++ consumer example
# (examples/consumer, docs/cpp.md) against it. scripts/test.sh runs it after the Release tests.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build/release}"
prefix="$(mktemp -d)"
trap 'rm -rf "$prefix"' EXIT

cmake --install "$build" --prefix "$prefix" >/dev/null
"$prefix/bin/demlight" --version
# The installed CLI finds its picture plugin (libdemlight_oiio.so) in its own folder.
"$prefix/bin/demlight" -q render samples/mount_st_helens_1980_usgs.dem -o "$prefix/render.jpg" \
  --time 2024-06-21T07:30 --tz America/Los_Angeles
test -s "$prefix/render.jpg"

cmake -S examples/consumer -B "$prefix/consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$prefix/consumer" >/dev/null
"$prefix/consumer/consumer" samples/mount_st_helens_1980_usgs.dem 2024-06-21T07:30:00-07:00 | tee "$prefix/consumer.txt"
grep -q "cells see the sun" "$prefix/consumer.txt"
echo "check_install: the installed CLI and the consumer example work"
