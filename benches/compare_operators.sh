#!/usr/bin/env bash
# Issue #16 comparison: `lacuna operators` against python-flint on the operators of a structure
# (default F0: its eleven self-mapping operators, six of them 9×9). Installs python-flint in a
# virtual environment under target/ (nothing global), exports the matrices with
# `lacuna operators F0 --json`, and times both on the same matrices in one run: FLINT in process,
# lacuna as a whole process and, in process, its kernel alone (benches/operators.rs; issue #34).
set -euo pipefail
cd "$(dirname "$0")/.."
input=${1:-F0}
venv=target/bench-venv
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/pip" install -q "python-flint==0.9.0"
cargo build --release --quiet
bin=${CARGO_TARGET_DIR:-target}/release/lacuna
# lacuna's kernel clock (benches/operators.rs), release profile: it shares the library just built.
kernel_bin=$(cargo build --release --quiet --bench operators --message-format=json \
  | sed -n 's|.*"executable":"\([^"]*/deps/operators-[^"]*\)".*|\1|p' | tail -1)
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
res=$("$venv/bin/python" benches/flint_operators.py "$dir/matrices.txt" "$bin")
echo "$res"
kernel=$("$kernel_bin" --matrices "$dir/matrices.txt" | sed -n 's/^lacuna kernel.*: \([0-9.]*\) s$/\1/p')
flint=$(echo "$res" | sed -n 's/^python-flint.*: wall \([0-9.]*\) s,.*/\1/p')
echo "lacuna kernel in process (analyse_matrix on each matrix, best of 20): wall $kernel s"
awk -v f="$flint" -v l="$kernel" 'BEGIN { printf "kernel ratio flint / lacuna: %.2fx (below 1: lacuna slower)\n", f / l }'
