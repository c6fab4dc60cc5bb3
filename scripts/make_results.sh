#!/usr/bin/env bash
# Regenerates a committed result set docs/results/NAME from a clean tree, so that its
# provenance names a real commit (never "-dirty") and its tasks by their task set path
# (tasks/envNNN.yaml, docs/install.md "Provenance"), not by this machine's paths.
#
#   scripts/make_results.sh NAME [JOBS]     NAME: pid_hmmwv | classical_hmmwv | robustness_pid |
#                                                 oracle_hmmwv | pid_m113 |
#                                                 pid_hmmwv_verti_bench
#
# VB_KEEP_RUN=DIR keeps the batch's trial files (trajectories) in DIR for analysis.
# Refuses (exit 2) when tracked files differ from HEAD, or when build/ was not built from HEAD
# (vb_run --version must print HEAD's commit without -dirty): `git stash` or commit first, then
# `cmake --build build`. Runs the same commands the docs quote for each set (docs/reports.md,
# docs/baselines.md, docs/perception.md) into a temporary directory and copies the report,
# top-down pictures and index into docs/results/NAME. Long: pid_hmmwv is 1000 trials (~3 min on
# 2 free cores), classical_hmmwv 1400 (over an hour), robustness_pid 800 (~15 min), oracle_hmmwv
# 200 (PID and the oracle on pair 0 of the 100 environments; see docs/baselines.md "Oracle"),
# pid_m113 1000 (the tracked M113 with PID, docs/results/pid_m113/README.md),
# pid_hmmwv_verti_bench 1000 (pid_hmmwv decided by the original's success and stuck rules,
# --rules verti_bench; docs/validation.md "The original's rules").
set -euo pipefail
cd "$(dirname "$0")/.."
name=${1:-}
jobs=${2:-2}
case "$name" in
  pid_hmmwv|classical_hmmwv|robustness_pid|oracle_hmmwv|pid_m113|pid_hmmwv_verti_bench) ;;
  *) echo "usage: scripts/make_results.sh pid_hmmwv|classical_hmmwv|robustness_pid|oracle_hmmwv|pid_m113|pid_hmmwv_verti_bench [JOBS]" >&2
     exit 2 ;;
esac
if [ -n "$(git status --porcelain --untracked-files=no)" ]; then
  echo "make_results: the tree has uncommitted changes (git status); results must come from a" \
       "clean tree: commit or stash first" >&2
  exit 2
fi
head=$(git rev-parse --short=12 HEAD)
built=$(build/tools/vb_run --version 2>/dev/null || true)
version=$(sed -n 's/^project(vb VERSION \([0-9.]*\).*/\1/p' CMakeLists.txt)
if [ "$built" != "vb_run $version (git $head)" ]; then
  echo "make_results: build/ is not a build of HEAD ($head): '$built'; run cmake --build build" >&2
  exit 2
fi
tmp=$(mktemp -d /tmp/vb_results.XXXXXX)
keep=${VB_KEEP_RUN:-}
trap 'if [ -n "$keep" ] && [ -d "$tmp/run" ]; then rm -rf "$keep"; mkdir -p "$(dirname "$keep")"; mv "$tmp/run" "$keep"; fi; rm -rf "$tmp"' EXIT
out=docs/results/$name
batch() { nice build/tools/vb_batch tasks/ --jobs "$jobs" --quiet "$@"; }
case "$name" in
  pid_hmmwv)
    batch --traj-every 10 --out "$tmp/run"
    topdown=env061_p0_s0_hmmwv_pid,env042_p1_s0_hmmwv_pid,env095_p2_s0_hmmwv_pid ;;
  classical_hmmwv)
    batch --systems pid,eh,mppi --pairs 0,2,5,7 --traj-every 10 --out "$tmp/run"
    batch --systems mppi_original --pairs 0,5 --traj-every 10 --out "$tmp/mppi_original"
    topdown=env011_p0_s0_hmmwv_pid,env011_p0_s0_hmmwv_eh
    topdown+=,env042_p0_s0_hmmwv_pid,env042_p0_s0_hmmwv_mppi ;;
  robustness_pid)
    batch --pairs 0,5 --perception none,mild,moderate,severe --traj-every 20 --out "$tmp/run"
    topdown="" ;;
  pid_hmmwv_verti_bench)
    batch --traj-every 10 --rules verti_bench --out "$tmp/run"
    topdown=env061_p0_s0_hmmwv_pid,env042_p1_s0_hmmwv_pid,env095_p2_s0_hmmwv_pid ;;
  pid_m113)
    batch --vehicles m113 --traj-every 10 --out "$tmp/run"
    topdown=env061_p0_s0_m113_pid,env066_p0_s0_m113_pid,env095_p2_s0_m113_pid ;;
  oracle_hmmwv)
    batch --systems pid,oracle --pairs 0 --traj-every 10 --out "$tmp/run"
    topdown=env002_p0_s0_hmmwv_pid,env002_p0_s0_hmmwv_oracle
    topdown+=,env061_p0_s0_hmmwv_pid,env061_p0_s0_hmmwv_oracle ;;
esac
build/tools/vb_report "$tmp/run" --out "$tmp/report" ${topdown:+--topdown "$topdown"} --tasks tasks
rm -f "$tmp/report/trials.html"   # links to trial files that are not committed
# a hand-written README.md (the set's analysis) survives the regeneration
if [ -f "$out/README.md" ]; then cp "$out/README.md" "$tmp/README.md"; fi
git rm -rq --ignore-unmatch "$out"
rm -rf "$out"
mkdir -p "$out"
cp -r "$tmp/report/." "$out/"
if [ -f "$tmp/README.md" ]; then cp "$tmp/README.md" "$out/README.md"; fi
if [ "$name" != robustness_pid ]; then cp "$tmp/run/index.csv" "$out/index.csv"; fi
if [ "$name" = classical_hmmwv ]; then
  cp "$tmp/mppi_original/index.csv" "$out/mppi_original_pairs05_index.csv"
fi
if grep -rq "$PWD" "$out"; then echo "make_results: $out names $PWD" >&2; exit 1; fi
git add "$out"
echo "make_results: $out regenerated at $head; review with git diff --cached --stat, then commit"
