#!/usr/bin/env bash
# BuildTreeLayoutTest: the build tree's share/vb/{data,tasks,web} (cmake/vb_install.cmake) are
# relative symbolic links that resolve into this source tree, and a copy of the checkout with its
# build tree (same relative layout) reads the copy's files, not the original's: a vehicle file
# that exists only in the copy is listed by the copied vb_run, and one that exists only in the
# original is not. (Before: absolute links, so a copied checkout silently read the original's
# vehicles, tasks and viewer page.)
#
#   test/install/build_tree_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src=$(cd "$1" && pwd -P)
build=$(cd "$2" && pwd -P)
tmp=$(mktemp -d /tmp/vb_build_tree_test.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "BuildTreeLayoutTest: FAIL: $*" >&2; exit 1; }

for d in data tasks web; do
  link="$build/share/vb/$d"
  [ -L "$link" ] || fail "$link is not a symbolic link"
  target=$(readlink "$link")
  case "$target" in /*) fail "$link -> $target is absolute (a copied tree would read this one)";; esac
  [ "$(cd "$link" && pwd -P)" = "$src/$d" ] || fail "$link does not resolve to $src/$d"
done

# The copy: the two trees at the same relative place under $tmp (their absolute paths, rebased).
copy_src="$tmp$src"
copy_build="$tmp$build"
mkdir -p "$copy_src" "$copy_build/tools" "$copy_build/share/vb"
cp -a "$src/data" "$src/tasks" "$src/web" "$copy_src/"
cp -a "$build/share/vb/." "$copy_build/share/vb/"
cp "$build/tools/vb_run" "$copy_build/tools/"
cp "$copy_src/data/vehicles/hmmwv.yaml" "$copy_src/data/vehicles/only_in_the_copy.yaml"
out=$(env -u VB_DATA_DIR -u VB_WEB_DIR "$copy_build/tools/vb_run" "$copy_src/tasks/env042.yaml" \
      --vehicle nosuch 2>&1 || true)
echo "$out" | grep -q "only_in_the_copy" || fail "the copied vb_run did not read the copy's data: $out"
echo "$out" | grep -q "$copy_build/share/vb/data" || fail "the copied vb_run names another data directory: $out"
echo "BuildTreeLayoutTest: OK (links relative; the copy reads its own data)"
