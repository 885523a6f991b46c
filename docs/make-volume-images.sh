#!/bin/sh
# Writes the pictures of volumes in docs/images/ (issue #15, docs/VOLUMES.md), with the release
# binary (or $LACUNA). Run from the repository's root.
set -e
L=${LACUNA:-target/release/lacuna}
$L render cube-B2 --level 1 --png docs/images/cube-B2-level1.png --size 480
$L render tetrahedron-B2 --level 1 --png docs/images/tetrahedron-B2-level1.png --size 480
$L render 'octahedron B2 | B2 B2 B2 | A1 | B2 B2 | V2' --level 1 --png docs/images/octahedron-B2-V2-level1.png --size 480
$L render cube-B2 --level 1 --svg docs/images/cube-B2-level1.svg
$L render cube-B2 --level 2 --png docs/images/cube-B2-level2.png --size 480
$L render two-cubes --level 2 --png docs/images/two-cubes-level2.png --size 480
$L render fixtures/pyramid.txt --level 2 --png docs/images/pyramid-level2.png --size 480
$L render 'tetrahedron C3 | B2 B2 B2 | A1 | B2 B2 | V1' --level 3 --png docs/images/tetrahedron-C3-A1-V1-level3.png --size 480
