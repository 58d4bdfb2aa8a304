#!/usr/bin/python3
"""A random search of the limb model's constants for Figure 7's three criteria
(issue 33; docs/sds_figures.md).

usage: tools/sds/limb_search.py SESSILE OUT [--runs N] [--jobs J] [--seed S]
                                [--t-end T] [--jitter-seeds K] [--from FILE]
                                [--ranges default|narrow|apical|apical_abs|stiff|produce|axial|axial_behind|
                                          axial_inhibit|axial_inhibit_behind|axial_inhibit_stiff|
                                          axial_inhibit_growth]
                                [--realisations K]
                                [--near RESULTS --index N [--spread S]] [--axial Q] [--growth A]

Each point draws the limb model's process constants and a few physics keys
from the ranges below (log-uniform; numpy's generator seeded by --seed, so a
search is repeatable), writes a copy of host/sds/models/limb.sds with them,
runs it to --t-end (default 200) and measures the last frame with
`figures.py limb` (whose width is the complex's section since 2026-12-04:
the searches docs/sds_figures.md reports before that date were read with
the centres' extent, now `--width extent`, and rerun give other scores).
Its score is the sum of the three criteria's relative
shortfalls (0 when all three hold):
  max(0, distal/neck / 1.2 - 1) + max(0, lag / tip radius - 1) + max(0, 1 - (L/neck) / 3).
A point with no neck (a limb under two slices) scores 2-3 by its length;
a point that blows up, passes 1 500 cells or runs past 300 s scores 9.
--ranges picks the ranges (and, for apical, the rules: the tip grows and
divides inward, only the zone's surface grows); --near draws round point N
of an earlier results.jsonl instead, each value times exp(N(0, S)); only
axial_growth is clipped (at 1, its range's end), so R can fall below 1 (a
cell that divides at birth: such points pass 1 500 cells and score 9).
--from FILE reruns the points of an earlier search's results.jsonl (its best
--runs by score) on --jitter-seeds realisations of the start each
(`start_jitter 0.1`, seeds 1..K), to see whether a point carries past the
exact sphere.  --axial Q gives every point the axial stiffness Q (a surface
spring born along base's gradient Q x as stiff; the axial ranges), after the
draw, so that the points are those of the same search without it: a paired
comparison (docs/sds_figures.md, "A sheath softer along the limb"); --growth
A the oriented growth A alike ("Growth along the limb").
Every run's folder is removed once measured; OUT/results.jsonl
holds one JSON line a run (the point, its metrics, its score).
"""
import argparse, json, math, os, re, shutil, subprocess, sys, threading
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
MODEL = os.path.join(HERE, "..", "..", "host", "sds", "models", "limb.sds")
# name: (low, high, log-uniform)
RANGES = {
    "Delta": (0.002, 0.008, True),          # growth rate of the zone's cells
    "phi_decay": (0.15, 1.0, True),         # phi's decay: the zone's reach
    "phi_diffusion": (0.02, 0.2, True),
    "K": (0.01, 0.08, True),                # the zone: phi > K volume
    "R": (1.12, 1.4, False),                # divide at R x birth radius
    "surface_multiplier": (1.0, 4.0, True),
    "viscosity": (0.3, 4.0, True),
}
# --ranges narrow (2026-12-01): a zone of about one ring round the tip (K well
# above the default ranges' 0.08) with fast growth, and the tip itself growing
# to tip_R x its birth radius (rule r0; 1 is the paper's tip, which never grows).
RANGES_NARROW = {
    "Delta": (0.003, 0.03, True),
    "phi_decay": (0.1, 1.0, True),
    "phi_diffusion": (0.02, 0.4, True),
    "K": (0.08, 0.5, True),
    "R": (1.2, 1.4, False),
    "surface_multiplier": (1.0, 4.0, True),
    "viscosity": (0.3, 4.0, True),
    "tip_R": (1.0, 1.6, False),
}
# --ranges apical (2026-12-01): the tip grows at Dt and divides inward
# (`divide away grad(phi)`: the daughter goes below it, the §3.6 cell below
# the tip, again at every division), and only the zone's surface cells grow
# (at Delta), so the interior is the tip's chain.
RANGES_APICAL = {
    "Dt": (0.008, 0.05, True),
    "Delta": (0.0005, 0.004, True),
    "phi_decay": (0.15, 0.8, True),
    "phi_diffusion": (0.02, 0.15, True),
    "K": (0.015, 0.05, True),
    "surface_multiplier": (1.0, 4.0, True),
    "viscosity": (0.3, 4.0, True),
}
# --ranges apical_abs: the same with the tip dividing at an absolute radius Rt
# (`radius > Rt`, as the paper's r3), so that a tip the start made small
# first grows.
RANGES_APICAL_ABS = {
    "Dt": (0.008, 0.05, True),
    "Rt": (0.2, 0.32, False),
    "Delta": (0.0005, 0.004, True),
    "phi_decay": (0.3, 1.5, True),
    "phi_diffusion": (0.03, 0.15, True),
    "K": (0.012, 0.04, True),
    "surface_multiplier": (1.0, 3.0, True),
    "viscosity": (0.5, 3.0, True),
}

