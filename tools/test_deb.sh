#!/usr/bin/env bash
# Builds the Debian packages with CPack and checks them (docs/install.md):
#   tools/test_deb.sh [BUILD_DIR]            build, then check with dpkg-deb
#   tools/test_deb.sh [BUILD_DIR] --chroot   also install into a fresh Debian 12
#                                            chroot and run sessile there
# The dpkg-deb checks: the two packages' names, files and Depends, and that
# every shared library the binary and libsessile.so load belongs to a package
# named in Depends (dpkg -S on this machine).  The chroot check (root,
# debootstrap, network to a Debian mirror; minutes): `apt-get install
# ./sessile_*.deb ./sessile-dev_*.deb` in a minimal bookworm, then
# `sessile --version`, `sessile sphere`, the man page, completion of
# `sessile gr`, and the embedding example built with pkg-config.
set -u
B=$(realpath "${1:-build}")
CHROOT=0
[ "${2:-}" = --chroot ] && CHROOT=1
SRC=$(cd "$(dirname "$0")/.." && pwd)
. "$SRC/tests/common/harness.sh"

cmake --build "$B" -j"$(nproc)" --target sessile sessile_shared >"$T/build.log" 2>&1 || { tail -20 "$T/build.log"; exit 1; }
(cd "$T" && cpack --config "$B/CPackConfig.cmake" -G DEB -B "$T/pkg") >"$T/cpack.log" 2>&1
RT=$(ls "$T"/pkg/sessile_*.deb 2>/dev/null | head -1)
DEV=$(ls "$T"/pkg/sessile-dev_*.deb 2>/dev/null | head -1)
check "cpack -G DEB builds sessile_*.deb and sessile-dev_*.deb" eval \
  '[ -n "$RT" ] && [ -n "$DEV" ] || { cat "$T/cpack.log"; false; }'
[ -n "$RT" ] && [ -n "$DEV" ] || { finish; exit 1; }

field() { dpkg-deb -f "$1" "$2"; }
deps=$(field "$RT" Depends)
echo "sessile Depends: $deps"
depends() { echo "$deps" | tr ',' '\n' | awk '{ print $1 }' | grep -qxF -- "$1"; } # a package named there
check "sessile: package name, version, architecture" eval \
  '[ "$(field "$RT" Package)" = sessile ] && [ -n "$(field "$RT" Version)" ] && [ "$(field "$RT" Architecture)" = "$(dpkg --print-architecture)" ]'
missing=""
for p in libvulkan1 mesa-vulkan-drivers libopenexr-3-1-30 libcjson1 libmuparser2v5 libcairo2 libpng16-16 zlib1g libtet1.5 libgomp1; do
  depends "$p" || missing="$missing $p"
done
check "sessile Depends on the runtime libraries and the Vulkan driver${missing:+ (missing:$missing)}" test -z "$missing"
check "sessile-dev Depends on sessile of the same version and the -dev packages" eval \
  'field "$DEV" Depends | grep -q "sessile (= $(field "$RT" Version))" && field "$DEV" Depends | grep -q libcjson-dev'

dpkg-deb -c "$RT" | awk '{ print $6 }' >"$T/rt.list"
dpkg-deb -c "$DEV" | awk '{ print $6 }' >"$T/dev.list"
bad=""
for f in ./usr/bin/sessile ./usr/share/man/man1/sessile.1 ./usr/share/bash-completion/completions/sessile \
         ./usr/share/zsh/vendor-completions/_sessile; do
  grep -qx -- "$f" "$T/rt.list" || bad="$bad $f"
done
grep -qE '^\./usr/lib/(.*/)?libsessile\.so\.[0-9]+\.[0-9]+\.[0-9]+$' "$T/rt.list" || bad="$bad libsessile.so.X.Y.Z"
check "sessile holds the binary, the man page, both completions, libsessile.so.X.Y.Z${bad:+ (missing:$bad)}" test -z "$bad"
bad=""
for f in ./usr/include/sessile/status.h ./usr/include/sessile/mesh/surface.h ./usr/include/sessile/io/io.h; do
  grep -qx -- "$f" "$T/dev.list" || bad="$bad $f"
