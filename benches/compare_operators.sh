#!/usr/bin/env bash
# Issue #16 comparison: `lacuna operators` against python-flint on the operators of a structure
# (default F0: its eleven self-mapping operators, six of them 9×9). Installs python-flint in a
# virtual environment under target/ (nothing global), exports the matrices with
# `lacuna operators F0 --json`, and times both on the same matrices in one run.
set -euo pipefail
cd "$(dirname "$0")/.."
input=${1:-F0}
venv=target/bench-venv
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/pip" install -q "python-flint==0.9.0"
cargo build --release --quiet
bin=${CARGO_TARGET_DIR:-target}/release/lacuna
dir=target/bench-operators
mkdir -p "$dir"
start=$(date +%s.%N)
"$bin" operators "$input" --json > "$dir/report.json"
end=$(date +%s.%N)
echo "lacuna operators $input --json: $(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f", b - a }') s (instantiation included)"
"$venv/bin/python" -c '
import json, sys
d = json.load(open(sys.argv[1]))
for op in d["automaton"]["operators"]:
    print(op["matrix"])
' "$dir/report.json" > "$dir/matrices.txt"
"$venv/bin/python" benches/flint_operators.py "$dir/matrices.txt" "$bin"
