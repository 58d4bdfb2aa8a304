#!/usr/bin/env bash
# `sessile sweep gather`'s pictures (docs/sweep.md "Gather"): on an 8-point
# sweep of `sphere` (noise x level, 2 seeds, previews on) one plot per metric
# with numbers and axis, 800 x 600; none for a metric of text; a plot changes
# when its metric's numbers change and only then; the contact sheet is
# `sessile render --sheet` of the completed points' previews with their
# captions (the same bytes), one row per combination; a point without a
# preview is left out and counted.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"

cat >"$T/sweep.json" <<'EOF'
{"generator": "sphere", "iterations": 6, "options": ["--every", "3"],
 "axes": [{"parameter": "noise", "values": [0.03, 0.01]}, {"parameter": "level", "values": [2, 3]}],
 "seeds": {"count": 2},
 "metrics": ["last_record.radius_mean_cm", "checkpoint.iteration", "state"]}
EOF
"$S" sweep plan "$T/sweep.json" --out "$T/s" >/dev/null
run sweep run "$T/s" -j 2
check "the sweep runs (8 points)" eval 'rc_is 0 && "$S" sweep status "$T/s" | grep -q "8 points: 8 completed"'

# A PNG's width and height from its header.
size() { od -An -tu1 -j16 -N8 "$1" | awk '{print $1*16777216+$2*65536+$3*256+$4, $5*16777216+$6*65536+$7*256+$8}'; }
P="$T/s/gather/plots"
plots="last_record.radius_mean_cm-vs-noise last_record.radius_mean_cm-vs-level checkpoint.iteration-vs-noise checkpoint.iteration-vs-level"
run sweep gather "$T/s"
check "gather: exit 0, says 4 plots and a sheet of 8" eval \
  'rc_is 0 && grep -q "^sweep: 4 plots in .*gather/plots/ (metrics with no completed number not plotted)" "$T/out" &&
   grep -q "^sweep: a contact sheet of 8 previews in .*gather/sheet.png$" "$T/out"'
check "a plot per numeric metric and axis, 800 x 600" eval \
  'for p in $plots; do [ "$(size "$P/$p.png")" = "800 600" ] || exit 1; done'
check "no plot of a metric of text (state)" eval '[ "$(ls "$P")" = "$(for p in $plots; do echo $p.png; done | sort)" ]'
mkdir "$T/before" && cp "$P"/*.png "$T/before/"

# The sheet: render --sheet of the previews, captions "NNNN seed S axis=value ...".
args=()
for i in 0 1 2 3 4 5 6 7; do
  c=$((i / 2)) seed=$((i % 2 + 1)) noise=0.03 level=2
  [ $c -ge 2 ] && noise=0.01
  [ $((c % 2)) = 1 ] && level=3
  args+=("$T/s/runs/000$i/preview.png" --caption "000$i seed $seed noise=$noise level=$level")
done
"$S" render --sheet 2 -o "$T/ref.png" "${args[@]}" >/dev/null
check "the sheet is render --sheet 2 of the 8 previews with their captions (same bytes)" cmp -s "$T/ref.png" "$T/s/gather/sheet.png"
read -r pw ph <<<"$(size "$T/s/runs/0000/preview.png")"
check "... 2 columns (the seeds) by 4 rows (the combinations): the layout's size" eval \
  '[ "$(size "$T/s/gather/sheet.png")" = "$((8 + 2 * (pw + 8))) $((8 + 4 * (ph + 22 + 8)))" ]'

# Change one point's radius in its last record: its metric's plots change, the others not.
r="$T/s/runs/0005/records.jsonl"
/usr/bin/python3 - "$r" <<'PYEOF'
import json, sys
lines = open(sys.argv[1]).read().splitlines()
last = json.loads(lines[-1]); last["radius_mean_cm"] *= 1.5
open(sys.argv[1], "w").write("\n".join(lines[:-1] + [json.dumps(last)]) + "\n")
PYEOF
run sweep gather "$T/s"
check "a changed radius changes both radius plots" eval \
  '! cmp -s "$T/before/last_record.radius_mean_cm-vs-noise.png" "$P/last_record.radius_mean_cm-vs-noise.png" &&
   ! cmp -s "$T/before/last_record.radius_mean_cm-vs-level.png" "$P/last_record.radius_mean_cm-vs-level.png"'
check "... and leaves the iteration plots byte-identical" eval \
  'cmp -s "$T/before/checkpoint.iteration-vs-noise.png" "$P/checkpoint.iteration-vs-noise.png" &&
   cmp -s "$T/before/checkpoint.iteration-vs-level.png" "$P/checkpoint.iteration-vs-level.png"'

rm "$T/s/runs/0006/preview.png"
run sweep gather "$T/s"
check "a point without preview.png is left out and counted" eval \
  'rc_is 0 && grep -q "contact sheet of 7 previews .*(1 completed points without preview.png left out)" "$T/out"'
check "... the sheet is 2 x 4 cells still (7 tiles)" eval \
  '[ "$(size "$T/s/gather/sheet.png")" = "$((8 + 2 * (pw + 8))) $((8 + 4 * (ph + 22 + 8)))" ]'
rm "$T"/s/runs/*/preview.png
run sweep gather "$T/s"
check "no preview at all: no sheet, said so" eval \
  'rc_is 0 && grep -q "no contact sheet" "$T/out" && [ ! -e "$T/s/gather/sheet.png" ]'
finish
