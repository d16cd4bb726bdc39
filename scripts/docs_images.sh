#!/usr/bin/env bash
# Draws the pictures of docs/reference/render.md with the built lrvd: CGAL's elk and the comb stress mesh,
# their LRVD and RVD cells, the elk remeshed to 516 vertices, and the open cup stress mesh remeshed
# to 300 by CGAL's isotropic remeshing and by lrvd. `make images` runs it.
# Usage: scripts/docs_images.sh [BUILD_DIR]   (BUILD_DIR defaults to build)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
lrvd="$build/lrvd"
elk="$build/cgal-data/elk.off"
out=docs/images
size=640x480
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$lrvd" stress comb -o "$tmp/comb.off" > /dev/null
for diagram in lrvd rvd; do
  "$lrvd" render "$elk" -n 300 --seed 1 --diagram "$diagram" --size "$size" -o "$out/elk_300_$diagram.png"
  "$lrvd" render "$tmp/comb.off" -n 150 --seed 1 --diagram "$diagram" --view 20,30 --size "$size" \
    -o "$out/comb_150_$diagram.png"
done
"$lrvd" remesh "$elk" -n 516 --seed 1 -o "$tmp/elk_516.off" > /dev/null
"$lrvd" render "$tmp/elk_516.off" --edges --size "$size" -o "$out/elk_516_remesh.png"

# The open cup at 300 vertices by CGAL's isotropic remeshing and by lrvd, where each fails a check
# coloured (bench_isotropic writes both remeshes).
"$build/bench_isotropic" --models '' --stress open_cup --counts 300 --save "$tmp" > /dev/null 2>&1
for method in cgal_isotropic lrvd; do
  "$lrvd" render "$tmp/open_cup_300_$method.off" --color defects --edges --size "$size" \
    -o "$out/open_cup_300_$method.png"
done
