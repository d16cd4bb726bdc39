#!/usr/bin/env bash
# Installs the Debian packages lrvd needs (skipping what is already there) and extracts the
# CGAL data-set meshes the tests use into a build-local folder.
# Usage: scripts/setup.sh [DATA_DIR]   (DATA_DIR defaults to build/cgal-data)
set -euo pipefail

packages=(cmake ninja-build ccache g++ libcgal-dev libgmp-dev libmpfr-dev libembree-dev
  libeigen3-dev liblbfgspp-dev libtbb-dev libcli11-dev nlohmann-json3-dev libfmt-dev libstb-dev
  libnanoflann-dev catch2 libbenchmark-dev libcgal-demo clang-14 libfuzzer-14-dev
  pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

data_dir="${1:-build/cgal-data}"
archive=/usr/share/doc/libcgal-dev/data.tar.gz
meshes=(elk.off knot.off knot1.off ellipsoid.off armadillo.off lion.off fold.off
  ChineseDragon-10kv.off bunny00.off bones.off holes.off pig.off triceratops.off mpi.off pinion_small.off man.off
  diplodocus.off negative.off ALSTOM_TEST4.off pig.stl)
mkdir -p "$data_dir"
need=0
for m in "${meshes[@]}"; do [ -s "$data_dir/$m" ] || need=1; done
if [ "$need" -eq 1 ]; then
  [ -f "$archive" ] || { echo "setup: $archive not found (package libcgal-demo)" >&2; exit 1; }
  tmp=$(mktemp -d)
  tar -xzf "$archive" -C "$tmp"
  for m in "${meshes[@]}"; do
    f=$(find "$tmp" -name "$m" -type f | head -1)
    [ -n "$f" ] || { echo "setup: $m is not in $archive" >&2; rm -rf "$tmp"; exit 1; }
    cp "$f" "$data_dir/$m"
  done
  rm -rf "$tmp"
fi
echo "setup: packages present, CGAL meshes in $data_dir"
