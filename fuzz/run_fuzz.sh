#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan, -DVB_FUZZ=ON, into build-fuzz/) and runs each
# for a while. Needs clang: scripts/setup.sh --fuzz.
#
#   fuzz/run_fuzz.sh [SECONDS] [TARGET...]     default: 600 s each, every target, one at a time
#   VB_FUZZ_JOBS=2 fuzz/run_fuzz.sh 600        two targets at a time
#
# The working corpus grows in build-fuzz/corpus/<target>/ (seeded from fuzz/corpus/<target>/ and
# the repository files each target names in fuzz/targets.cc); crashes land in
# build-fuzz/artifacts/<target>/. A summary line per target (runs, execs/s, corpus size, result)
# goes to build-fuzz/fuzz_summary.txt. Add each crash to fuzz/corpus/<target>/ with a name that
# says what it is: the CI replay (test/io/fuzz_replay_test.cc) then keeps it fixed.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
seconds="${1:-600}"
shift || true
build="$here/build-fuzz"
all=(task_yaml vehicle_yaml soil_yaml original_config labels_npy trial_json batch_json index_csv
     gym_frame gym_request http_request mesh_file)
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=("${all[@]}")

if ! command -v clang++ > /dev/null; then
  echo "run_fuzz: clang++ not found; run scripts/setup.sh --fuzz" >&2
  exit 2
fi
if [ ! -f "$build/build.ninja" ]; then
  CC=clang CXX=clang++ cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DVB_FUZZ=ON -DVB_BUILD_TESTS=OFF > /dev/null
fi
# VB_FUZZ_NO_BUILD=1: run the executables as they are (e.g. built by hand).
if [ "${VB_FUZZ_NO_BUILD:-0}" != 1 ]; then
  nice cmake --build "$build" --target $(printf 'vb_fuzz_%s ' "${targets[@]}")
fi

run_one() {
  local t="$1"
  local corpus="$build/corpus/$t" artifacts="$build/artifacts/$t/" log="$build/fuzz_$t.log"
  mkdir -p "$corpus" "$artifacts"
  # Seeds: the committed corpus and the repository files the target lists (fuzz/targets.cc).
  cp -n "$here/fuzz/corpus/$t"/* "$corpus"/ 2> /dev/null || true
  local globs
  globs=$(VB_FUZZ_PRINT_SEEDS=1 "$build/fuzz/vb_fuzz_$t")
  for g in $globs; do
    for f in $here/$g; do [ -f "$f" ] && cp -n "$f" "$corpus/seed_$(basename "$f")"; done
  done
  local rc=0
  (cd "$build" && nice "$build/fuzz/vb_fuzz_$t" -max_total_time="$seconds" -timeout=10 \
      -rss_limit_mb=2048 -max_len=262144 -print_final_stats=1 -artifact_prefix="$artifacts" \
      "$corpus" > "$log" 2>&1) || rc=$?
  local runs execs
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo "?")
  execs=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo "?")
  local result="no crash"
  [ "$rc" -ne 0 ] && result="FINDING (exit $rc, see $log and $artifacts)"
  printf '%-16s %6s s  %10s runs  %7s exec/s  corpus %5s files  %s\n' "$t" "$seconds" "$runs" \
    "$execs" "$(ls "$corpus" | wc -l)" "$result" | tee -a "$build/fuzz_summary.txt"
}

jobs="${VB_FUZZ_JOBS:-1}"
for t in "${targets[@]}"; do
  run_one "$t" &
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
done
wait
