#!/usr/bin/env bash
# Runs each fuzz target of BUILD_DIR for SECONDS (make fuzz): from the generated seeds, the corpus
# kept in BUILD_DIR/fuzz-corpus/TARGET and the findings in tests/data/fuzz/TARGET, where a new
# crashing, leaking, out-of-memory or too slow (over 30 s) input is written. Exit 1 when a target
# found one.
# Usage: fuzz/run.sh BUILD_DIR SECONDS
set -uo pipefail
build="$1"
seconds="$2"
cd "$(dirname "$0")/.."
"$build/lrvd_fuzz_seeds" "$build/fuzz-seeds" > /dev/null || exit 1
status=0
for target in mesh_file point_files compute; do
  corpus="$build/fuzz-corpus/$target"
  findings="tests/data/fuzz/$target"
  mkdir -p "$corpus" "$findings"
  log="$build/fuzz-$target.log"
  # Known findings are replayed by the unit tests; here they only seed the corpus (-merge-free).
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    "$build/fuzz_$target" -max_total_time="$seconds" -timeout=30 -report_slow_units=30 -rss_limit_mb=2560 -max_len=4096 \
    -print_final_stats=1 -close_fd_mask=1 -artifact_prefix="$findings/" \
    "$corpus" "$build/fuzz-seeds/$target" > "$log" 2>&1
  rc=$?
  runs=$(grep -ao 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$')
  echo "fuzz $target: ${runs:-?} runs in ${seconds} s, exit $rc (log: $log)"
  if [ "$rc" -ne 0 ]; then
    status=1
    grep -aE '^(==[0-9]+==ERROR|SUMMARY|artifact_prefix|Test unit written)' "$log" | head -5
  fi
done
exit $status
