#!/usr/bin/env bash
# Runs every fuzz target for a bounded time on the stable toolchain (no sanitizer), starting
# from the seeds in fuzz/seeds/<target>, and prints the number of executions of each.
# Usage: fuzz/run.sh [SECONDS_PER_TARGET]   (needs `cargo install cargo-fuzz`)
set -euo pipefail
cd "$(dirname "$0")"
secs=${1:-30}
total=0
for t in face_notation input_files automaton_file certificate pipeline; do
  mkdir -p "corpus/$t"
  cp -n seeds/"$t"/* "corpus/$t/" 2>/dev/null || true
  log=$(mktemp)
  if ! cargo fuzz run --sanitizer none "$t" "corpus/$t" -- -max_total_time="$secs" -max_len=4096 >"$log" 2>&1; then
    tail -40 "$log"
    echo "fuzz target $t FAILED (crash input saved under fuzz/artifacts/$t)"
    exit 1
  fi
  runs=$(grep -o 'Done [0-9]* runs' "$log" | awk '{print $2}' | tail -1)
  echo "fuzz target $t: ${runs:-0} executions in ${secs}s, no crash"
  total=$((total + ${runs:-0}))
done
echo "fuzzing: $total executions in total, no crash"
