#!/usr/bin/env bash
# Builds Project Chrono 9.0.1 and PyChrono (core + vehicle) from a source tarball into a cache
# directory outside the repository, for the cross-check with the original Verti-Bench
# (docs/validation.md, "Cross-check with the original"). Idempotent and resumable: each stage leaves a
# stamp, ninja resumes an interrupted build. Never part of vb's build or tests.
#
#   scripts/reference/build_chrono.sh [--tarball FILE] [--cache DIR] [--jobs N]
#
# Defaults: --tarball ../shared/reference/chrono-9.0.1-src.tar.xz (beside the repository),
#           --cache $VB_REFERENCE_CACHE or ~/.cache/vb-reference, --jobs nproc.
# Afterwards: PYTHONPATH=CACHE/chrono-build/bin LD_LIBRARY_PATH=CACHE/chrono-build/lib python3 -c 'import pychrono.vehicle'
#
# What it changes in Chrono's sources, and why (each change is ours, applied by patch_chrono.py):
#  1. SWIG 4.1 wraps a constructor of the abstract ChVehicleVisualSystem without Irrlicht: %ignore it.
#  2. SCMTerrain::SetBoundary(ChAABB), which the original's terrain.py calls and 9.0.1 lacks: grid
#     nodes outside the box are never ray-cast (the behaviour of later upstream Chrono).
#  3. data/vehicle/hmmwv/hmmwv_chassis.obj is not in the tarball; the original sets the chassis
#     visualisation to MESH and needs the file: a copy of hmmwv_chassis_simple.obj (visual only;
#     the chassis collides as primitives).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
tarball="$repo/../shared/reference/chrono-9.0.1-src.tar.xz"
cache="${VB_REFERENCE_CACHE:-$HOME/.cache/vb-reference}"
jobs="$(nproc)"
while [ $# -gt 0 ]; do
  case "$1" in
    --tarball) tarball="$2"; shift 2 ;;
    --cache) cache="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    -h|--help) sed -n '2,22p' "$0"; exit 0 ;;
    *) echo "build_chrono: unknown option $1 (valid: --tarball FILE, --cache DIR, --jobs N)" >&2; exit 2 ;;
  esac
done
[ -f "$tarball" ] || { echo "build_chrono: $tarball: no such file (give --tarball)" >&2; exit 2; }
mkdir -p "$cache"
cache="$(cd "$cache" && pwd)"
src="$cache/chrono-9.0.1"
build="$cache/chrono-build"
log() { echo "build_chrono: $*"; }

# Debian packages the build needs (the same set-up rule as scripts/setup.sh: only what is missing).
need=(cmake ninja-build g++ libeigen3-dev swig python3-dev python3-venv)
missing=()
for p in "${need[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
  log "installing ${missing[*]}"
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

sum="$(sha256sum "$tarball" | cut -d' ' -f1)"
if [ "$(cat "$cache/.extracted" 2>/dev/null)" != "$sum" ]; then
  log "extracting $tarball into $cache"
  rm -rf "$src" "$cache/.patched"
  tar -xJf "$tarball" -C "$cache"
  echo "$sum" > "$cache/.extracted"
fi
if [ ! -f "$cache/.patched" ]; then
  log "patching the sources (SWIG visual system, SCMTerrain::SetBoundary, chassis stand-in mesh)"
  python3 "$here/patch_chrono.py" "$src"
  rm -f "$build"/src/chrono_swig/chrono_python/*vehicle*PYTHON_wrap.cxx 2>/dev/null || true
  touch "$cache/.patched"
fi

if [ ! -f "$build/build.ninja" ]; then
  log "configuring into $build"
  cmake -S "$src" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DENABLE_MODULE_VEHICLE=ON -DENABLE_MODULE_PYTHON=ON \
    -DBUILD_DEMOS=OFF -DBUILD_TESTING=OFF -DBUILD_BENCHMARKING=OFF \
    -DPython3_EXECUTABLE=/usr/bin/python3 > "$cache/configure.log" 2>&1 \
    || { tail -30 "$cache/configure.log" >&2; exit 1; }
fi
log "building with $jobs jobs (about 80 CPU-minutes the first time; resumes where it stopped)"
t0=$(date +%s)
cmake --build "$build" -j "$jobs" --target ChronoEngine ChronoEngine_vehicle ChronoModels_vehicle \
  _core _fea _vehicle
log "built in $(( $(date +%s) - t0 )) s"
PYTHONPATH="$build/bin" LD_LIBRARY_PATH="$build/lib" python3 -c \
  'import pychrono, pychrono.vehicle as v; assert hasattr(v.SCMTerrain, "SetBoundary"); print("build_chrono: pychrono", pychrono.__file__)'
echo "$build" > "$cache/.built"