# --ranges stiff (2026-12-01, twenty-first session): the default process
# ranges with the physics that sets how a growing zone's pressure divides
# between length and width: the tets' volume stiffness against the edges',
# and the surface's multiplier to 30 (a taut skin).
RANGES_STIFF = dict(RANGES, surface_multiplier=(1.0, 30.0, True), volume_stiffness=(0.5, 20.0, True),
                    edge_stiffness=(0.3, 3.0, True))

# --ranges produce (2026-12-01, twenty-first session): the paper's text says
# the tip "constantly creates" phi; r1 read as a source of P per unit time
# (`produce phi P`) instead of holding the tip full (`set phi = volume`):
# a fixed flux, shared by however many neighbours the tip has, while P is
# below the tip's outflow (above it the volume cap fills the tip: r1 again).
RANGES_PRODUCE = dict(RANGES, P=(0.01, 0.1, True), Delta=(0.001, 0.006, True))

# --ranges axial (2026-12-01, twenty-second session): the zone's cells divide
# along the limb instead of toward the tip: a second morphogen `base`, held
# full in every cell outside the zone (phi < K volume), falls off into it, and
# r3 divides away from its gradient (`divide away grad(base)`), so daughters
# stack along the limb rather than crowd round one point; the tip grows to
# an absolute radius tip_abs at Dtip (so that its size does not depend on
# where the start put it).
RANGES_AXIAL = {
    "tip_abs": (0.17, 0.35, True),
    "Dtip": (0.002, 0.01, True),
    "Delta": (0.0015, 0.004, True),
    "phi_decay": (0.2, 0.8, True),
    "phi_diffusion": (0.03, 0.1, True),
    "K": (0.015, 0.06, True),
    "base_decay": (0.1, 2.0, True),
    "base_diffusion": (0.02, 0.2, True),
    "surface_multiplier": (1.0, 3.0, True),
    "viscosity": (0.5, 2.0, True),
}
# --ranges axial_behind: the same, and only the zone's cells nearer base's
# sources than Kb grow (`base > Kb * volume`): the zone behind the tip, so
# that its half ahead of the tip does not carry the front past it.
RANGES_AXIAL_BEHIND = dict(RANGES_AXIAL, Kb=(0.02, 0.2, True))
# --ranges axial_inhibit (2026-12-01, twenty-third session): axial, with a
# negative feedback on the zone's size: every growing cell makes an inhibitor
# `inh` (inh_P x its volume per unit time) that raises the zone's threshold
# (`phi > (K + inh_A inh / volume) volume`), so that a zone holding more cells
# narrows to the cells nearest the tip instead of swelling into a bulb.
RANGES_AXIAL_INHIBIT = dict(RANGES_AXIAL, inh_P=(0.01, 0.2, True), inh_A=(0.3, 3.0, True),
                            inh_diffusion=(0.1, 1.0, True), inh_decay=(0.1, 1.0, True))
