#!/usr/bin/env bash
# Regenerates the committed benchmark: tasks/env000.yaml ... env099.yaml and their height images
# data/worlds/env000.png ... env099.png, with `vb_gen --env K` (seed K, labels fixed by K; see
# docs/generator.md). The output is byte-identical on every run; test/terrain/benchmark_set_test.cc
# checks a sample of the committed files against a fresh generation.
#
# usage: scripts/make_benchmark_tasks.sh [BUILD_DIR]   (default: build)
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-${root}/build}"
vb_gen="${build}/tools/vb_gen"
if [[ ! -x "${vb_gen}" ]]; then
  echo "make_benchmark_tasks.sh: ${vb_gen} not found; build the vb_gen target first" >&2
  exit 2
fi

for k in $(seq 0 99); do
  "${vb_gen}" --env "${k}" --out "${root}/tasks" --image-dir "${root}/data/worlds" >/dev/null
done
echo "wrote 100 environments to ${root}/tasks and ${root}/data/worlds"
