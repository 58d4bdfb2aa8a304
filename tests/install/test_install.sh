#!/usr/bin/env bash
# `cmake --install` into a temporary prefix, then what a user of the
# installation meets (docs/install.md): the binary, the man page (which must
# name every command, generator and global option `sessile --help` lists),
# bash and zsh completion driven the way the shells drive them, the shared
# library's SONAME, headers that compile on their own, and the embedding
# example built with pkg-config against the prefix and run.
# Usage: test_install.sh BUILD_DIR SOURCE_DIR
set -u
B="$1" SRC="$2"
. "$SRC/tests/common/harness.sh"
P="$T/prefix"

cmake --install "$B" --prefix "$P" >"$T/install.log" 2>&1
install_rc=$?
check "cmake --install into a fresh prefix" eval '[ $install_rc -eq 0 ] || { cat "$T/install.log"; false; }'
S="$P/bin/sessile"

run --version
check "bin/sessile --version runs" eval 'rc_is 0 && grep -Eq "^sessile [0-9]+\.[0-9]+" "$T/out"'

# --- the man page -------------------------------------------------------------
M="$P/share/man/man1/sessile.1"
check "share/man/man1/sessile.1 is installed" test -s "$M"
if command -v man >/dev/null; then
  MANWIDTH=250 man -l "$M" >"$T/man.txt" 2>"$T/man.err"
else
  groff -man -Tutf8 -rLL=250n "$M" >"$T/man.txt" 2>"$T/man.err"
fi
check "the man page renders without warnings" eval '[ -s "$T/man.txt" ] && [ ! -s "$T/man.err" ] && grep -q "^NAME" "$T/man.txt"'
groff -man -Tutf8 -ww -z "$M" 2>"$T/groff.err"
check "groff -ww finds nothing to warn about" eval '[ ! -s "$T/groff.err" ] || { cat "$T/groff.err"; false; }'
# Every command and generator under "commands:" and "generators" in --help,
# and every global option, must be in the man page (it is written by hand).
# (generator names are two words at most, in a 16-column field)
"$S" --help | awk '/^[a-z].*:$/ { on = ($1 == "commands:") + 2 * ($1 == "generators"); next } /^$/ { on = 0 }
                   on == 1 && /^  [a-z]/ { print $1 }
                   on == 2 && /^  [a-z]/ { n = substr($0, 3, 16); sub(/ +$/, "", n); print n }' >"$T/names"
"$S" --help | sed -n '/^options/,/^$/p' | grep -oE -- '^  --[a-z-]+' | tr -d ' ' >>"$T/names"
check "--help lists commands, generators and options to compare with" eval '[ $(wc -l <"$T/names") -ge 12 ]'
missing=""
while read -r name; do
  grep -qF -- "$name" "$T/man.txt" || missing="$missing [$name]"
done <"$T/names"
check "the man page names everything --help lists${missing:+ (missing:$missing)}" test -z "$missing"

# --- bash completion ------------------------------------------------------------
BC="$P/share/bash-completion/completions/sessile"
check "the bash completion is installed" test -s "$BC"
complete_bash() { # words...: what _sessile offers for the last word
  PATH="$P/bin:$PATH" bash -c '. "$1"; shift; complete -p sessile | grep -q -- "-F _sessile" || exit 3
    COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1)); _sessile; printf "%s\n" "${COMPREPLY[@]}"' x "$BC" "$@"
}
check "bash: 'sessile gr<TAB>' completes to grow" eval '[ "$(complete_bash sessile gr)" = grow ]'
check "bash: 'sessile coral <TAB>' offers lsystem and venation" eval \
  '[ "$(complete_bash sessile coral "" | tr "\n" " ")" = "lsystem venation " ]'
check "bash: 'sessile grow --it<TAB>' completes to --iterations" eval \
  '[ "$(complete_bash sessile grow --it)" = --iterations ]'
# parameter names come from the table: all of --print-config's, as KEY=
"$S" sphere --print-config | awk 'NR > 1 { print $1 "=" }' | sort >"$T/params"
complete_bash sessile sphere --set "" | sort >"$T/offered"
check "bash: 'sessile sphere --set <TAB>' offers every parameter of the table" eval \
  '[ $(wc -l <"$T/params") -ge 3 ] && cmp -s "$T/params" "$T/offered"'
check "bash: 'sessile grow --set probe_d<TAB>' completes to probe_distance=" eval \
  '[ "$(complete_bash sessile grow --set probe_d)" = probe_distance= ]'

