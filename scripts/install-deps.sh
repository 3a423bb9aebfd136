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
    libopencolorio-dev  # WriteImage's OpenColorIO display transform
    ccache  # rebuilds and the sanitizer build reuse compiled objects
    ffmpeg  # EncodeVideo runs the ffmpeg program (H.264 via libx264)
    pybind11-dev python3-dev python3-numpy  # the Python module (docs/python.md)
    libcpp-httplib-dev  # the HTTP client of serve's tests (serve's server is our own)
)
# The farm test (ctest -L slurm) runs a real one-node Slurm; where these cannot be installed
# (no package archive, a locked-down container) the build skips that test and says so.
optional=()
if [ "${1:-}" = "--tests" ]; then
    packages+=(
        clang libclang-rt-14-dev  # the sanitizer build and the libFuzzer targets (CI)
        clang-format  # ctest -L format: every C++ source as .clang-format says
        clang-tidy  # ctest -L tidy: the changed C++ sources pass .clang-tidy
        blender  # ctest -L blender follows the user guide's Blender steps (Debian 12: 3.4)
        python3-pytest python3-openvdb  # ctest -L python: the Python module's tests, a FogVolume as a pyopenvdb grid
        chromium chromium-driver  # ctest -L browser: serve's page in headless Chromium
    )
    optional+=(slurm-wlm munge python3)
fi

missing_of() {
    for p in "$@"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || echo "$p"
    done
}
mapfile -t missing < <(missing_of "${packages[@]}")
mapfile -t missing_optional < <(missing_of "${optional[@]}")
[ ${#missing[@]} -eq 0 ] && [ ${#missing_optional[@]} -eq 0 ] && exit 0

sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
if [ ${#missing[@]} -gt 0 ]; then
    echo "install-deps: installing ${missing[*]}"
    "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
if [ ${#missing_optional[@]} -gt 0 ]; then
    echo "install-deps: installing ${missing_optional[*]} (for the Slurm farm test)"
    "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing_optional[@]}" ||
        echo "install-deps: cannot install ${missing_optional[*]}: the Slurm farm test will not run"
fi
