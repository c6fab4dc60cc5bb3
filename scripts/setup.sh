#!/usr/bin/env bash
# Installs what vb needs to build and test on Debian 12 (bookworm). Safe to re-run: installs only
# missing packages. Needs root (or sudo).
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config git
  libeigen3-dev                  # linear algebra
  libbullet-dev                  # multibody dynamics and body-body contact (float64 libraries)
  libyaml-cpp-dev                # task and vehicle files
  libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev   # height images
  libgtest-dev                   # tests
  python3 chromium               # headless-browser tests of the 3-D viewer (docs/viewer.md)
)

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
