#!/bin/sh
# The sweep of docs/VOLUMES.md (issue #15): six solids × {B2, C2, B3, C3} × {A1, A2} × {V1, V2},
# E = B2 B2 B2, G = B2 B2, through `measure` at level $LEVEL (default 1), with the release binary
# (or $LACUNA). Prints every case that does not embed and the totals. Run from the repository's
# root.
#
# SET=issue31 runs the 60 cases of issue #31 instead: cube, tetrahedron, octahedron, prism-3 and
# truncated tetrahedron × {C2, C3, B3} × {A1, A2} × {V1, V2} (use it with LEVEL=3). $CAP, when
# set, stops a case after that many seconds (`timeout`), counted as "other (exit 124)".
L=${LACUNA:-target/release/lacuna}
LEVEL=${LEVEL:-1}
case "${SET:-all}" in
  issue31)
    SOLIDS="cube tetrahedron octahedron prism-3 truncated-tetrahedron"
    EDGES="C2 C3 B3"
    ;;
  *)
    SOLIDS="cube tetrahedron octahedron prism-3 prism-5 truncated-tetrahedron"
    EDGES="B2 C2 B3 C3"
    ;;
esac
ok=0
fold=0
other=0
for s in $SOLIDS; do
  for x in $EDGES; do
    for a in A1 A2; do
      for r in V1 V2; do
        v="$s $x | B2 B2 B2 | $a | B2 B2 | $r"
        if [ -n "$CAP" ]; then
          out=$(timeout "$CAP" $L measure "$v" --level "$LEVEL" 2>&1)
        else
          out=$($L measure "$v" --level "$LEVEL" 2>&1)
        fi
        rc=$?
        if [ $rc = 0 ]; then
          ok=$((ok + 1))
        elif echo "$out" | grep -q "NOT EMBEDDED"; then
          fold=$((fold + 1))
          echo "fold: $v"
        else
          other=$((other + 1))
          echo "other (exit $rc): $v: $(echo "$out" | tail -n 1)"
        fi
      done
    done
  done
done
echo "level $LEVEL: $ok embed, $fold fold, $other other"
