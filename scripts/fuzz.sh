#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/, in the asan build: AddressSanitizer + UBSan) and runs each
# for SECONDS, two at a time (one per core). Fails if any target crashes, hangs, leaks or goes
# past the memory cap; the input that did it is kept in build/asan/fuzz-runs/<target>/artifacts/.
# Usage: scripts/fuzz.sh SECONDS
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:?usage: scripts/fuzz.sh SECONDS}
jobs=${FUZZ_JOBS:-2}
targets=(time duration patches cli_args paths dem_open)
# Memory cap per input (MB): the DEM opener must not hold memory in proportion to a declared
# size; the sanitizers' own share is well under it.
rss_limit_mb=1024

scripts/install-deps.sh
cmake --preset asan >/dev/null
cmake --build --preset asan --target demlight_fuzzers

# One target: a working corpus that grows across runs (seeded from fuzz/corpus/<target>), its
# log, and its exit status in status.txt.
run_target() {
  local name=$1 dir=build/asan/fuzz-runs/$1
  mkdir -p "$dir/corpus" "$dir/artifacts"
  set +e
  "build/asan/fuzz/demlight_fuzz_$name" "$dir/corpus" "fuzz/corpus/$name" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb="$rss_limit_mb" -print_final_stats=1 -close_fd_mask=1 \
    -artifact_prefix="$dir/artifacts/" >"$dir/log.txt" 2>&1
  echo $? >"$dir/status.txt"
}

for name in "${targets[@]}"; do
  run_target "$name" &
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
done
wait

failed=0 total=0
for name in "${targets[@]}"; do
  dir=build/asan/fuzz-runs/$name
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$dir/log.txt" | tail -1)
  total=$((total + ${runs:-0}))
  if [ "$(cat "$dir/status.txt")" = 0 ]; then
    echo "fuzz $name: ${runs:-?} executions in ${seconds} s, no crash"
  else
    failed=1
    echo "fuzz $name: FAILED after ${runs:-?} executions (log $dir/log.txt, input in $dir/artifacts/):"
    grep -m1 -E "ERROR|runtime error|_fuzz:" "$dir/log.txt" || tail -5 "$dir/log.txt"
  fi
done
echo "fuzz: $total executions in all"
exit "$failed"
