#!/usr/bin/env bash
# Draws the pictures of docs/render.md with the built lrvd: CGAL's elk and the comb stress mesh,
# their LRVD and RVD cells, and the elk remeshed to 516 vertices. `make images` runs it.
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
