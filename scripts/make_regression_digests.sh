#!/usr/bin/env bash
# Regenerates test/data/regression/pid_hmmwv_digests.csv: the digest of every PID + HMMWV trial of
# tasks/ (seed 0, full trajectory). Run it only after a change that is meant to move results (say
# so in the commit, with the outcome changes); a refactor must leave the file unchanged.
# usage: scripts/make_regression_digests.sh [JOBS]   (default 2; ~5 CPU-minutes in all)
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${1:-2}
bin=build/test/vb_make_regression_digests
[ -x "$bin" ] || { echo "build first (scripts/build.sh)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for ((i = 0; i < jobs; i++)); do "$bin" tasks --shard "$i/$jobs" > "$tmp/$i.csv" & done
wait
out=test/data/regression/pid_hmmwv_digests.csv
{ echo "task,pair,status,sim_time_s,digest"; cat "$tmp"/*.csv | sort -t, -k1,1 -k2,2n; } > "$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out ($(($(wc -l < "$out") - 1)) trials)"
