#!/usr/bin/env bash
# Runs every fuzz target on the stable toolchain (no sanitizer) from a fresh copy of its seeds
# (fuzz/seeds/<target>), with a fixed libFuzzer seed so that a run is reproducible, bounded by a
# number of executions and a time cap, and prints the executions of each target.
# Every input has a time limit (libFuzzer's -timeout, default 10 s): a slow input is reported
# as a failure with the input saved, like a crash.
# Usage: fuzz/run.sh [MAX_SECONDS_PER_TARGET] [MAX_RUNS_PER_TARGET] [LIBFUZZER_SEED] [SECONDS_PER_INPUT]
# (needs `cargo install cargo-fuzz`)
set -euo pipefail
cd "$(dirname "$0")"
secs=${1:-30}
runs=${2:-1000000000}
seed=${3:-1}
per_input=${4:-10}
total=0
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cargo fuzz build --sanitizer none >/dev/null 2>&1 || cargo fuzz build --sanitizer none
for t in face_notation input_files automaton_file structure_files certificate certificate_forgery pipeline; do
  mkdir -p "$work/$t"
  cp seeds/"$t"/* "$work/$t/"
  log="$work/$t.log"
  if ! cargo fuzz run --sanitizer none "$t" "$work/$t" -- -seed="$seed" -runs="$runs" \
      -max_total_time="$secs" -timeout="$per_input" -max_len=8192 >"$log" 2>&1; then
    tail -40 "$log"
    echo "fuzz target $t FAILED (crash input saved under fuzz/artifacts/$t)"
    exit 1
  fi
  done_runs=$(grep -o 'Done [0-9]* runs' "$log" | awk '{print $2}' | tail -1)
  echo "fuzz target $t: ${done_runs:-0} executions, no crash"
  total=$((total + ${done_runs:-0}))
done
echo "fuzzing: $total executions in total, no crash"
