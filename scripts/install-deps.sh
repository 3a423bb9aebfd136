#!/usr/bin/env bash
# Installs CloudGraph's build dependencies from Debian 12 packages, non-interactively.
# Returns at once when everything is already installed.
# Usage: scripts/install-deps.sh [--tests]   (--tests: also what only the test suite needs)
set -euo pipefail

packages=(
    build-essential cmake pkg-config
    libopenvdb-dev libopenvdb-tools libboost-iostreams-dev libtbb-dev
    nlohmann-json3-dev libfftw3-dev libspdlog-dev libxxhash-dev
    libgtest-dev libbenchmark-dev libpng-dev libopenexr-dev
    ccache  # rebuilds and the sanitizer build reuse compiled objects
    ffmpeg  # EncodeVideo runs the ffmpeg program (H.264 via libx264)
)
if [ "${1:-}" = "--tests" ]; then
    packages+=(
        clang libclang-rt-14-dev  # the sanitizer build and the libFuzzer targets (CI)
        blender  # ctest -L blender follows the user guide's Blender steps (Debian 12: 3.4)
    )
fi

missing=()
for p in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$p")
    fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
