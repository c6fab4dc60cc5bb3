#!/usr/bin/env bash
# Prepares the original Verti-Bench's code to run on the PyChrono that build_chrono.sh built, in
# the same cache directory outside the repository (docs/validation.md, "Cross-check with the
# original"). Idempotent: each stage leaves a stamp and is redone only when its input changes.
# Never part of vb's build or tests.
#
#   scripts/reference/prepare_original.sh [--cache DIR] [--code TARBALL] [--data DIR]
#
# Defaults: --cache $VB_REFERENCE_CACHE or ~/.cache/vb-reference (as build_chrono.sh),
#           --code ../shared/reference/verti_bench-df6a965-code.tar.xz (the original's code),
#           --data ../shared/verti_bench_calibration/envs/data/BenchMaps/sampled_maps (or the
#                  sampled_maps directory of an original checkout: Worlds/, Configs/Final/).
#
# What it lays out in CACHE (nothing of it is copied into the repository):
#  venv/          Python environment on the system Python (the one PyChrono was built for):
#                 numpy, pillow, pyyaml, scipy, matplotlib, opencv (headless), torch, torchvision
#                 from PyPI (the original imports all of them at module level).
#  original/verti_bench/
#                 the original's code, extracted unmodified; its data directory
#                 envs/data/BenchMaps/sampled_maps/ holds links to the world images and configs of
#                 --data, and the height*.npy files the harness remakes (make_heights.py; the
#                 original's are Git LFS objects that are not available).
#  chrono-data/   CHRONO_DATA_DIR: Chrono's vehicle data, and stand-in *visual* meshes for the
#                 original's rocks and trees (sensor/offroad/rock.obj, tree.obj are LFS objects;
#                 the original collides with their bounding boxes, so the mesh changes nothing
#                 physical: it is only drawn).
#  stand-in weight files for the original MPPI's unused networks (make_inert_weights.py).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
cache="${VB_REFERENCE_CACHE:-$HOME/.cache/vb-reference}"
code="$repo/../shared/reference/verti_bench-df6a965-code.tar.xz"
data="$repo/../shared/verti_bench_calibration/envs/data/BenchMaps/sampled_maps"
while [ $# -gt 0 ]; do
  case "$1" in
    --cache) cache="$2"; shift 2 ;;
    --code) code="$2"; shift 2 ;;
    --data) data="$2"; shift 2 ;;
    -h|--help) sed -n '2,28p' "$0"; exit 0 ;;
    *) echo "prepare_original: unknown option $1 (valid: --cache DIR, --code TARBALL, --data DIR)" >&2; exit 2 ;;
  esac
done
[ -f "$code" ] || { echo "prepare_original: $code: no such file (give --code)" >&2; exit 2; }
[ -d "$data/Worlds" ] && [ -d "$data/Configs/Final" ] ||
  { echo "prepare_original: $data: expected Worlds/ and Configs/Final/ (give --data)" >&2; exit 2; }
mkdir -p "$cache"
cache="$(cd "$cache" && pwd)"
data="$(cd "$data" && pwd)"
log() { echo "prepare_original: $*"; }

# 1. Python environment. The packages are the original's imports; torch from PyPI (CPU is enough:
# the harness runs the original's few .cuda() calls as no-ops, original_env.py).
packages="numpy pillow pyyaml scipy matplotlib opencv-python-headless torch torchvision"
venv="$cache/venv"
if [ "$(cat "$venv/.vb_stamp" 2>/dev/null)" != "$packages" ]; then
  log "creating $venv ($packages; torch is large, a few minutes the first time)"
  [ -x "$venv/bin/python" ] || /usr/bin/python3 -m venv "$venv"
  "$venv/bin/python" -m pip install -q $packages
  echo "$packages" > "$venv/.vb_stamp"
fi

# 2. The original's code, unmodified.
orig="$cache/original"
sum="$(sha256sum "$code" | cut -d' ' -f1)"
if [ "$(cat "$orig/.extracted" 2>/dev/null)" != "$sum" ]; then
  log "extracting $code into $orig"
  rm -rf "$orig"
  mkdir -p "$orig"
  tar -xJf "$code" -C "$orig"
  [ -f "$orig/verti_bench/systems/PID/PID_sim.py" ] ||
    { echo "prepare_original: $code has no verti_bench/systems/PID/PID_sim.py" >&2; exit 1; }
  echo "$sum" > "$orig/.extracted"
fi

# 3. Its data directory: links to the worlds and configs (the heights are remade into it).
maps="$orig/verti_bench/envs/data/BenchMaps/sampled_maps"
mkdir -p "$maps/Worlds" "$maps/Configs/Final"
for f in "$data"/Worlds/*.bmp; do ln -sfn "$f" "$maps/Worlds/$(basename "$f")"; done
for f in "$data"/Configs/Final/config*.yaml "$data"/Configs/Final/labels*.npy "$data"/Configs/Final/obs*.bmp; do
  ln -sfn "$f" "$maps/Configs/Final/$(basename "$f")"
done
for f in "$data"/Configs/Final/height*.npy; do  # an original checkout's own heights, if any
  [ -e "$f" ] && ln -sfn "$f" "$maps/Configs/Final/$(basename "$f")"
done
log "$(ls "$maps"/Configs/Final/config*.yaml | wc -l) worlds linked from $data"

# 4. Chrono's data directory with the stand-in visual meshes (a 1 m cube, drawn only).
cdata="$cache/chrono-data"
chrono_src="$cache/chrono-9.0.1"
[ -d "$chrono_src/data/vehicle" ] ||
  { echo "prepare_original: $chrono_src/data/vehicle missing: run build_chrono.sh first" >&2; exit 1; }
mkdir -p "$cdata/sensor/offroad"
ln -sfn "$chrono_src/data/vehicle" "$cdata/vehicle"
for name in rock tree; do
  obj="$cdata/sensor/offroad/$name.obj"
  [ -f "$obj" ] && continue
  {
    echo "# vb-reference-harness: stand-in visual mesh (the original's $name.obj is a Git LFS object)"
    for v in "-0.5 -0.5 -0.5" "0.5 -0.5 -0.5" "0.5 0.5 -0.5" "-0.5 0.5 -0.5" \
             "-0.5 -0.5 0.5" "0.5 -0.5 0.5" "0.5 0.5 0.5" "-0.5 0.5 0.5"; do echo "v $v"; done
    for f in "1 3 2" "1 4 3" "5 6 7" "5 7 8" "1 2 6" "1 6 5" "2 3 7" "2 7 6" "3 4 8" "3 8 7" "4 1 5" "4 5 8"; do
      echo "f $f"
    done
  } > "$obj"
done

# 5. Stand-in weights for the original MPPI's networks whose outputs its cost never reads.
"$venv/bin/python" "$here/make_inert_weights.py" "$orig"
touch "$cache/.prepared"
log "ready: scripts/reference/run_original.py WORLD PAIR [--system pid|eh|mppi]"
