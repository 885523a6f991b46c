#!/bin/sh
# Writes docs/images/F0-morph.svg (issue #18, THEORY §13): F0 morphing from its default template
# to a template whose lacunas are at 40 % of their size, 9 frames at level 2, every frame verified
# (exact collapse check, observed holes and components against the exact counts). Run from the
# repository's root after `cargo build`; LACUNA overrides the binary.
set -e
L=${LACUNA:-target/debug/lacuna}
[ -x "$L" ] || L=${CARGO_TARGET_DIR:-target}/debug/lacuna
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
$L render F0 --write-template "$T/a.txt" >/dev/null
# The lacuna side of every sub-face: points 6-8 of the even sub-faces, 3-5 of the odd ones (the
# template's comments name each edge), scaled about the centre.
awk '/^sub / {
  k = $2; line = "sub " k " "; rest = $0; sub(/^sub [0-9]+ /, "", rest);
  n = split(rest, p, /; */);
  for (i = 1; i <= n; i++) {
    split(p[i], xy, " ");
    j = i - 1;
    if ((k % 2 == 0 && j >= 6 && j <= 8) || (k % 2 == 1 && j >= 3 && j <= 5))
      p[i] = sprintf("%.6f %.6f", xy[1] * 0.4, xy[2] * 0.4);
    line = line (i > 1 ? "; " : "") p[i];
  }
  print line; next }
{ print }' "$T/a.txt" > "$T/b.txt"
$L morph "$T/a.txt" "$T/b.txt" --on F0 --frames 9 --level 2 --size 400 --seconds 0.4 \
  --svg docs/images/F0-morph.svg
