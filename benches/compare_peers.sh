#!/usr/bin/env bash
# Issue #34: lacuna against each named peer, re-measured in one run, printed as one table of
# ratios (peer seconds / lacuna seconds: above 1 means lacuna is faster). docs/PERFORMANCE.md
# says what every row compares and holds the table of a run.
#
#   benches/compare_peers.sh            small and medium sizes (under a minute once built)
#   FULL=1 benches/compare_peers.sh     every constraint system of the solver bench (up to 1.2
#                                       million unknowns; SymPy then needs about 2 GB)
#   PEER_BIN=/path/to/AutoFrac2DCLI benches/compare_peers.sh
#                                       also times the seed authors' tool (PEER_ARGS: the
#                                       arguments placed before the input file, default -a: the
#                                       files give the corner points only)
#
# Rows: closure (AutoFrac2DCLI), solve (SymPy sparse DomainMatrix rref), R digits (SymPy/mpmath),
# operators (python-flint), STL throughput (a plain Python struct writer). The Python peers go
# into a virtual environment under target/ (nothing global). A missing peer makes its rows
# "skipped: reason"; the run goes on.
set -euo pipefail
# PEER_BIN as given from the caller's directory, or found on PATH, made absolute before moving.
if [ -n "${PEER_BIN:-}" ]; then
  case $PEER_BIN in
    /*) ;;
    */*) PEER_BIN=$PWD/$PEER_BIN ;;
    *) PEER_BIN=$(command -v "$PEER_BIN" || echo "$PEER_BIN") ;;
  esac
fi
cd "$(dirname "$0")/.."

full=${FULL:-0}
target=${CARGO_TARGET_DIR:-target}
mkdir -p "$target"
target=$(cd "$target" && pwd)
out=$target/bench-peers
venv=$target/bench-venv
rm -rf "$out"
mkdir -p "$out"
rows=$out/rows.txt
: > "$rows"

# One table row: what, lacuna s, peer s, ratio, lacuna peak MB, peer peak MB, note.
row() {
  local IFS='|'
  echo "$*" >> "$rows"
}

# Seconds elapsed since a `date +%s.%N` stamp.
since() {
  awk -v a="$1" -v b="$(date +%s.%N)" 'BEGIN { printf "%.4f", b - a }'
}

# Best wall-clock seconds of $1 runs of the command that follows (its output discarded); fails
# when one run fails.
best_of() {
  local runs=$1 best="" t s
  shift
  for _ in $(seq "$runs"); do
    s=$(date +%s.%N)
    "$@" > /dev/null 2>&1 || return 1
    t=$(since "$s")
    best=$(awk -v a="$best" -v b="$t" 'BEGIN { if (a == "" || b < a) print b; else print a }')
  done
  echo "$best"
}

# Peak resident memory in MB of one run of the command that follows, "-" without /usr/bin/time.
peak_mb() {
  if [ -x /usr/bin/time ] && /usr/bin/time -f '%M' -o "$out/peak" "$@" > /dev/null 2>&1; then
    awk '{ printf "%.0f", $1 / 1024 }' "$out/peak"
  else
    echo "-"
  fi
}

# peer / lacuna, "-" when either is not a number of seconds.
ratio() {
  awk -v p="$1" -v l="$2" 'BEGIN {
    if (p !~ /^[0-9.]+$/ || l !~ /^[0-9.]+$/ || l <= 0) { print "-"; exit }
    r = p / l
    if (r >= 10) printf "%.0fx", r; else printf "%.2fx", r }'
}

# The load average before and after, printed with the table: the machine may be shared.
load() { cut -d ' ' -f 1-3 /proc/loadavg 2> /dev/null || echo "?"; }

echo "== build (release) and benches" >&2
cargo build --release --quiet
# The in-process clock of lacuna's operator kernel (benches/operators.rs), built with the release
# profile so that it shares the library just built.
kernel_bin=$(cargo build --release --quiet --bench operators --message-format=json \
  | sed -n 's|.*"executable":"\([^"]*/deps/operators-[^"]*\)".*|\1|p' | tail -1)