# --ranges axial_inhibit_behind: both, the zone behind the tip (Kb) and the
# inhibitor.
RANGES_AXIAL_INHIBIT_BEHIND = dict(RANGES_AXIAL_INHIBIT, Kb=(0.02, 0.2, True))
# --ranges axial_inhibit_stiff (2026-12-01, twenty-fourth session): the
# inhibitor design with the sheath stiffer along the limb (axial_stiffness
# 1-10, base's gradient the axis: docs/sds.md, "Axial stiffness"), which
# kept the tip nearer the front at q = 3 (docs/sds_figures.md).
RANGES_AXIAL_INHIBIT_STIFF = dict(RANGES_AXIAL_INHIBIT, axial_stiffness=(1.0, 10.0, True))
# --ranges axial_inhibit_growth (2026-12-01, twenty-fifth session): the
# inhibitor design with the zone's growth oriented along the limb
# (axial_growth 0-1, base's gradient the axis: docs/sds.md, "Oriented
# growth"), drawn uniformly.
RANGES_AXIAL_INHIBIT_GROWTH = dict(RANGES_AXIAL_INHIBIT, axial_growth=(0.0, 1.0, False))
# --ranges NAME: its table
RANGE_SETS = {"default": RANGES, "narrow": RANGES_NARROW, "apical": RANGES_APICAL, "apical_abs": RANGES_APICAL_ABS,
              "stiff": RANGES_STIFF, "produce": RANGES_PRODUCE, "axial": RANGES_AXIAL,
              "axial_behind": RANGES_AXIAL_BEHIND, "axial_inhibit": RANGES_AXIAL_INHIBIT,
              "axial_inhibit_behind": RANGES_AXIAL_INHIBIT_BEHIND, "axial_inhibit_stiff": RANGES_AXIAL_INHIBIT_STIFF,
              "axial_inhibit_growth": RANGES_AXIAL_INHIBIT_GROWTH}


def draw(rng, ranges):
    p = {}
    for k, (lo, hi, lg) in ranges.items():
        u = rng.random()
        p[k] = float(math.exp(math.log(lo) + u * (math.log(hi) - math.log(lo)))) if lg else lo + u * (hi - lo)
    p["uniform_stiffness"] = bool(rng.random() < 0.3)
    return p


def model_text(p, jitter_seed=None):
    s = open(MODEL).read()
    s = re.sub(r"(?m)^const Delta = \S+", "const Delta = %.6g" % p["Delta"], s)
    s = re.sub(r"(?m)^const K = \S+", "const K = %.6g" % p["K"], s)
    if "R" in p:
        s = re.sub(r"(?m)^const R = \S+", "const R = %.6g" % p["R"], s)
    s = re.sub(r"(?m)^morphogen phi .*$", "morphogen phi diffusion=%.6g decay=%.6g" %
               (p["phi_diffusion"], p["phi_decay"]), s)
    s = re.sub(r"(?m)^surface_multiplier = \S+", "surface_multiplier = %.6g" % p["surface_multiplier"], s)
    s = re.sub(r"(?m)^viscosity = \S+", "viscosity = %.6g" % p["viscosity"], s)
    for key in ("volume_stiffness", "edge_stiffness"):
        if key in p:
            s = re.sub(r"(?m)^%s = \S+" % key, "%s = %.6g" % (key, p[key]), s)
    extra = []
    if p.get("uniform_stiffness"):
        extra.append("uniform_stiffness = 1")
    if "axial_stiffness" in p:
        extra.append("axial_stiffness = %.6g" % p["axial_stiffness"])
    if "axial_growth" in p:
        extra.append("axial_growth = %.6g" % p["axial_growth"])
    if jitter_seed is not None:
        extra.append("start_jitter = 0.1")
    if "Dt" in p:
        s = s.replace("\nconst R =", "\nconst Dt = %.6g\nconst R =" % p["Dt"], 1)
        s = s.replace("\nrule r1:", "\nrule r0: tip == 1 -> grow Dt\n"
                      "rule rt: tip == 1 && radius > %s -> divide away grad(phi)\nrule r1:"
                      % ("%.6g" % p["Rt"] if "Rt" in p else "R * birth_radius"), 1)
        s = re.sub(r"(?m)^rule r2: tip == 0 && ", "rule r2: tip == 0 && surface == 1 && ", s)
    if "P" in p:
        s = re.sub(r"(?m)^rule r1: tip == 1 -> set phi = volume", "rule r1: tip == 1 -> produce phi %.6g" % p["P"], s)
    if "base_decay" in p:
        s = re.sub(r"(?m)^(morphogen phi .*)$", r"\1\nmorphogen base diffusion=%.6g decay=%.6g%s" %
                   (p["base_diffusion"], p["base_decay"],
                    " axis=1" if "axial_stiffness" in p or "axial_growth" in p else ""), s)
        s = re.sub(r"(?m)^rule r3: .*$", "rule r3: tip == 0 && radius > R * birth_radius -> divide away grad(base)\n"
                   "rule b1: tip == 0 && phi < K * volume -> set base = volume", s)
        s = s.replace("\nrule r1:", "\nrule r0: tip == 1 && radius < %.6g -> grow %.6g\nrule r1:"
                      % (p["tip_abs"], p["Dtip"]), 1)
        if "Kb" in p:
            s = re.sub(r"(?m)^rule r2: tip == 0 && phi > K \* volume", "rule r2: tip == 0 && phi > K * volume && "
                       "base > %.6g * volume" % p["Kb"], s)
        if "inh_P" in p:
            s = re.sub(r"(?m)^(morphogen phi .*)$", r"\1\nmorphogen inh diffusion=%.6g decay=%.6g" %
                       (p["inh_diffusion"], p["inh_decay"]), s)
            s = re.sub(r"(?m)^rule r2: tip == 0 && phi > K \* volume(.*?) -> grow Delta.*$",
                       r"rule r2: tip == 0 && phi > (K + %.6g * inh / volume) * volume\1 -> grow Delta; "
                       "produce inh %.6g * volume" % (p["inh_A"], p["inh_P"]), s)
    if p.get("tip_R", 1.0) > 1.0:
        s = s.replace("\nrule r1:", "\nrule r0: tip == 1 && radius < %.6g * birth_radius -> grow Delta\nrule r1:"
                      % p["tip_R"], 1)
    return s.replace("\n# --- process model", "\n" + "".join(e + "\n" for e in extra) + "# --- process model", 1)