# --- zsh completion (zsh is a test dependency: tools/install.sh installs it) --------
ZC="$P/share/zsh/vendor-completions/_sessile"
check "the zsh completion is installed" test -s "$ZC"
if command -v zsh >/dev/null; then
  check "zsh parses the completion" zsh -n "$ZC"
  # compadd stands in for zsh's own, which filters by the typed prefix.
  complete_zsh() {
    PATH="$P/bin:$PATH" zsh -fc 'compadd() { while [[ $1 == -* && $1 != -- ]]; do [[ $1 == -S ]] && shift; shift; done
      [[ $1 == -- ]] && shift; print -l -- ${(M)@:#${words[CURRENT]}*} }
      _files() { print FILES }; ZC=$1; shift; words=("$@"); CURRENT=$#; source $ZC' x "$ZC" "$@"
  }
  check "zsh: 'sessile gr<TAB>' completes to grow" eval '[ "$(complete_zsh sessile gr)" = grow ]'
  check "zsh: 'sessile sphere --set <TAB>' offers every parameter of the table" eval \
    '[ "$(complete_zsh sessile sphere --set "" | sort)" = "$(cat "$T/params")" ]'
else
  check "zsh is installed (tools/install.sh), so the zsh completion can be exercised" false
fi

# --- the library, its headers, pkg-config -----------------------------------------
so=$(find "$P" -name 'libsessile.so.*.*.*' | head -1)
check "libsessile.so.X.Y.Z is installed with SONAME libsessile.so.X.Y" eval \
  '[ -n "$so" ] && readelf -d "$so" | grep -Eq "SONAME.*\[libsessile\.so\.[0-9]+\.[0-9]+\]"'
check "libsessile.a is installed" eval '[ -n "$(find "$P" -name libsessile.a)" ]'
pc=$(find "$P" -name sessile.pc | head -1)
export PKG_CONFIG_PATH="$(dirname "${pc:-$P}")"
check "sessile.pc is installed and pkg-config answers for the moved prefix" eval \
  '[ -n "$pc" ] && pkg-config --cflags sessile | grep -qF -- "-I$P/include" && pkg-config --libs sessile | grep -q -- -lsessile'
CC=${CC:-cc}
SAN=""
[ "${SESSILE_TEST_SANITIZED:-0}" = 1 ] && SAN="-fsanitize=address,undefined"
bad=""
for h in $(cd "$P/include" && find sessile -name '*.h' | LC_ALL=C sort); do
  echo "#include <$h>" | $CC -std=c17 -Wall -Werror -fsyntax-only -x c - $(pkg-config --cflags sessile) 2>/dev/null ||
    bad="$bad $h"
done
check "every installed header compiles on its own${bad:+ (not:$bad)}" test -z "$bad"

$CC -std=c17 -Wall -Werror $SAN "$SRC/docs/embed/example.c" $(pkg-config --cflags --libs sessile) \
  -o "$T/example" 2>"$T/cc.err"
check "docs/embed/example.c builds with pkg-config --cflags --libs sessile" eval \
  '[ -x "$T/example" ] || { cat "$T/cc.err"; false; }'
LD_LIBRARY_PATH="$(dirname "$so")" ldd "$T/example" >"$T/ldd" 2>&1
check "the example is linked to the installed libsessile.so" grep -qF "$(dirname "$so")/libsessile.so." "$T/ldd"
LD_LIBRARY_PATH="$(dirname "$so")" "$T/example" "$T/ball.ply" 3 >"$T/out" 2>"$T/err"
# level 3: 10*4^2+2 vertices, 20*4^2 triangles (the icosphere's counts)
check "the example runs and writes the level-3 icosphere as PLY" eval \
  'grep -q "^vertices 162 triangles 320 " "$T/out" && head -c 400 "$T/ball.ply" | grep -aq "^element vertex 162" &&
   head -c 400 "$T/ball.ply" | grep -aq "^property float height"'
$CC -std=c17 $SAN "$SRC/docs/embed/example.c" $(pkg-config --cflags sessile) \
  "$(dirname "$so")/libsessile.a" $(pkg-config --static --libs-only-other --libs-only-l sessile | sed 's/-lsessile//') \
  -o "$T/example_static" 2>"$T/cc2.err"
"$T/example_static" "$T/ball2.ply" 3 >/dev/null 2>&1
check "the example links libsessile.a with pkg-config --static and writes the same PLY" eval \
  'cmp -s "$T/ball.ply" "$T/ball2.ply" || { cat "$T/cc2.err"; false; }'
finish
