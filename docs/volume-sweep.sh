#!/bin/sh
# The sweep of docs/VOLUMES.md (issue #15): six solids × {B2, C2, B3, C3} × {A1, A2} × {V1, V2},
# E = B2 B2 B2, G = B2 B2, through `measure` at level $LEVEL (default 1), with the release binary
# (or $LACUNA). Prints every case that does not embed and the totals. Run from the repository's
# root.
L=${LACUNA:-target/release/lacuna}
LEVEL=${LEVEL:-1}
ok=0
fold=0
other=0
for s in cube tetrahedron octahedron prism-3 prism-5 truncated-tetrahedron; do
  for x in B2 C2 B3 C3; do
    for a in A1 A2; do
      for r in V1 V2; do
        v="$s $x | B2 B2 B2 | $a | B2 B2 | $r"
        out=$($L measure "$v" --level "$LEVEL" 2>&1)
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
