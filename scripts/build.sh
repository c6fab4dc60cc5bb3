#!/usr/bin/env bash
# Configures and builds vb (Release) into ./build, after making sure dependencies are installed.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build
