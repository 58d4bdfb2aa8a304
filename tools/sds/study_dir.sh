# Sourced by the SDS studies (step_study.sh, ensemble_study.sh): the
# binary's check and the study's output folder, made afresh.  A folder that
# exists is replaced only when it is this kind of study's own (its marker
# file inside, not a symbolic link), so a mistyped OUT_DIR never deletes
# anything else.
#   study_prepare NAME SESSILE OUT MARKER
study_prepare() {
  local name="$1" bin="$2" out="$3" marker="$4"
  [ -x "$bin" ] || { echo "$name: no sessile binary at $bin (build first, or name it)" >&2; exit 2; }
  if [ -e "$out" ]; then
    [ -d "$out" ] && [ ! -L "$out" ] && [ -f "$out/$marker" ] ||
      { echo "$name: $out exists and is not this study's folder: name another" >&2; exit 2; }
    rm -rf -- "$out"
  fi
  mkdir -p -- "$out"
  touch "$out/$marker"
}