done
for f in 'libsessile\.a' 'libsessile\.so' 'pkgconfig/sessile\.pc'; do
  grep -qE "^\./usr/lib/(.*/)?$f\$" "$T/dev.list" || bad="$bad $f"
done
check "sessile-dev holds the headers, libsessile.a, the .so link and sessile.pc${bad:+ (missing:$bad)}" test -z "$bad"
check "sessile-dev holds no file of sessile" eval '[ -z "$(grep -v "/$" "$T/rt.list" | grep -xFf - "$T/dev.list")" ]'

# Every library the ELF files load, by the package that holds it here.
dpkg-deb -x "$RT" "$T/root"
unowned=""
for elf in "$T/root/usr/bin/sessile" $(find "$T/root" -name 'libsessile.so.*' -type f); do
  for lib in $(readelf -d "$elf" | sed -n 's/.*NEEDED.*\[\(.*\)\]/\1/p'); do
    path=$(ldconfig -p | awk -v l="$lib" '$1 == l && /x86-64|64bit/ { print $NF; exit }')
    [ -n "$path" ] || path=$(ldconfig -p | awk -v l="$lib" '$1 == l { print $NF; exit }')
    pkg=""
    for p in "$path" "$(realpath "$path")" "${path#/usr}" "/usr$path"; do # merged /usr: dpkg knows one name
      [ -n "$pkg" ] || pkg=$(dpkg -S "$p" 2>/dev/null | head -1 | cut -d: -f1)
    done
    depends "$pkg" || unowned="$unowned $lib($pkg)"
  done
done
check "every NEEDED library of sessile and libsessile.so is in a package of Depends${unowned:+ (not:$unowned)}" test -z "$unowned"

if [ "$CHROOT" = 1 ]; then
  # A fresh, minimal Debian 12: only what the packages' Depends bring.
  R="$T/chroot"
  if debootstrap --variant=minbase bookworm "$R" http://deb.debian.org/debian >"$T/debootstrap.log" 2>&1; then
    cp "$RT" "$DEV" "$SRC/docs/embed/example.c" "$R/tmp/"
    mount -t proc proc "$R/proc" 2>/dev/null && trap 'umount "$R/proc"; rm -rf "$T"' EXIT
    in_root() { chroot "$R" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8 bash -c "$1"; }
    in_root 'apt-get update -qq && apt-get install -y -qq --no-install-recommends \
               /tmp/'"$(basename "$RT")"' /tmp/'"$(basename "$DEV")"' gcc libc6-dev man-db bash-completion' \
      >"$T/apt.log" 2>&1
    apt_rc=$?
    check "apt-get install ./sessile_*.deb ./sessile-dev_*.deb in a fresh bookworm" eval \
      '[ $apt_rc -eq 0 ] || { tail -20 "$T/apt.log"; false; }'
    check "chroot: sessile --version" in_root 'sessile --version | grep -q "^sessile "'
    check "chroot: sessile sphere writes its run" in_root \
      'cd /tmp && sessile sphere --out /tmp/ball --quiet && test -s /tmp/ball/sphere/final.ply'
    check "chroot: man sessile" in_root 'MANWIDTH=80 man sessile 2>/dev/null | grep -q "^NAME"'
    check "chroot: bash completes sessile gr to grow" in_root \
      '. /usr/share/bash-completion/completions/sessile; COMP_WORDS=(sessile gr); COMP_CWORD=1; _sessile; [ "${COMPREPLY[*]}" = grow ]'
    check "chroot: the embedding example builds with pkg-config and runs" in_root \
      'cd /tmp && cc example.c $(pkg-config --cflags --libs sessile) -o example && ./example ball.ply 2 | grep -q "^vertices 42 "'
  else
    tail -5 "$T/debootstrap.log"
    check "debootstrap bookworm (needs root and a Debian mirror)" false
  fi
fi
finish
