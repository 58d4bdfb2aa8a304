#!/usr/bin/python3
"""L(100) of the limb model per max_move, from the sweep tools/sds/sweeps/limb_ensemble.json
(the runs of tools/sds/ensemble_study.sh as one sweep; docs/sweep.md).

usage: tools/sds/limb_sweep.py SWEEP_DIR   (after `sessile sweep gather SWEEP_DIR`)

Reads gather/points.csv for each completed point's max_move and seed, measures
its frames with limb.py, and prints per max_move the mean, standard deviation and
standard error of L(100) over the seeds, and each mean's difference from the
finest setting's with its standard error (ensemble_study.sh's last columns).
"""
import csv, json, math, os, sys
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import limb  # noqa: E402

d = sys.argv[1] if len(sys.argv) == 2 else sys.exit(__doc__)
width = json.load(open(os.path.join(d, "sweep.json")))["width"]
by_move = {}
for row in csv.DictReader(open(os.path.join(d, "gather", "points.csv"), newline="")):
    if row["state"] == "completed":
        sds = os.path.join(d, "runs", "%0*d" % (width, int(row["index"])), "sds")
        by_move.setdefault(float(row["max_move"]), []).append(limb.measure(sds, 5)[5][0])
stats = {}
for mm, v in sorted(by_move.items(), reverse=True):
    m = sum(v) / len(v)
    sd = math.sqrt(sum((x - m) ** 2 for x in v) / (len(v) - 1)) if len(v) > 1 else float("nan")
    stats[mm] = (m, sd, sd / math.sqrt(len(v)), len(v))
fin = stats[min(stats)]
print("max_move  seeds  L(100) mean +- se   sd(L(100))  L(100) - finest (+- se)")
for mm, (m, sd, se, n) in stats.items():
    print("%8.5f  %5d     %7.3f +- %5.3f     %7.3f     %+7.3f (+- %5.3f)" %
          (mm, n, m, se, sd, m - fin[0], math.sqrt(se ** 2 + fin[2] ** 2)))
