#!/usr/bin/python3
"""The study's grid-convergence table from a sweep (tools/science/sweeps/grid.json)
run by `sessile sweep` and tabulated by `sessile sweep gather`.

usage: tools/science/sweep_tables.py grid SWEEP_DIR [--against RESULTS.json]

Reads SWEEP_DIR/gather/points.csv (gather's table: each point's seed, state and
parameters) and, for each completed point, its final surface
(runs/NNNN/sponge/final.ply) measured by study.py's own code (metrics.py), then
prints the table of docs/science_results.md "Grid convergence": with the three
levels, study.py's report itself; with fewer (r = 3 still pending, say), the
columns of the levels that are there.  --against compares every per-seed value
with a study's results.json (docs/science_results.json): the relative
difference and whether the 4 digits the report prints agree.
"""
import argparse
import csv
import json
import os
import sys
import types

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True
sys.path.insert(0, HERE)
import study  # noqa: E402  (checks numpy and scipy)


class Point:
    """A completed point of the sweep, shaped as study.measure wants a run."""

    def __init__(self, folder):
        self._folder = folder
        m = json.load(open(os.path.join(folder, "manifest.json")))
        cfg = m.get("config", {})
        self.iterations = cfg.get("iterations")
        self.table = {k: str(v) for k, v in cfg.get("parameters", {}).items()}
        self.metrics = None

    def folder(self, out):
        return self._folder


def completed_points(d):
    """{(seed, box_resolution): Point} from gather's points.csv."""
    plan = json.load(open(os.path.join(d, "sweep.json")))
    width = plan["width"]
    runs = {}
    with open(os.path.join(d, "gather", "points.csv"), newline="") as f:
        for row in csv.DictReader(f):
            if row["state"] != "completed":
                continue
            p = Point(os.path.join(d, "runs", "%0*d" % (width, int(row["index"]))))
            study.measure(p, None)
            runs[(int(row["seed"]), int(row["box_resolution"]))] = p
    return plan, runs


def grid(d, against):
    plan, runs = completed_points(d)
    seeds = sorted({s for s, _ in runs})
    levels = sorted(r for r in {r for _, r in runs} if all((s, r) in runs for s in seeds))
    if not levels:
        sys.exit("sweep_tables: no level has every seed completed (run `sessile sweep gather` first)")
    base = plan["sweep"].get("base", {})
    P = types.SimpleNamespace(grid_levels=levels, grid_seeds=seeds, grid_iterations=plan["iterations"],
                              grid_jitter=base.get("position_jitter", 0), quick=False)
    if len(levels) == 3:
        print("\n".join(study.report_grid(P, study.analyse_grid(P, runs), runs)))
    else:
        print(f"Levels {', '.join(map(str, levels))} of the sweep's {len(plan['sweep']['axes'][0]['values'])} "
              "(the others are not completed for every seed).\n")
        rows = []
        for k, label in study.GRID_METRICS:
            vals = [[runs[(s, r)].metrics[k] for s in seeds] for r in levels]
            st = [study.stats(v) for v in vals]
            row = [label] + [f"{study.fnum(x['mean'], 4)} ± {study.fnum(x['std'], 2)}" for x in st]
            row += [study.fpct((st[i + 1]["mean"] - st[i]["mean"]) / abs(st[i + 1]["mean"])) for i in range(len(levels) - 1)]
            rows.append(row)
        head = ["metric (mean ± sd over seeds)"] + [f"r = {r}" for r in levels]
        head += [f"r{levels[i]}→r{levels[i + 1]}" for i in range(len(levels) - 1)]
        print(study.table(head, rows))
    return compare(against, runs, seeds, levels) if against else True


def compare(path, runs, seeds, levels):
    g = json.load(open(path))["parts"]["grid"]
    worst, differ = 0.0, []
    for k, label in study.GRID_METRICS:
        for s in seeds:
            ref = g["per_seed"][k][str(s)]["values"]
            for r in levels:
                a, b = runs[(s, r)].metrics[k], ref[g["levels"].index(r)]
                rel = abs(a - b) / abs(b) if b else abs(a)
                worst = max(worst, rel)
                if study.fnum(a, 4) != study.fnum(b, 4):
                    differ.append(f"{label} seed {s} r = {r}: {study.fnum(a, 4)} against {study.fnum(b, 4)}")
    n = len(study.GRID_METRICS) * len(seeds) * len(levels)
    print(f"\nAgainst {os.path.basename(path)}: {n} per-seed values, worst relative difference {worst:.3g}; "
          + ("every printed value agrees." if not differ else f"{len(differ)} printed values differ:"))
    for line in differ:
        print("  " + line)
    return not differ


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("table", choices=["grid"])
    ap.add_argument("sweep_dir")
    ap.add_argument("--against", help="a study's results.json to compare the per-seed values with")
    a = ap.parse_args(argv)
    if not os.path.isfile(os.path.join(a.sweep_dir, "gather", "points.csv")):
        sys.exit(f"sweep_tables: no {a.sweep_dir}/gather/points.csv: run `sessile sweep gather {a.sweep_dir}` first")
    return 0 if grid(a.sweep_dir, a.against) else 1


if __name__ == "__main__":
    sys.exit(main())
