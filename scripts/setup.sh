#!/usr/bin/env bash
# Installs what vb needs to build and test on Debian 12 (bookworm). Safe to re-run: installs only
# missing packages. Needs root (or sudo).
#
#   scripts/setup.sh          what the build and the test suite need
#   scripts/setup.sh --fuzz   also clang and its libFuzzer runtime, for the fuzz targets
#                             (cmake -DVB_FUZZ=ON, fuzz/run_fuzz.sh; not part of the default build)
set -euo pipefail

fuzz=0
for arg in "$@"; do
  case "$arg" in
    --fuzz) fuzz=1 ;;
    *) echo "setup: unknown option $arg (valid: --fuzz)" >&2; exit 2 ;;
  esac
done

packages=(
  cmake ninja-build g++ pkg-config git
  libeigen3-dev                  # linear algebra
  libbullet-dev                  # multibody dynamics and body-body contact (float64 libraries)
  libyaml-cpp-dev                # task and vehicle files
  libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev   # height images
  libgtest-dev                   # tests
)
if [ "$fuzz" -eq 1 ]; then
  packages+=(clang libclang-rt-14-dev)   # Debian 12's clang 14 with -fsanitize=fuzzer
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
