#!/usr/bin/env bash
# DebPackageTest: builds the Debian package with CPack from BUILD_DIR and checks it: the files
# (tools in /usr/bin, data, tasks and the viewer in /usr/share/vb), Depends naming Debian 12's
# runtime libraries and covering every shared library the tools load, and the tools running
# from the unpacked package (/usr layout, another directory, a clean environment).
# scripts/check_deb_clean_chroot.sh goes further: apt installs the package on a clean Debian 12.
#
#   test/install/deb_package_test.sh BUILD_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
tmp=$(mktemp -d /tmp/vb_deb_test.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "DebPackageTest: FAIL: $*" >&2; exit 1; }

(cd "$tmp" && cpack --config "$build/CPackConfig.cmake" -G DEB -B "$tmp/out" > cpack.log 2>&1) \
  || { cat "$tmp/cpack.log"; fail "cpack -G DEB"; }
deb=$(ls "$tmp"/out/vb_*.deb)
echo "DebPackageTest: $(basename "$deb") $(du -h "$deb" | cut -f1)"
dpkg-deb -c "$deb" | awk '{print $NF}' > "$tmp/contents"
for f in ./usr/bin/vb_run ./usr/bin/vb_batch ./usr/bin/vb_report ./usr/bin/vb_view \
         ./usr/bin/vb_gym ./usr/bin/vb_gen ./usr/bin/vb_import ./usr/share/vb/tasks/env042.yaml \
         ./usr/share/vb/data/vehicles/hmmwv.yaml ./usr/share/vb/data/worlds/env042.png \
         ./usr/share/vb/data/soils/verti_bench.yaml ./usr/share/vb/web/viewer/index.html \
         ./usr/share/doc/vb/README.md; do
  grep -qxF "$f" "$tmp/contents" || fail "$f missing from the package"
done
depends=$(dpkg-deb -f "$deb" Depends)
echo "DebPackageTest: Depends: $depends"
for p in libbullet libyaml-cpp libopencv-core libopencv-imgproc libpng16 libstdc++6 \
         libc6; do
  echo "$depends" | grep -q "$p" || fail "Depends lacks $p"
done
# Every shared library a tool needs comes from a package named in Depends.
echo "$depends" | tr ',' '\n' | awk '{print $1}' > "$tmp/depends"
dpkg-deb -x "$deb" "$tmp/root"
for lib in $(objdump -p "$tmp"/root/usr/bin/vb_* | awk '/NEEDED/ {print $2}' | sort -u); do
  path=$(ldconfig -p | awk -v l="$lib" '$1 == l && /x86-64|AArch64/ {print $NF; exit}')
  [ -n "$path" ] || fail "$lib: not found by ldconfig"
  pkg=$(dpkg -S "$(readlink -f "$path")" 2>/dev/null | head -1 | cut -d: -f1) \
    || pkg=$(dpkg -S "$path" | head -1 | cut -d: -f1)
  grep -qxF "$pkg" "$tmp/depends" || fail "$lib ($pkg) is not in Depends"
done
# The unpacked package runs as installed: /usr/bin/vb_run with /usr/share/vb next to it.
mkdir "$tmp/work"
(cd "$tmp/work" && env -i PATH="$tmp/root/usr/bin:/usr/bin:/bin" \
   vb_run "$tmp/root/usr/share/vb/tasks/env042.yaml" --vehicle hmmwv --pair 3 --quiet \
   --out demo > run.log 2>&1) || { cat "$tmp/work/run.log"; fail "unpacked vb_run"; }
[ -f "$tmp/work/demo/env042_p3_s0_hmmwv_pid.json" ] || fail "no trial record"
echo "DebPackageTest: passed"
