#!/bin/sh
# Writes the pictures of the automaton library entries in docs/images/ (issue #14), with the
# release binary (or $LACUNA). Run from the repository's root.
set -e
L=${LACUNA:-target/release/lacuna}
$L render sierpinski-triangle --level 6 --svg docs/images/sierpinski-triangle.svg
$L render cantor-set --level 6 --svg docs/images/cantor-set.svg
$L render penrose-robinson --level 6 --svg docs/images/penrose-robinson.svg
$L render de-casteljau-cubic --level 3 --svg docs/images/de-casteljau-cubic.svg
$L render bspline-quadratic-4 --level 3 --svg docs/images/bspline-quadratic-4.svg
$L render bspline-cubic --level 3 --svg docs/images/bspline-cubic.svg
$L render half-tangent-edge --level 4 --svg docs/images/half-tangent-edge.svg
$L render quad-patch-3d --level 3 --svg docs/images/quad-patch-3d.svg
# Seed 002's Sierpinski carpet and gasket family (docs/GALLERY.md): PNG, the levels have thousands
# of pieces.
$L render sierpinski-carpet --level 4 --png docs/images/sierpinski-carpet.png
$L render gasket-3 --level 6 --png docs/images/gasket-3.png
$L render gasket-4 --level 3 --png docs/images/gasket-4.png
$L render gasket-5 --level 5 --png docs/images/gasket-5.png
$L render gasket-6 --level 5 --png docs/images/gasket-6.png
$L render gasket-7 --level 5 --png docs/images/gasket-7.png
$L render gasket-8 --level 4 --png docs/images/gasket-8.png
$L render lemniscate-fractal --level 6 --png docs/images/lemniscate-fractal.png
$L render rose-fractal --level 6 --png docs/images/rose-fractal.png
$L render fixtures/triangle-hexagon-alternating.aut --level 6 --png docs/images/triangle-hexagon-alternating.png
$L morph fixtures/octagonal-gasket-product.aut fixtures/carpet-product.aut --frames 8 --level 3 --svg docs/images/octagonal-gasket-to-carpet.svg
$L morph fixtures/gasket-to-hexagonal-start.aut fixtures/gasket-to-hexagonal-end.aut --frames 8 --level 4 --svg docs/images/gasket-to-hexagonal.svg
$L morph fixtures/gasket-to-carpet-start.aut fixtures/gasket-to-carpet-end.aut --frames 8 --level 3 --svg docs/images/gasket-to-carpet.svg
$L morph fixtures/hexagonal-gasket-samples.aut lemniscate-fractal --frames 8 --level 3 --svg docs/images/hexagonal-gasket-to-lemniscate.svg
$L morph fixtures/twisted-circle-circle-view.aut fixtures/twisted-circle-lemniscate-view.aut --frames 8 --level 3 --svg docs/images/twisted-circle-circle-to-lemniscate.svg
# Seed 003's fig. 12 (docs/GALLERY.md): the arrowhead from triangles.
$L render fixtures/sierpinski-arrowhead-triangles.rule --level 6 --png docs/images/sierpinski-arrowhead-triangles.png
# Seed 004's fractal kite and dart (docs/GALLERY.md, docs/GUIDE.md): the kite is the start state
# a, the dart state b, drawn from its frame.
$L render kite-dart --level 14 --png docs/images/kite-dart.png
$L render kite-dart --state b --level 14 --png docs/images/kite-dart-b.png
# Seed 001's pictures (docs/GALLERY.md): the Takagi curve, the parabola's osculating circles.
$L render fixtures/takagi.aut --level 8 --size 480 --png docs/images/seed001-takagi.png
$L operators de-casteljau-edge --points '0 0; 1 1; 2 0' --svg docs/images/seed001-bezier-osculating.svg > /dev/null
$L operators fixtures/alpha-two-valley.aut --points '0 0; 1 3; 2 0' --svg docs/images/seed001-alpha-two-valley.svg > /dev/null
