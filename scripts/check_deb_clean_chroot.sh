#!/usr/bin/env bash
# Checks that the Debian package installs with apt on a clean Debian 12 and that the README's
# installed example runs:  vb_run /usr/share/vb/tasks/env042.yaml --vehicle hmmwv
#
#   scripts/check_deb_clean_chroot.sh [--chroot] [DEB]
#
# DEB defaults to a package built now from ./build (cpack -G DEB). Two levels:
#
#  --chroot  (root, debootstrap and network needed) a fresh minimal Debian 12 in a temporary
#            chroot (debootstrap --variant=minbase bookworm), `apt-get install ./vb_*.deb`
#            inside it, then the example runs there: nothing of this machine's libraries,
#            source or build tree is visible to it. Took 22 min on 2026-11-26 on the shared
#            2-core machine (apt installed 153 packages into the minimal system).
#  default   debootstrap-free: (1) apt resolves the package's Depends from the Debian 12
#            archive as on a system with nothing installed (`apt-get install --simulate` with an
#            empty dpkg status file: every dependency, down to libc6, must come from the
#            archive the machine's sources.list names); (2) the package is unpacked into a
#            temporary root and its /usr/bin/vb_run runs the example from another directory
#            with a clean environment (the shared libraries are this machine's, which (1)
#            shows apt would install). It does not prove the package's maintainer scripts
#            (it has none) or that the archive's library versions behave as this machine's.
set -euo pipefail
cd "$(dirname "$0")/.."
chroot_mode=0
deb=""
for arg in "$@"; do
  case "$arg" in
    --chroot) chroot_mode=1 ;;
    -h|--help) awk 'NR > 1 && !/^#/ {exit} NR > 1 {print}' "$0"; exit 0 ;;
    *) deb=$arg ;;
  esac
done
tmp=$(mktemp -d /tmp/vb_deb_check.XXXXXX)
cleanup() {
  if [ -n "${root:-}" ]; then umount -R "$root/proc" 2>/dev/null || true; fi
  rm -rf "$tmp"
}
trap cleanup EXIT
if [ -z "$deb" ]; then
  [ -f build/CPackConfig.cmake ] || { echo "no build/ (run scripts/build.sh)" >&2; exit 2; }
  (cd "$tmp" && cpack --config "$OLDPWD/build/CPackConfig.cmake" -G DEB -B "$tmp/out" >/dev/null)
  deb=$(ls "$tmp"/out/vb_*.deb)
fi
deb=$(readlink -f "$deb")
echo "check: $deb"
example=(vb_run /usr/share/vb/tasks/env042.yaml --vehicle hmmwv --pair 3 --out /tmp/vb_demo)

if [ "$chroot_mode" -eq 1 ]; then
  [ "$(id -u)" -eq 0 ] || { echo "--chroot needs root" >&2; exit 2; }
  if ! command -v debootstrap >/dev/null; then
    echo "--chroot needs debootstrap (apt install debootstrap)" >&2
    exit 2
  fi
  root="$tmp/root"
  debootstrap --variant=minbase bookworm "$root" http://deb.debian.org/debian \
    > "$tmp/debootstrap.log"
  cp "$deb" "$root/tmp/"
  mount -t proc proc "$root/proc"   # /proc/self/exe: how the tools find /usr/share/vb
  chroot "$root" apt-get update -qq
  chroot "$root" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "/tmp/$(basename "$deb")"
  chroot "$root" "${example[@]}"
  chroot "$root" vb_batch --version
  echo "check: passed (apt install and the example in a fresh Debian 12 chroot)"
  exit 0
fi

# (1) apt on a system with nothing installed.
: > "$tmp/empty_status"
apt-get -s -o Dir::State::status="$tmp/empty_status" install "$deb" > "$tmp/apt.log" 2>&1 \
  || { cat "$tmp/apt.log"; echo "check: FAIL: apt cannot resolve the Depends" >&2; exit 1; }
if ! grep -q '^Inst vb ' "$tmp/apt.log"; then
  cat "$tmp/apt.log"
  echo "check: FAIL: vb not installed" >&2
  exit 1
fi
echo "check: apt resolves vb and $(grep -c '^Inst ' "$tmp/apt.log") packages from an empty system"
# (2) the unpacked package runs the example from another directory, clean environment.
dpkg-deb -x "$deb" "$tmp/root"
mkdir "$tmp/work"
example[1]="$tmp/root${example[1]}"
example[-1]="$tmp/work/vb_demo"
(cd "$tmp/work" && env -i PATH="$tmp/root/usr/bin:/usr/bin:/bin" "${example[@]}")
echo "check: passed (debootstrap-free: apt resolution on an empty status, unpacked package runs)"
