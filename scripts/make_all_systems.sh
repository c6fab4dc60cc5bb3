#!/usr/bin/env bash
# Builds docs/results/all_systems_hmmwv's report and the figures its README quotes from finished
# batches of the 1000 tasks (docs/results/all_systems_hmmwv/README.md has the batch commands):
#
#   scripts/make_all_systems.sh COMB DIR [DIR ...]
#
# COMB: a new directory for the combined batch (scripts/combine_batches.py); DIRs: the batches
# (e.g. HYB LRN CLS PID ORC). Writes the report into docs/results/all_systems_hmmwv (README.md
# untouched), its index.csv, and the analyses the README is written from into COMB/analysis/:
# compare_systems.md (Table I by group, failure signatures, every pair's discordant trials and
# sign test) and discordant_<A>_<B>.md for the README's trajectory table. VB_TOPDOWN overrides the
# README's three top-down pictures (comma-separated trial stems).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -lt 2 ]; then
  sed -n '2,10p' "$0" >&2
  exit 2
fi
comb=$1
shift
scripts/combine_batches.py "$comb" "$@"
out=docs/results/all_systems_hmmwv
tmp=$(mktemp -d /tmp/vb_all_systems.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
# the report is made aside and swapped in only when it is whole (the README stays either way)
build/tools/vb_report "$comb" --out "$tmp/report" --tasks tasks \
  --topdown "${VB_TOPDOWN:-env029_p0_s0_hmmwv_tnt,env029_p0_s0_hmmwv_tal,env029_p0_s0_hmmwv_pid}"
rm -f "$tmp/report/trials.html"   # links to trial files that are not committed
cp "$comb/index.csv" "$tmp/report/index.csv"
cp "$out/README.md" "$tmp/report/README.md"
rm -rf "$out"
mv "$tmp/report" "$out"
mkdir -p "$comb/analysis"
scripts/compare_systems.py "$comb" > "$comb/analysis/compare_systems.md"
for pair in "tnt pid" "tal pid" "pid tnt" "tnt tal" "tal tnt" "tnt mppi"; do
  set -- $pair
  scripts/discordant_trajectories.py "$comb" "$1" "$2" > "$comb/analysis/discordant_$1_$2.md"
done
echo "make_all_systems: report in $out, analyses in $comb/analysis"
