# Shared by the sweep tests (after harness.sh): the 6-point sweep of both
# (2 noise values x 3 seeds of `sphere`, ITERATIONS and FIRST_SEED given) and
# the byte comparison of two sweep folders.
write_sweep() { # FILE ITERATIONS FIRST_SEED
  cat >"$1" <<EOF2
{"generator": "sphere", "iterations": $2, "options": ["--no-preview", "--every", "5"],
 "base": {"level": 4},
 "axes": [{"parameter": "noise", "values": [0.01, 0.03]}],
 "seeds": {"count": 3, "first": $3},
 "metrics": ["last_record.radius_mean_cm", "checkpoint.iteration"]}
EOF2
}
# Every file of the runs but the manifest, records and lock owner: the same bytes.
same() { # A B [points...]: the named points (default all 6) equal
  local a="$1" b="$2"; shift 2
  local pts="${*:-0000 0001 0002 0003 0004 0005}" p f
  for p in $pts; do
    [ -s "$a/runs/$p/sphere/final.ply" ] || { echo "  $a/runs/$p has no final mesh"; return 1; }
    (cd "$a/runs/$p" && find . -type f ! -name manifest.json ! -name records.jsonl ! -name .sessile.lock | sort) >"$T/fa"
    (cd "$b/runs/$p" && find . -type f ! -name manifest.json ! -name records.jsonl ! -name .sessile.lock | sort) >"$T/fb"
    cmp -s "$T/fa" "$T/fb" || { echo "  runs/$p: other files: $(diff "$T/fa" "$T/fb" | tr '\n' ' ')"; return 1; }
    while read -r f; do cmp -s "$a/runs/$p/$f" "$b/runs/$p/$f" || { echo "  runs/$p/$f differs"; return 1; }; done <"$T/fa"
  done
}
