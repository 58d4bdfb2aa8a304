#!/usr/bin/env bash
# The paper's Figures 7-12 as measured outcomes (issue 33;
# docs/sds_figures.md): runs the shipped models and the
# references their criteria compare against, two at a time, then measures
# each with tools/sds/figures.py and prints one line per criterion.
#
#   limb             to t = 200              Figure 7 (figures.py limb)
#   six_limbs_box    to t = 250, and without its box          Figure 8 (bend)
#   attractor        to t = 250, and with the attraction 0    Figure 10 (attract)
#   budded           to t = 400                                Figure 11 (buds)
#   rock             to t = 400, and with the timer's decay halved
#                                            Figures 9 and 12 (stripes, cells, divisions)
#
# About 20 minutes on 2 cores (lavapipe); the rock runs are the longest.
#
#   tools/sds/figures_study.sh [SESSILE [OUT_DIR]]
#     SESSILE  the binary (default build/sessile)
#     OUT_DIR  where the runs go (default runs/sds-figures; must not exist,
#              or be this study's own folder, which is replaced)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
SESSILE="${1:-$root/build/sessile}"
OUT="${2:-runs/sds-figures}"
. "$here/study_dir.sh"
study_prepare figures_study "$SESSILE" "$OUT" .sds_figures_study
M="$root/host/sds/models"
cp "$M/limb.sds" "$M/six_limbs_box.sds" "$M/attractor.sds" "$M/budded.sds" "$M/rock.sds" "$OUT/"
# the references: one change each
sed 's/^box = .*/# (no box: the reference of Figure 8)/' "$M/six_limbs_box.sds" >"$OUT/six_limbs_nobox.sds"
sed 's/^attractor = \([^ ]* [^ ]* [^ ]*\) [^ #]*/attractor = \1 0/' "$M/attractor.sds" >"$OUT/attractor_off.sds"
awk '/^timer clock decay=/ { sub(/decay=[0-9.eE+-]+/, "decay=" substr($3, 7) / 2) } { print }' "$M/rock.sds" \
  >"$OUT/rock_half.sds"
grep -q '^box' "$OUT/six_limbs_nobox.sds" && { echo "figures_study: the box is still in the reference" >&2; exit 1; }
awk '$1 == "attractor" && $6 == 0 { ok = 1 } END { exit !ok }' "$OUT/attractor_off.sds" || { echo "figures_study: the attraction is not off" >&2; exit 1; }
cmp -s "$M/rock.sds" "$OUT/rock_half.sds" && { echo "figures_study: the timer's decay is unchanged" >&2; exit 1; }
printf '%s\n' "limb 200 20" "six_limbs_box 250 25" "six_limbs_nobox 250 25" "attractor 250 25" "attractor_off 250 25" \
  "budded 400 40" "rock 400 80" "rock_half 400 80" |
  xargs -P 2 -L 1 sh -c '"$0" sds run "$1/$2.sds" --t-end "$3" --frames "$4" --out "$1/$2" --quiet --progress none' \
    "$SESSILE" "$OUT"
FIG="/usr/bin/python3 -B $here/figures.py"
last() { tail -n 1; }
{
  echo "== Figure 7: limb at t = 200"; $FIG limb "$OUT/limb" --time 200 | last
  echo "== Figure 8: six_limbs_box against six_limbs_nobox"
  for t in 100 150 200 250; do $FIG bend "$OUT/six_limbs_box" --ref "$OUT/six_limbs_nobox" --time $t | last; done
  echo "== Figure 10: attractor against attractor_off"
  for t in 100 150 200 250; do $FIG attract "$OUT/attractor" --ref "$OUT/attractor_off" --time $t | last; done
  echo "== Figure 11: budded"
  for t in 250 300 350 400; do $FIG buds "$OUT/budded" --time $t | last; done
  echo "== Figure 9: rock, then rock_half, at t = 400"
  $FIG stripes "$OUT/rock" --time 400 | last
  $FIG stripes "$OUT/rock_half" --time 400 --ref "$OUT/rock" | last
  echo "== Figure 12: rock's cells from t = 100 to 400"; $FIG cells "$OUT/rock" | last
  echo "== Figure 12: which of rock's limbs divided when"; $FIG divisions "$OUT/rock" | last
} | tee "$OUT/figures_study.txt"
