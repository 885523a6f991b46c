#!/usr/bin/env bash
# Issue #3 comparison: lacuna's exact limit ratio (50 digits) against SymPy on the same matrices.
# Installs SymPy in a virtual environment under target/ (nothing global).
set -euo pipefail
cd "$(dirname "$0")/.."
venv=target/bench-venv
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/pip" install -q "sympy==1.14.0"
dir=target/bench-ratio
rm -rf "$dir"
cargo bench --bench ratio -- --export "$dir"
for f in "$dir"/ratio_*.json; do
  timeout 600 "$venv/bin/python" benches/sympy_ratio.py "$f" || echo "$f: SymPy did not finish within 600 s"
done
