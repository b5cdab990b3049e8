#!/usr/bin/env bash
# Installs gonio's Debian packages (as root, idempotent) and builds it in build/ (Release).
# Usage: bash scripts/setup.sh [--sanitize]
#   --sanitize   build in build-asan/ with AddressSanitizer and UndefinedBehaviorSanitizer
# Extra CMake arguments may be given in GONIO_CMAKE_ARGS (e.g. -DGONIO_WERROR=ON).
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake pkg-config git
  libembree-dev libfftw3-dev libopenexr-dev libhdf5-dev libtbb-dev libhwy-dev
  libcli11-dev libtomlplusplus-dev doctest-dev nlohmann-json3-dev libpng-dev zlib1g-dev
  libopenmpi-dev openmpi-bin libceres-dev libzip-dev libpugixml-dev libssl-dev pybind11-dev python3-pybind11 python3-pytest python3-mypy
  python3-h5py python3-numpy python3-matplotlib python3-xarray python3-h5netcdf
  python3-plotly chromium chromium-driver python3-selenium
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  if [[ $(id -u) -ne 0 ]]; then
    echo "setup: need root to install: ${missing[*]}" >&2
    exit 1
  fi
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${packages[@]}" > /dev/null
fi

build=build
args=(-DCMAKE_BUILD_TYPE=Release)
if [[ "${1:-}" == "--sanitize" ]]; then
  build=build-asan
  args=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DGONIO_SANITIZE=ON)
fi
# shellcheck disable=SC2206
extra=(${GONIO_CMAKE_ARGS:-})
cmake -S . -B "$build" "${args[@]}" "${extra[@]}" > /dev/null
cmake --build "$build" -j "$(nproc)"

# The Python module: Debian's /usr/bin/python3 finds build/python through a .pth file in its
# site directory (root only; otherwise PYTHONPATH=build/python). Not for sanitizer builds.
if [[ "$build" == build && $(id -u) -eq 0 ]]; then
  site=$(/usr/bin/python3 -c "import site; print(site.getsitepackages()[0])")
  mkdir -p "$site"
  echo "$(pwd)/build/python" > "$site/gonio.pth"
fi
