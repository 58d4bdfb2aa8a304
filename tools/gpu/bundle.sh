#!/usr/bin/env bash
# Packs a Release build into one folder that runs on another x86-64 Linux
# machine with a GPU's Vulkan driver but none of Debian's packages (a lent
# GPU machine, a cluster node): the stripped `sessile` and the SDS and GPU
# test binaries (xz), the shared libraries they load but glibc's, libstdc++'s
# and the Vulkan loader's, and Debian's Vulkan loader, glvnd and Khronos
# validation layer as .deb files.  tools/gpu/check.sh, run there from a copy
# of the source tree, unpacks it and runs the bench and the tests.  The
# bundle is about 45 MiB.  docs/performance.md, "A real GPU", has what it
# measured.
#
# usage: tools/gpu/bundle.sh [BUILD_DIR [BUNDLE_DIR]]
#   BUILD_DIR   a Release build (default build)
#   BUNDLE_DIR  a new or empty folder (default .gpu-bundle, which .gitignore
#               lists)
set -euo pipefail
case "${1:-}" in -h|--help) sed -n 2,15p "$0" | sed 's/^# \{0,1\}//'; exit 0;; esac
BUILD=${1:-build}
OUT=${2:-.gpu-bundle}
[ -x "$BUILD/sessile" ] || { echo "bundle.sh: no $BUILD/sessile: build first (README)" >&2; exit 2; }
if [ -e "$OUT" ] && [ -n "$(ls -A "$OUT")" ]; then
  echo "bundle.sh: $OUT is not empty" >&2; exit 2
fi
# The test binaries check.sh runs (tests/CMakeLists.txt builds them).
TESTS="test_gpu test_rules_vm test_morph_gpu test_sds_batch test_sds_stable test_sds_lists
  test_sds_collide test_sds_forces test_sds_dynamics test_sds_collide_dyn test_sds_adhesion
  test_sds_axial test_sds_symmetric test_sds_complex test_vec test_spmv test_solvers fuzz_rules_device"
for t in $TESTS; do
  [ -x "$BUILD/tests/$t" ] || { echo "bundle.sh: no $BUILD/tests/$t" >&2; exit 2; }
done
mkdir -p "$OUT"
STAGE=$(mktemp -d)
trap 'rm -rf "$STAGE"' EXIT
mkdir -p "$STAGE/bin" "$STAGE/lib"
strip -o "$STAGE/bin/sessile" "$BUILD/sessile"
for t in $TESTS; do strip -o "$STAGE/bin/$t" "$BUILD/tests/$t"; done
# Libraries the target may lack; glibc, libstdc++ and libgcc are the
# target's own (newer there is fine), and the Vulkan loader comes as a .deb.
ldd "$BUILD/sessile" "$BUILD/tests/test_gpu" | awk '$3 ~ /^\//{print $3}' | sort -u |
  grep -v -E '/(libc|libm|libgcc_s|libstdc\+\+|libvulkan|ld-linux[^/]*)\.so' |
  while read -r l; do cp -L "$l" "$STAGE/lib/"; done
tar cf - -C "$STAGE" bin | xz -T0 -6 > "$OUT/bin.tar.xz.tmp" && mv "$OUT/bin.tar.xz.tmp" "$OUT/bin.tar.xz"
tar cf - -C "$STAGE" lib | xz -T0 -6 > "$OUT/lib.tar.xz.tmp" && mv "$OUT/lib.tar.xz.tmp" "$OUT/lib.tar.xz"
# Debian's loader, glvnd (the NVIDIA ICD loads through libGLX) and the
# validation layer, fetched with lists of our own so no root is needed.
LISTS="$STAGE/apt"
mkdir -p "$LISTS/lists/partial" "$LISTS/cache/archives/partial" "$OUT/debs"
APT=(-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists="$LISTS/lists"
     -oDir::Cache="$LISTS/cache" -oDebug::NoLocking=1 -oAPT::Sandbox::User="$(id -un)")
apt-get "${APT[@]}" update -qq
(cd "$OUT/debs" && apt-get "${APT[@]}" download -qq libvulkan1 libegl1 libglvnd0 libopengl0 \
  libgl1 libglx0 libgles2 vulkan-validationlayers)
git -C "$(dirname "$0")" rev-parse --short HEAD > "$OUT/commit" 2>/dev/null || echo unknown > "$OUT/commit"
du -sh "$OUT"
echo "bundle.sh: $OUT holds the build of $(cat "$OUT/commit"); there: tools/gpu/check.sh $OUT RESULTS_DIR"