def score(m):
    if not m:
        return 9.0
    if m.get("distal_over_neck") is None:  # no limb to measure: 2-3 by its length
        return 3.0 - min(1.0, max(0.0, m["length"]))
    return (max(0.0, m["distal_over_neck"] / 1.2 - 1) + max(0.0, m["tip_behind_front"] / m["tip_radius"] - 1)
            + max(0.0, 1 - m["length_over_neck"] / 3))


def run_point(sessile, out, idx, p, t_end, seed):
    d = os.path.join(out, "run%04d" % idx)
    os.makedirs(d, exist_ok=True)
    f = os.path.join(d, "limb_search.sds")
    open(f, "w").write(model_text(p, seed))
    cmd = [sessile, "sds", "run", f, "--t-end", str(t_end), "--frames", "4", "--quiet", "--no-preview",
           "--max-cells", "1500", "--out", os.path.join(d, "run"), "--seed", str(seed or 1)]
    m, status = None, "ok"
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
        status = "ok" if r.returncode == 0 else "exit %d: %s" % (
            r.returncode, (r.stderr.strip().splitlines() or [""])[-1][:160])
        if r.returncode == 0:
            fr = subprocess.run(["/usr/bin/python3", os.path.join(HERE, "figures.py"), "limb",
                                 os.path.join(d, "run")], capture_output=True, text=True, timeout=120)
            lines = fr.stdout.strip().splitlines()
            if fr.returncode == 0 and lines:
                m = json.loads(lines[-1])
                m.pop("profile", None)
            else:
                status = "figures failed"
    except subprocess.TimeoutExpired:
        status = "timeout"
    shutil.rmtree(d, ignore_errors=True)
    return {"index": idx, "point": p, "jitter_seed": seed, "status": status, "metrics": m, "score": score(m)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("sessile")
    ap.add_argument("out")
    ap.add_argument("--runs", type=int, default=40)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--t-end", type=float, default=200)
    ap.add_argument("--from", dest="src")
    ap.add_argument("--jitter-seeds", type=int, default=3)
    ap.add_argument("--realisations", type=int, default=0,
                    help="score each point by the worst of the exact start and K realisations (seeds 1..K)")
    ap.add_argument("--near", help="draw round a point of an earlier results.jsonl (with --index)")
    ap.add_argument("--index", type=int, help="--near's point (its index)")
    ap.add_argument("--spread", type=float, default=0.2, help="--near: each value times exp(N(0, spread))")
    ap.add_argument("--axial", type=float, metavar="Q",
                    help="every point with axial_stiffness Q, base's gradient the axis (the axial ranges; the "
                         "points drawn are those without it, for a paired comparison)")
    ap.add_argument("--growth", type=float, metavar="A",
                    help="every point with axial_growth A, base's gradient the axis (the axial ranges; paired as "
                         "--axial)")
    ap.add_argument("--ranges", choices=list(RANGE_SETS), default="default",
                    help="default: round the shipped model; narrow: K 0.08-0.5, Delta to 0.03, the tip growing; "
                    "apical: the tip grows and divides inward, only the zone's surface grows; apical_abs: "
                    "the tip divides at an absolute radius; stiff: default with the volume and edge stiffness and a "
                    "surface multiplier to 30; produce: default with the tip a source of P per unit time; axial: the zone "
                    "divides along the limb, away from a morphogen held full outside it, the tip grown to an "
                    "absolute radius; axial_behind: axial, only the zone behind the tip "
                    "growing (base > Kb volume); axial_inhibit: axial, the growing cells making an "
                    "inhibitor that raises the zone's threshold; axial_inhibit_behind: both; "
                    "axial_inhibit_stiff: axial_inhibit with the sheath 1-10 x stiffer along base's gradient; "
                    "axial_inhibit_growth: axial_inhibit with the zone's growth 0-1 along base's gradient")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    if a.src:
        rows = [json.loads(l) for l in open(a.src)]
        best = sorted(rows, key=lambda r: r["score"])[:a.runs]
        work = [(r["point"], s) for r in best for s in range(1, a.jitter_seeds + 1)]
    elif a.near:
        rows = [r for r in map(json.loads, open(a.near)) if r["index"] == a.index]
        if not rows:
            ap.error("--near: %s has no point with index %s (give --index)" % (a.near, a.index))
        centre = rows[0]["point"]
        rng = np.random.default_rng(a.seed)
        work = [({k: (float(v * math.exp(a.spread * rng.standard_normal())) if isinstance(v, float) else v)
                  for k, v in centre.items()}, None) for _ in range(a.runs)]
        for w in work:  # the oriented growth's range ends at 1 (all of it along the axis)
            if "axial_growth" in w[0]:
                w[0]["axial_growth"] = min(w[0]["axial_growth"], 1.0)
    else:
        rng = np.random.default_rng(a.seed)
        work = [(draw(rng, RANGE_SETS[a.ranges]), None) for _ in range(a.runs)]
    if a.axial is not None or a.growth is not None or any(
            "axial_stiffness" in w[0] or "axial_growth" in w[0] for w in work):
        if not all("base_decay" in w[0] for w in work):
            ap.error("--axial and --growth need points with the morphogen base (--ranges axial...)")
        if a.axial is not None:
            work = [(dict(w[0], axial_stiffness=a.axial), w[1]) for w in work]
        if a.growth is not None:
            work = [(dict(w[0], axial_growth=a.growth), w[1]) for w in work]
    lock, nxt = threading.Lock(), [0]
    path = os.path.join(a.out, "results.jsonl")
    # a search appending to an earlier one numbers its points after it, so
    # that --near --index names one point
    base = sum(1 for _ in open(path)) if os.path.exists(path) else 0
    res = open(path, "a")

    def worker():
        while True:
            with lock:
                i = nxt[0]
                nxt[0] += 1
            if i >= len(work):
                return
            r = run_point(a.sessile, a.out, base + i, work[i][0], a.t_end, work[i][1])
            if a.realisations and r["score"] < 9:  # the worst of the exact start and K realisations
                rs = [run_point(a.sessile, a.out, base + i, work[i][0], a.t_end, k)
                      for k in range(1, a.realisations + 1)]
                r["realisations"] = [{"seed": x["jitter_seed"], "status": x["status"], "metrics": x["metrics"],
                                      "score": x["score"]} for x in rs]
                r["score_exact"] = r["score"]
                r["score"] = max([r["score"]] + [x["score"] for x in rs])
            with lock:
                res.write(json.dumps(r) + "\n")
                res.flush()
                m = r["metrics"] or {}
                print("%4d score %.3f %s d/n %s lag %s L/n %s" % (
                    r["index"], r["score"], r["status"], m.get("distal_over_neck"), m.get("tip_behind_front"),
                    m.get("length_over_neck")), flush=True)

    th = [threading.Thread(target=worker) for _ in range(a.jobs)]
    for t in th:
        t.start()
    for t in th:
        t.join()


if __name__ == "__main__":
    main()