load_before=$(load)
bin=$target/release/lacuna

# Python peers: one venv, pinned versions. Without python3 or PyPI their rows are skipped.
py=""
py_reason=""
if ! command -v python3 > /dev/null; then
  py_reason="no python3"
elif ! { [ -x "$venv/bin/python" ] || python3 -m venv "$venv"; }; then
  py_reason="python3 -m venv failed"
elif ! "$venv/bin/pip" install -q "sympy==1.14.0" "python-flint==0.9.0"; then
  py_reason="pip install sympy==1.14.0 python-flint==0.9.0 failed"
else
  py=$venv/bin/python
fi
# Whether the venv's Python imports module $1 (sets py_reason when not).
has_module() {
  if [ -z "$py" ]; then
    return 1
  elif ! "$py" -c "import $1" 2> /dev/null; then
    py_reason="python module $1 not importable"
    return 1
  fi
}

# 1. closure against AutoFrac2DCLI on AutoFrac2D input files. lacuna's side is what the tool
# produces from such a file: the closure and the MODITERE model (`export --format moditere`);
# on the wide faces, whose constraint systems are far larger than the tool's output, the closure
# alone (`lacuna closure`). Every file gives the corner points of its faces, which is what the
# tool reads with -a (it reads past the end of its list of points without them).
echo "== 1. closure (AutoFrac2DCLI)" >&2
peer_args=${PEER_ARGS--a}
# A one-face AutoFrac2D file: the face line $2 and its corners on a circle, into $1.
autofrac_face() {
  printf 'f\n%s\nc\np\n' "$2" > "$1"
  awk -v n="$(echo "${2%% / *}" | awk -F ' - ' '{ print NF }')" 'BEGIN {
    for (i = 0; i < n; i++) printf "%.6f %.6f\n", 100 * cos(6.283185307 * i / n), 100 * sin(6.283185307 * i / n) }' >> "$1"
}
cp fixtures/autofrac-two-quads.txt "$out/two-quads.txt"
autofrac_face "$out/twenty-types.txt" "B_4_0 - C_4_0 - B_3_2 - C_4_0 - B_4_0 - C_3_0 - B_2_1 / C_3_0 - B_2_0 - C_3_0 / 0 / 0"
# Wide faces: E's edges (or some boundary edges) of 800 and 2000 sub-edges, so that every type's
# step has thousands of sub-faces; the closure is the whole work. Issue #34's memory figures.
autofrac_face "$out/wide-800.txt" "B_4_0 - C_4_0 - B_3_2 - C_4_0 - B_4_0 - C_3_0 - B_2_1 / C_800_0 - B_800_0 - C_800_0 / 0 / 0"
autofrac_face "$out/wide-2000.txt" "B_4_0 - C_4_0 - B_3_2 - C_4_0 - B_4_0 - C_3_0 - B_2_1 / C_2000_0 - B_2000_0 - C_2000_0 / 0 / 0"
autofrac_face "$out/wide-800-boundary.txt" "B_800_0 - C_800_0 - B_3_2 - C_4_0 - B_4_0 - C_3_0 - B_2_1 / C_800_0 - B_800_0 - C_800_0 / 0 / 0"
# Rows: (input, lacuna's side). The small files get two rows: lacuna's closure alone (the part
# of the tool's work that lacuna also does the same way), and lacuna's MODITERE export, which
# writes the same kind of model but with the exact particular solution of the constraint system
# in it (the tool leaves the solve to MODITERE). The wide faces get the closure alone.
for job in two-quads:closure two-quads:export twenty-types:closure twenty-types:export \
  wide-800:closure wide-2000:closure wide-800-boundary:closure; do
  input=${job%%:*}
  file=$out/$input.txt
  extra=()
  case $input in wide-*) extra=(--max-subedges 2000) ;; esac
  types=$("$bin" closure "$file" "${extra[@]}" | awk '/^closure:/ { print $3; exit }')
  case ${job##*:} in
    closure)
      lac=$(best_of 5 "$bin" closure "$file" "${extra[@]}")
      lac_mb=$(peak_mb "$bin" closure "$file" "${extra[@]}")
      what="closure, $input.txt ($types types)"
      ;;
    export)
      lac=$(best_of 5 "$bin" export "$file" --format moditere -o "$out/$input.py")
      lac_mb=$(peak_mb "$bin" export "$file" --format moditere -o "$out/$input.py")
      unknowns=$("$bin" solve "$file" | awk '/^unknowns/ { sub(",", "", $2); print $2; exit }')
      what="closure + MODITERE model, $input.txt ($types types; lacuna also solves $unknowns unknowns)"
      ;;
  esac
  if [ -z "${PEER_BIN:-}" ]; then
    row "$what" "$lac" "-" "-" "$lac_mb" "-" "skipped: set PEER_BIN"
  elif [ ! -x "$PEER_BIN" ]; then
    row "$what" "$lac" "-" "-" "$lac_mb" "-" "skipped: PEER_BIN $PEER_BIN is not executable"
  else
    mkdir -p "$out/peer-$input"
    # shellcheck disable=SC2086 # PEER_ARGS is a list of words
    if peer=$(cd "$out/peer-$input" && best_of 5 timeout 600 "$PEER_BIN" $peer_args "$file"); then
      peer_mb=$(cd "$out/peer-$input" && peak_mb timeout 600 "$PEER_BIN" $peer_args "$file")
      row "$what" "$lac" "$peer" "$(ratio "$peer" "$lac")" "$lac_mb" "$peer_mb" "whole processes, best of 5"
    else
      row "$what" "$lac" "-" "-" "$lac_mb" "-" "skipped: $PEER_BIN failed or ran over 600 s"
    fi
  fi
