#!/usr/bin/env bash
# ColconTest (slow: a full Release build): the user story. A colcon workspace builds vb
# from a copy of the source, the source copy is then moved away, and install/vb/bin/vb_run runs
# the README's example with its data from install/vb/share/vb. Exit 77 (skipped) without colcon
# (pip install colcon-common-extensions, or Debian/ROS's python3-colcon-common-extensions).
#
#   test/install/colcon_test.sh SOURCE_DIR
set -euo pipefail
src=$(cd "$1" && pwd)
command -v colcon >/dev/null || { echo "ColconTest: colcon not installed: skipped"; exit 77; }
tmp=$(mktemp -d /tmp/vb_colcon_test.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/ws/src/vb"
(cd "$src" && git ls-files -z | xargs -0 cp --parents -t "$tmp/ws/src/vb")   # tracked files only
cd "$tmp/ws"
# MAKEFLAGS: colcon's default adds -l<cores>, which on a busy machine builds one file at a time.
MAKEFLAGS="-j$(nproc)" colcon build \
  --cmake-args -DCMAKE_BUILD_TYPE=Release -DVB_BUILD_TESTS=OFF -G Ninja \
  > "$tmp/colcon.log" 2>&1 \
  || { tail -50 "$tmp/colcon.log"; echo "ColconTest: FAIL: colcon build"; exit 1; }
mv "$tmp/ws/src" "$tmp/src_moved_away"
rm -rf "$tmp/ws/build"
mkdir "$tmp/elsewhere" && cd "$tmp/elsewhere"
env -i PATH="$tmp/ws/install/vb/bin:/usr/bin:/bin" \
  vb_run "$tmp/ws/install/vb/share/vb/tasks/env042.yaml" --vehicle hmmwv --pair 3 --out demo
[ -f demo/env042_p3_s0_hmmwv_pid.json ] || { echo "ColconTest: FAIL: no record"; exit 1; }
echo "ColconTest: passed"
