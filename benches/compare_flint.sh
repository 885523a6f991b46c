#!/usr/bin/env bash
# Issue #4 comparison: lacuna's exact sparse solver against FLINT (python-flint, dense fmpq_mat
# rref) on the same constraint systems, at every size FLINT finishes within 60 s.
# Installs python-flint in a virtual environment under target/ (nothing global).
set -euo pipefail
cd "$(dirname "$0")/.."
venv=target/bench-venv
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/pip" install -q "python-flint==0.9.0"
dir=target/bench-systems
rm -rf "$dir"
cargo bench --bench solver -- --export "$dir" | tee target/bench-solver.txt
cargo build --release --quiet
printf '\n%-9s %-12s %-12s %-9s %-14s %s\n' unknowns "lacuna (s)" "FLINT (s)" ratio "peak MB lacuna" face
grep -E '^ +[0-9]+ ' target/bench-solver.txt | while read -r k types unknowns equations secs consistent face; do
  mem=$( { /usr/bin/time -f '%M' ./target/release/lacuna solve "$face" >/dev/null; } 2>&1 | tail -1 )
  mem_mb=$(( mem / 1024 ))
  flint="-"; ratio="-"
  if [ -f "$dir/system_$k.txt" ]; then
    if out=$(timeout 60 "$venv/bin/python" benches/flint_rref.py "$dir/system_$k.txt" 2>/dev/null); then
      flint=$(echo "$out" | awk '{print $3}')
      ratio=$(awk -v a="$flint" -v b="$secs" 'BEGIN { printf "%.0fx", a / b }')
    else
      flint=">60"
    fi
  fi
  printf '%-9s %-12s %-12s %-9s %-14s %s\n' "$unknowns" "$secs" "$flint" "$ratio" "$mem_mb" "$face"
done