done

# 2. solve against SymPy's sparse DomainMatrix rref, on the systems the solver bench exports.
# Default: the systems of at most 10,000 unknowns. FULL=1: every system of the series, up to
# 1.2 million unknowns (SymPy then needs about 2 GB and some seconds for the largest).
echo "== 2. solve (SymPy sparse DomainMatrix rref)" >&2
max_unknowns=10000
[ "$full" = 1 ] && max_unknowns=999999999
EXPORT_MAX_UNKNOWNS=$max_unknowns cargo bench --quiet --bench solver -- --export "$out/systems" \
  | tee "$out/solver.txt" >&2
grep -E '^ +[0-9]+ ' "$out/solver.txt" | while read -r k _types unknowns equations _build secs consistent face; do
  [ "$unknowns" -le "$max_unknowns" ] || continue
  what="solve, $unknowns unknowns × $equations equations"
  # The million-unknown system is estimated above solve's default memory limit of 1 GiB.
  lac_mb=$(peak_mb "$bin" solve "$face" --max-memory 16384)
  if [ ! -f "$out/systems/system_$k.txt" ]; then
    row "$what" "$secs" "-" "-" "$lac_mb" "-" "skipped: the bench did not export this system"
  elif ! has_module sympy; then
    row "$what" "$secs" "-" "-" "$lac_mb" "-" "skipped: $py_reason"
  elif res=$(timeout 600 "$py" benches/sympy_rref.py "$out/systems/system_$k.txt"); then
    read -r rank_a rank_ab peer ground <<< "$res"
    peer_mb=$(peak_mb "$py" benches/sympy_rref.py "$out/systems/system_$k.txt")
    agree="SymPy inconsistent"
    [ "$rank_a" = "$rank_ab" ] && [ "$consistent" = true ] && agree="both consistent"
    row "$what" "$secs" "$peer" "$(ratio "$peer" "$secs")" "$lac_mb" "$peer_mb" "rank $rank_a, $agree; SymPy ground types $ground"
  else
    row "$what" "$secs" ">600" "-" "$lac_mb" "-" "SymPy did not finish within 600 s"
  fi
