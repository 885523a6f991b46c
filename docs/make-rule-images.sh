#!/bin/sh
# Writes the pictures of the production-rule library entries in docs/images/ (issue #17), with
# the release binary (or $LACUNA). Run from the repository's root.
set -e
L=${LACUNA:-target/release/lacuna}
$L render quadric-koch --level 3 --svg docs/images/quadric-koch.svg
$L render koch --level 4 --svg docs/images/koch.svg
$L render sierpinski-arrowhead --level 6 --svg docs/images/sierpinski-arrowhead.svg
$L render heighway-dragon --level 10 --svg docs/images/heighway-dragon.svg
$L render pythagoras-tree --level 8 --svg docs/images/pythagoras-tree.svg
$L render self-seeding-square --level 3 --svg docs/images/self-seeding-square.svg
$L render vegetation --level 8 --svg docs/images/vegetation.svg
$L render random-tree --level 8 --svg docs/images/random-tree.svg
