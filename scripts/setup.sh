#!/usr/bin/env bash
# Installs what vb needs to build and test on Debian 12 (bookworm): the Debian packages, then the
# Python environment (.venv: the vb_gym package, editable, with numpy, gymnasium, h5py, minari,
# pytest from PyPI). Safe to re-run: installs only what is missing or changed. Needs root (or sudo) for apt.
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
  libassimp-dev                  # obstacle meshes (OBJ, STL, glTF): tools/io/mesh_loader.cc
  libopencv-core-dev libopencv-imgproc-dev   # drawing report plots and world pictures
  libpng-dev                     # height images and plots (PNG): tools/io/image_file.cc
  libgtest-dev                   # tests
  libhdf5-dev                    # datasets (vb_collect, docs/datasets.md): HDF5 C library
  python3 python3-venv           # the Python package's virtual environment (.venv)
  nlohmann-json3-dev             # vb_gym protocol headers (JSON)
  chromium                       # headless-browser tests of the 3-D viewer (docs/viewer.md)
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
else
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# Python: .venv in the repository with the package installed editable (python/, docs/gym.md).
# Re-installed only when python/pyproject.toml changes (its hash is kept in the venv). The
# training extra (stable-baselines3, torch) is never installed here: pip install -e "python[sb3]".
cd "$(dirname "$0")/.."
venv=.venv
stamp="$venv/.vb_setup_stamp"
want="$(sha256sum python/pyproject.toml | cut -d' ' -f1)"
if [ ! -x "$venv/bin/python" ]; then
  echo "setup: creating the Python environment $venv"
  /usr/bin/python3 -m venv "$venv"
fi
if [ "$(cat "$stamp" 2>/dev/null)" != "$want" ]; then
  echo "setup: installing the vb_gym Python package into $venv (numpy, gymnasium, h5py, minari, pytest)"
  "$venv/bin/python" -m pip install -q --upgrade pip
  "$venv/bin/python" -m pip install -q -e "python[test,datasets]"
  echo "$want" > "$stamp"
else
  echo "setup: Python environment $venv up to date"
fi