done

# 3. R to 50 digits against SymPy (charpoly, real roots, exact eigenvector over Q(rho), mpmath
# evaluation), on the closures the ratio bench exports.
echo "== 3. R digits (SymPy/mpmath)" >&2
cargo bench --quiet --bench ratio -- --export "$out/ratio" | tee "$out/ratio.txt" >&2
for f in "$out"/ratio/ratio_*.json; do
  k=${f##*_}
  k=${k%.json}
  # Columns 2 and 3 of the bench's line: types and seconds (the Perron root may hold spaces).
  line=$(grep -E "^ +$k " "$out/ratio.txt")
  types=$(echo "$line" | awk '{ print $2 }')
  lac=$(echo "$line" | awk '{ print $3 }')
  face=$(sed -n 's/.*"face":"\([^"]*\)".*/\1/p' "$f")
  what="R to 50 digits, $types types"
  lac_mb=$(peak_mb "$bin" ratio "$face")
  if ! has_module sympy; then
    row "$what" "$lac" "-" "-" "$lac_mb" "-" "skipped: $py_reason"
  elif res=$(timeout 600 "$py" benches/sympy_ratio.py "$f"); then
    peer=$(echo "$res" | sed -n 's/.*: sympy \([0-9.]*\) s,.*/\1/p')
    sym=$(echo "$res" | sed -n 's/.*R sympy \([0-9.]*\) lacuna.*/\1/p')
    ours=$(echo "$res" | sed -n 's/.* lacuna \([0-9.]*\)$/\1/p')
    if [ -z "$peer" ]; then
      row "$what" "$lac" "-" "-" "$lac_mb" "-" "SymPy: $res"
      continue
    fi
    agree="digits differ"
    [ -n "$sym" ] && [ "$sym" = "$ours" ] && agree="all 50 digits agree"
    peer_mb=$(peak_mb "$py" benches/sympy_ratio.py "$f")
    row "$what" "$lac" "$peer" "$(ratio "$peer" "$lac")" "$lac_mb" "$peer_mb" "$agree"
  else
    row "$what" "$lac" ">600" "-" "$lac_mb" "-" "SymPy did not finish within 600 s"
  fi
done

# 4. operators against python-flint on F0's operator matrices (as compare_operators.sh).
echo "== 4. operators (python-flint)" >&2
"$bin" operators F0 --json > "$out/operators.json"
lac=""
flint_kernel=""
if has_module flint; then
  "$py" -c '
import json, sys
for op in json.load(open(sys.argv[1]))["automaton"]["operators"]:
    print(op["matrix"])
' "$out/operators.json" > "$out/matrices.txt"
  n=$(grep -c . "$out/matrices.txt")
  if ! res=$("$py" benches/flint_operators.py "$out/matrices.txt" "$bin"); then
    res="flint_operators.py failed"
  fi
  echo "$res" >&2
  flint_kernel=$(echo "$res" | sed -n 's/^python-flint.*: wall \([0-9.]*\) s,.*/\1/p')
  lac=$(echo "$res" | sed -n 's/^lacuna operators.*: wall \([0-9.]*\) s,.*/\1/p')
  lac_kernel=$("$kernel_bin" --matrices "$out/matrices.txt" | sed -n 's/^lacuna kernel.*: \([0-9.]*\) s$/\1/p')
fi
if [ -n "${flint_kernel:-}" ] && [ -n "${lac:-}" ]; then
  args=()
  while read -r m; do args+=(--matrix "$m"); done < "$out/matrices.txt"
  lac_mb=$(peak_mb "$bin" operators "${args[@]}")
  flint_process=$(best_of 5 "$py" benches/flint_operators.py "$out/matrices.txt" --flint-only || echo "-")
  flint_mb=$(peak_mb "$py" benches/flint_operators.py "$out/matrices.txt" --flint-only)
  row "operators of F0 ($n matrices), both kernels in process" "${lac_kernel:--}" "$flint_kernel" "$(ratio "$flint_kernel" "${lac_kernel:--}")" "-" "-" \
    "lacuna: analyse_matrix on each (benches/operators.rs, best of 20); FLINT: charpoly, factor, roots only; best of 5"
  row "operators of F0 ($n matrices), FLINT in process" "$lac" "$flint_kernel" "$(ratio "$flint_kernel" "$lac")" "$lac_mb" "-" \
    "lacuna: whole process; FLINT: charpoly, factor, roots only; best of 5"
  row "operators of F0 ($n matrices), both whole processes" "$lac" "$flint_process" "$(ratio "$flint_process" "$lac")" "$lac_mb" "$flint_mb" \
    "FLINT: Python start, import, parse and the same work; best of 5"
else
  row "operators of F0" "-" "-" "-" "-" "-" "skipped: ${py_reason:-flint_operators.py failed}"
fi

# 5. STL throughput: lacuna's render to binary STL against a plain Python struct writer that
# writes the same triangles (read from lacuna's file before its clock starts).
echo "== 5. STL throughput (plain Python writer)" >&2
level=3
lac=$(best_of 3 "$bin" render cube-B2 --level "$level" --stl "$out/cube.stl" --no-progress)
lac_mb=$(peak_mb "$bin" render cube-B2 --level "$level" --stl "$out/cube.stl" --no-progress)
if ! command -v python3 > /dev/null; then
  row "binary STL, cube-B2 level $level" "$lac" "-" "-" "$lac_mb" "-" "skipped: no python3"
elif ! res=$(python3 benches/stl_writer.py "$out/cube.stl" "$out/plain.stl" 3); then
  row "binary STL, cube-B2 level $level" "$lac" "-" "-" "$lac_mb" "-" "skipped: stl_writer.py failed"
else
  read -r tris peer check <<< "$res"
  peer_mb=$(peak_mb python3 benches/stl_writer.py "$out/cube.stl" "$out/plain.stl" 1)
  rate() { awk -v n="$tris" -v s="$1" 'BEGIN { printf "%.0f", n / s }'; }
  row "binary STL, cube-B2 level $level, $tris triangles, lacuna's whole render" "$lac" "$peer" "$(ratio "$peer" "$lac")" "$lac_mb" "$peer_mb" \
    "triangles/s: lacuna $(rate "$lac") (build, check, write), writer $(rate "$peer") (write only); $check"
  # lacuna's writer alone: the mesh_checks bench times stl::write_binary of the same solid.
  LEVEL=$level cargo bench --quiet --bench mesh_checks | tee "$out/mesh_checks.txt" >&2
  write=$(awk '/^write binary STL/ { print $4 }' "$out/mesh_checks.txt")
  if [ -n "$write" ]; then
    row "binary STL, cube-B2 level $level, $tris triangles, writers only" "$write" "$peer" "$(ratio "$peer" "$write")" "-" "-" \
      "triangles/s: lacuna $(rate "$write") (stl::write_binary into memory, mesh_checks bench), writer $(rate "$peer") (into a file)"
  fi
fi

echo
echo "lacuna $(git rev-parse --short HEAD 2> /dev/null || echo '?'), $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, FULL=$full, load average $load_before before the measurements, $(load) after"
echo
echo "| what | lacuna (s) | peer (s) | peer / lacuna | lacuna peak MB | peer peak MB | note |"
echo "|---|---:|---:|---:|---:|---:|---|"
while IFS='|' read -r what lac peer r lmb pmb note; do
  echo "| $what | $lac | $peer | $r | $lmb | $pmb | $note |"
done < "$rows"
# The solver bench's growth line (issue #34 asks for ≤ n^1.05 from 5k to 1.2M unknowns).
growth=$(grep '^growth of the solve' "$out/solver.txt" || true)
[ -n "$growth" ] && echo && echo "$growth (solver bench, lacuna alone)"
exit 0
