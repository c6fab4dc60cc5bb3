#!/usr/bin/env bash
# InstallTreeTest: `cmake --install` into a temporary prefix, then the installed tools run with
# the source and build trees out of their view, from another directory, with a clean environment
# (no VB_DATA_DIR, no VB_WEB_DIR): the README's example task, a two-trial vb_batch, vb_report
# with top-down pictures (the task found by its recorded task set path), --version, the error
# for an unusable data directory, and the same after moving the whole prefix elsewhere.
#
# The trees are hidden by mounting empty directories over them in a private mount namespace
# (`unshare -m`, as root, or `unshare -rm` in a user namespace); where neither is allowed the
# test still runs from a moved prefix with a clean environment and says so.
#
#   test/install/install_tree_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src=$(cd "$1" && pwd)
build=$(cd "$2" && pwd)
tmp=$(mktemp -d /tmp/vb_install_test.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "InstallTreeTest: FAIL: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$tmp/prefix" > "$tmp/install.log" || fail "cmake --install"
prefix="$tmp/prefix"
for f in bin/vb_run bin/vb_batch bin/vb_report bin/vb_view bin/vb_gym bin/vb_gen bin/vb_import \
         share/vb/data/vehicles/hmmwv.yaml share/vb/data/soils/verti_bench.yaml \
         share/vb/data/worlds/env042.png share/vb/tasks/env042.yaml \
         share/vb/web/viewer/index.html share/doc/vb/README.md; do
  [ -e "$prefix/$f" ] || fail "$f not installed"
done
[ "$(ls "$prefix/share/vb/tasks" | wc -l)" -eq 100 ] || fail "expected the 100 tasks"
# No path of this machine's source or build tree inside the installed programs.
for b in "$prefix"/bin/*; do
  if grep -q -a -F "$src" "$b"; then fail "$b contains the source path $src"; fi
done

# The checks, run as a fresh user would: another directory, a clean environment.
cat > "$tmp/checks.sh" <<'CHECKS'
set -euo pipefail
prefix=$1
fail() { echo "InstallTreeTest: FAIL: $*" >&2; exit 1; }
export PATH="$prefix/bin:/usr/bin:/bin"
work=$(mktemp -d "$TMPDIR/work.XXXXXX")
cd "$work"
vb_run --version | grep -E '^vb_run [0-9]+\.[0-9]+\.[0-9]+ \(git [0-9a-f]{12}(-dirty)?\)$' \
  || fail "vb_run --version"
vb_batch --version | grep -q '^vb_batch ' || fail "vb_batch --version"
# The README's example task (all ten pairs).
vb_run "$prefix/share/vb/tasks/env042.yaml" --vehicle hmmwv --quiet --out run > run.log 2>&1 \
  || { cat run.log; fail "vb_run of the README example"; }
[ "$(ls run/*_traj.csv | wc -l)" -eq 10 ] || fail "vb_run: expected 10 trials"
grep -q '"task_file": "tasks/env042.yaml"' run/env042_p0_s0_hmmwv_pid.json \
  || fail "the record does not name its task as tasks/env042.yaml"
# A two-trial batch and its report with pictures (task found via the shipped task set).
vb_batch "$prefix/share/vb/tasks/env042.yaml" --pairs 0-1 --jobs 2 --quiet --out batch \
  > batch.log 2>&1 || { cat batch.log; fail "vb_batch"; }
[ "$(tail -n +2 batch/index.csv | wc -l)" -eq 2 ] || fail "vb_batch: expected 2 index rows"
grep -q ',tasks/env042.yaml,' batch/index.csv || fail "index.csv task_file is not relative"
if grep -q -F "$prefix" batch/index.csv; then fail "index.csv carries the install path"; fi
vb_report batch --topdown all > report.log 2>&1 || { cat report.log; fail "vb_report"; }
[ "$(ls batch/report/topdown/*.png | wc -l)" -eq 2 ] || { cat report.log; fail "no pictures"; }
# An unusable data directory: exit 2, says where it looked and how to point vb at the data.
set +e
VB_DATA_DIR="$work/empty" vb_run "$prefix/share/vb/tasks/env042.yaml" --vehicle hmmwv \
  > bad.log 2>&1
rc=$?
set -e
[ "$rc" -eq 2 ] || fail "empty VB_DATA_DIR: exit $rc, expected 2"
grep -q "$work/empty" bad.log && grep -q "VB_DATA_DIR" bad.log || { cat bad.log; fail "message"; }
echo "checks passed in $prefix"
CHECKS

run_clean() {   # run_clean PREFIX: the checks with a clean environment
  env -i TMPDIR="$tmp" HOME="$tmp" bash "$tmp/checks.sh" "$1"
}

hidden=0
empty="$tmp/empty_dir"
mkdir -p "$empty"
mount_script="mount --bind '$empty' '$build' && mount --bind '$empty' '$src' && \
  test ! -e '$src/CMakeLists.txt' && test ! -e '$build/CMakeCache.txt' && \
  env -i TMPDIR='$tmp' HOME='$tmp' bash '$tmp/checks.sh' '$prefix'"
for ns in "unshare -m" "unshare -rm"; do
  if $ns true 2>/dev/null; then
    $ns sh -c "$mount_script" || fail "checks with the trees hidden ($ns)"
    hidden=1
    echo "InstallTreeTest: source and build trees hidden ($ns, bind mounts)"
    break
  fi
done
if [ "$hidden" -eq 0 ]; then
  echo "InstallTreeTest: no mount namespace available; the source tree stays visible" \
       "(the moved-prefix run below still proves the tools use no compiled-in path)"
fi
# The whole prefix moved (as a relocated module or copied install): still self-contained.
mv "$prefix" "$tmp/moved"
if [ "$hidden" -eq 1 ]; then
  ${ns} sh -c "${mount_script//$prefix/$tmp/moved}" || fail "checks of the moved prefix"
else
  run_clean "$tmp/moved" || fail "checks of the moved prefix"
fi
echo "InstallTreeTest: passed"
