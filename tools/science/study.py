#!/usr/bin/python3
"""A rerunnable study of the sponge model: runs a matrix of `sessile grow` runs,
measures their final surfaces, and writes a Markdown report and results.json.

usage: tools/science/study.py --out DIR [--report FILE.md] [--parts grid,box,sweeps,species]
                              [-j N] [--quick] [--sessile PATH] ...

Parts (tools/science/README.md has the details and the time each takes):
  grid     radiate, 20 iterations, box_resolution 1, 2, 3 (3 seeds, each a different
           placement of the sponge on the grid): volume added, height, surface/volume;
           relative differences r1->r2, r2->r3 and the observed order
  box      radiate, 20 iterations: far_field=height on the default box (32x32x24 cells
           of 1.2 cm) against 48x48x36 cells at the same far_field_height, and the same
           with far_field=walls: volume added, height, drift of the centroid in x/y
  sweeps   the supplement's sweeps at 50 iterations (radiate, seed 1): growth_rate,
           kinetic_order, growth_constant, t_give; normal_offset_radius on crella
  species  crella against radiate with the same position jitter, seeds 1..6, 50
           iterations, paired by seed: height, volume, surface/volume, base area, tips
           and their spacing; paired t-test and exact Wilcoxon signed-rank test

Each run has its own folder under DIR/runs, named after its preset, seed, iterations
and the parameters that differ from the preset's defaults (so parts share identical
runs).  A folder whose manifest says `completed` with the same parameters, made by
the same sessile binary, is not run again: an interrupted study resumes where it
stopped.  Needs Debian's python3-numpy and python3-scipy (run with /usr/bin/python3);
python3-matplotlib, when installed, adds plots of the metrics.
"""
import argparse
import concurrent.futures
import datetime
import hashlib
import importlib.util
import json
import math
import os
import signal
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, HERE)

for _mod in ("numpy", "scipy"):
    if importlib.util.find_spec(_mod) is None:
        sys.exit(f"study: {_mod} is missing: apt-get install python3-numpy python3-scipy "
                 "(and run with /usr/bin/python3)")
import numpy as np  # noqa: E402

import metrics  # noqa: E402
import pipelines  # noqa: E402

PARTS = ("grid", "box", "sweeps", "species", "current", "literal", "height")
# The default: the first four.  current, literal and height are asked for by
# name (--parts): current solves the flow every iteration, hours here.
DEFAULT_PARTS = PARTS[:4]
# Every run: no snapshots but the last, no VTU fields, no slices, no flow
# solve (the flow does not feed the growth while diffusion_limited; it would
# only fill the snapshots' velocity channels).
RUN_FLAGS = ["--every", "0", "--no-fields", "--slices", ""]
COMMON_SETS = {"fluid_at_snapshots": "false"}

SWEEPS = [  # (parameter, symbol, values, preset)
    ("growth_rate", "Gr", ["2.5", "5", "10"], "radiate"),
    ("kinetic_order", "n", ["1", "1.4", "2"], "radiate"),
    ("growth_constant", "K", ["0.5", "1", "2"], "radiate"),
    ("t_give", "T_give", ["0", "0.05", "0.1"], "radiate"),
    ("normal_offset_radius", "R", ["0.02", "0.5", "1.0"], "crella"),
]


_log_lock = threading.Lock()


def log(msg):
    with _log_lock:
        sys.stdout.write(f"study: {msg}\n")
        sys.stdout.flush()


def die(msg, code=1):
    print(f"study: error: {msg}", file=sys.stderr, flush=True)
    sys.exit(code)


def parse_seeds(text):
    """'1,2,5' or '1-6' or '1-3,7'."""
    out = []
    for part in text.split(","):
        part = part.strip()
        if not part:
            continue
        if "-" in part:
            a, b = part.split("-", 1)
            out.extend(range(int(a), int(b) + 1))
        else:
            out.append(int(part))
    if not out:
        raise argparse.ArgumentTypeError(f"no seeds in '{text}'")
    return out


def fnum(x, digits=3):
    """A number for a table: NaN as '–', small and large in a readable form."""
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "–"
    if isinstance(x, (int, np.integer)) and not isinstance(x, bool):
        return str(int(x))
    ax = abs(x)
    if ax != 0 and (ax < 1e-3 or ax >= 1e5):
        return f"{x:.{digits - 1}e}"
    return f"{x:.{digits}g}" if ax < 1 else f"{x:.{max(digits, len(str(int(ax))))}g}"


def fpct(x):
    if x is None or not math.isfinite(x):
        return "–"
    return f"{100 * x:+.2f} %"


def fp(p):
    if p is None or not math.isfinite(p):
        return "–"
    return f"{p:.3g}" if p >= 1e-4 else f"{p:.1e}"


def fsummary(st):
    """mean ± sd (min–max) of stats(), or '–' when there is no value."""
    if st["n"] == 0 or not math.isfinite(st["mean"]):
        return "–"
    sd = f" ± {fnum(st['std'], 2)}" if math.isfinite(st["std"]) else ""
    return f"{fnum(st['mean'], 4)}{sd} ({fnum(st['min'], 3)}–{fnum(st['max'], 3)})"


def jsonable(x):
    """NaN and infinities as null; numpy scalars as Python numbers."""
    if isinstance(x, dict):
        return {str(k): jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [jsonable(v) for v in x]
    if isinstance(x, (np.integer,)):
        return int(x)
    if isinstance(x, (float, np.floating)):
        x = float(x)
        return x if math.isfinite(x) else None
    if isinstance(x, np.bool_):
        return bool(x)
    return x


# ---------------------------------------------------------------------------
# sessile: its parameter table, and the runs
# ---------------------------------------------------------------------------

class Sessile:
    def __init__(self, path):
        self.path = path
        with open(path, "rb") as f:
            self.sha256 = hashlib.sha256(f.read()).hexdigest()
        self._tables = {}
        self._lock = threading.Lock()

    def table(self, preset, sets):
        """The parameter table a run with these settings would use
        (`sessile grow --print-config`): {name: printed value}."""
        key = (preset, tuple(sorted(sets.items())))
        with self._lock:
            if key in self._tables:
                return self._tables[key]
        cmd = [self.path, "grow", "--preset", preset]
        for k, v in sorted(sets.items()):
            cmd += ["--set", f"{k}={v}"]
        cmd.append("--print-config")
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        if p.returncode != 0:
            die(f"sessile refused the settings {preset} {sets}: {p.stderr.strip()}", 2)
        table = {}
        for line in p.stdout.splitlines()[1:]:
            w = line.split()
            if len(w) >= 2:
                table[w[0]] = w[1]
        with self._lock:
            self._tables[key] = table
        return table


def same_value(printed, value):
    """A value of --print-config's table against the manifest's JSON value."""
    if isinstance(value, bool):
        return printed == ("true" if value else "false")
    if isinstance(value, str):
        return printed == value
    try:
        a = float(printed)
    except ValueError:
        return False
    return abs(a - float(value)) <= 1e-5 * max(abs(a), abs(float(value))) + 1e-12


class Run:
    """One `sessile grow` run; its folder name is its identity."""

    def __init__(self, sessile, preset, seed, iterations, sets):
        self.preset, self.seed, self.iterations = preset, int(seed), int(iterations)
        self.sets = {k: str(v) for k, v in sets.items()}
        allsets = dict(COMMON_SETS, **self.sets)
        self.table = sessile.table(preset, allsets)
        base = sessile.table(preset, dict(COMMON_SETS))
        diff = sorted(k for k in self.table if self.table[k] != base.get(k))
        self.name = f"{preset}-s{self.seed}-i{self.iterations}" + "".join(f"-{k}={self.table[k]}" for k in diff)
        self.differs = {k: self.table[k] for k in diff}
        self.allsets = allsets
        self.seconds = None
        self.skipped = False
        self.metrics = None
        self.info = None

    def folder(self, out):
        return os.path.join(out, "runs", self.name)

    def command(self, sessile, out):
        cmd = [sessile.path, "grow", "--preset", self.preset, "--seed", str(self.seed),
               "--iterations", str(self.iterations)] + RUN_FLAGS
        for k, v in sorted(self.allsets.items()):
            cmd += ["--set", f"{k}={v}"]
        return cmd + ["--out", self.folder(out), "--force", "--quiet"]

    def done(self, sessile, out, any_binary=False):
        """True when the folder holds this run, completed, by this binary."""
        d = self.folder(out)
        try:
            with open(os.path.join(d, "manifest.json")) as f:
                m = json.load(f)
            with open(os.path.join(out, "runs", self.name + ".study.json")) as f:
                side = json.load(f)
        except (OSError, ValueError):
            return False
        cfg = m.get("config", {})
        if m.get("state") != "completed" or m.get("generator") != "grow":
            return False
        # The preset only sets parameters, so the parameters (all of them,
        # below) decide; the manifest's preset name is not compared.
        if str(cfg.get("seed")) != str(self.seed):
            return False
        if cfg.get("iterations") != self.iterations or (m.get("totals") or {}).get("iterations_done") != self.iterations:
            return False
        params = cfg.get("parameters", {})
        missing = set(self.table) - set(params)
        if any_binary:
            # A parameter a newer binary added, left at its default, is the
            # older binary's behaviour (new options default to it).
            missing = {k for k in missing if k in self.differs}
        if missing or set(params) - set(self.table) or not all(same_value(self.table[k], params[k]) for k in params):
            return False
        if not any_binary and side.get("sessile_sha256") != sessile.sha256:
            return False
        return os.path.isfile(os.path.join(d, "sponge", "final.ply"))


class RunFailed(Exception):
    pass


def execute(runs, sessile, out, jobs, any_binary, counter):
    """Runs those not yet done, `jobs` at a time; raises RunFailed naming the
    folder of the first failure (the runs already started are finished)."""
    todo = []
    for r in runs:
        if r.done(sessile, out, any_binary):
            r.skipped = True
            side = json.load(open(os.path.join(out, "runs", r.name + ".study.json")))
            r.seconds = side.get("seconds")
            counter["done"] += 1
            log(f"[{counter['done']}/{counter['total']}] {r.name}: already done, kept")
        else:
            todo.append(r)
    failed = []
    stop = threading.Event()
    live = set()
    lock = threading.Lock()

    def one(r):
        if stop.is_set():
            return
        os.makedirs(os.path.join(out, "runs"), exist_ok=True)
        d = r.folder(out)
        if os.path.isdir(d) and not os.path.exists(os.path.join(d, "manifest.json")):
            # A folder without a manifest: sessile refuses it even with --force.
            # Only an empty one is ours to reuse.
            if os.listdir(d):
                failed.append((r, f"{os.path.relpath(d, out)} is not empty and holds no manifest; move it away"))
                stop.set()
                return
        logf = os.path.join(out, "runs", r.name + ".log")
        t0 = time.monotonic()
        log(f"start {r.name}")
        with open(logf, "w") as lf:
            p = subprocess.Popen(r.command(sessile, out), stdout=lf, stderr=subprocess.STDOUT,
                                 stdin=subprocess.DEVNULL)
            with lock:
                live.add(p)
            p.wait()
            with lock:
                live.discard(p)
        r.seconds = time.monotonic() - t0
        state = None
        try:
            state = json.load(open(os.path.join(d, "manifest.json"))).get("state")
        except (OSError, ValueError):
            pass
        if p.returncode != 0 or state != "completed":
            tail = ""
            try:
                tail = "".join(open(logf).readlines()[-5:]).strip()
            except OSError:
                pass
            failed.append((r, f"runs/{r.name} failed (exit {p.returncode}, "
                              f"{'manifest state ' + state if state else 'no manifest'}); "
                              f"its output: runs/{r.name}.log" + (f"\n{tail}" if tail else "")))
            stop.set()
            return
        with open(os.path.join(out, "runs", r.name + ".study.json"), "w") as f:
            json.dump({"sessile_sha256": sessile.sha256, "seconds": r.seconds,
                       "command": r.command(sessile, out)[1:]}, f, indent=1)
        with lock:
            counter["done"] += 1
            k = counter["done"]
        log(f"[{k}/{counter['total']}] {r.name}: done in {r.seconds:.1f} s")

    pool = concurrent.futures.ThreadPoolExecutor(max_workers=max(1, jobs))
    futures = [pool.submit(one, r) for r in todo]
    try:
        for f in futures:
            f.result()
    except BaseException:
        # Interrupted: start nothing more; the runs in flight stop after their
        # current iteration (SIGTERM: sessile writes a checkpoint and marks
        # its manifest interrupted); the next study redoes them.
        stop.set()
        for f in futures:
            f.cancel()
        with lock:
            for p in live:
                if p.poll() is None:
                    p.terminate()
        pool.shutdown(wait=True)
        raise
    pool.shutdown(wait=True)
    if failed:
        raise RunFailed("\n".join(msg for _, msg in failed))


# ---------------------------------------------------------------------------
# Metrics of one run
# ---------------------------------------------------------------------------

def measure(run, out):
    d = run.folder(out)
    m = json.load(open(os.path.join(d, "manifest.json")))
    recs = [json.loads(line) for line in open(os.path.join(d, "records.jsonl")) if line.strip()]
    V, F = metrics.read_ply(os.path.join(d, "sponge", "final.ply"))
    s = metrics.surface_metrics(V, F)
    # The initial sponge as the manifest describes it (NaN where a newer
    # manifest lacks a member: the metrics that need it are then undefined).
    nan = float("nan")
    init = m.get("initial_sponge") or {}
    v0 = init.get("volume_cm3", nan)
    h0 = (init.get("bbox_max_cm") or [nan, nan, nan])[2]
    s["initial_volume_cm3"] = v0
    s["initial_height_cm"] = h0
    s["volume_added_cm3"] = s["volume_cm3"] - v0
    s["height_gain_cm"] = s["height_cm"] - h0
    c0 = init.get("center_cm") or [nan, nan, nan]
    s["start_centre_cm"] = c0
    s["drift_x_cm"] = s["centroid_cm"][0] - c0[0]
    s["drift_y_cm"] = s["centroid_cm"][1] - c0[1]
    s["drift_cm"] = math.hypot(s["drift_x_cm"], s["drift_y_cm"])
    # The PLY holds float32 positions: its volume must agree with the run's own
    # (double precision) record of its last iteration.
    last = (recs[-1].get("surface") or {}) if recs else {}
    rv = last.get("volume_cm3")
    s["record_volume_cm3"] = rv
    s["volume_check_rel"] = abs(s["volume_cm3"] - rv) / abs(rv) if rv else None
    s["volume_series_cm3"] = [r["surface"]["volume_cm3"] for r in recs if "surface" in r]
    s["solves_converged"] = all(r.get("nutrient_solve", {}).get("status") == "converged" for r in recs)
    s["box_spacing_cm"] = m.get("box", {}).get("spacing_cm")
    s["box_max_cm"] = m.get("box", {}).get("max_cm")
    run.metrics = s
    run.info = {"device": (m.get("device") or {}).get("name"), "version": m.get("version"),
                "wall_seconds": (m.get("totals") or {}).get("wall_seconds_this_start")}
    return s


def stats(values):
    a = np.array([v for v in values if v is not None and math.isfinite(v)], dtype=float)
    if len(a) == 0:
        return {"n": 0, "mean": float("nan"), "std": float("nan"), "min": float("nan"), "max": float("nan")}
    return {"n": int(len(a)), "mean": float(a.mean()), "std": float(a.std(ddof=1)) if len(a) > 1 else float("nan"),
            "min": float(a.min()), "max": float(a.max())}


# ---------------------------------------------------------------------------
# The parts: their runs, and their analysis
# ---------------------------------------------------------------------------

class Plan:
    """Iterations, seeds and box settings of each part, full or --quick."""

    def __init__(self, a):
        q = a.quick
        it = a.iterations
        self.quick = q
        self.grid_iterations = it or (3 if q else 20)
        self.box_iterations = it or (3 if q else 20)
        self.sweep_iterations = it or (3 if q else 50)
        self.species_iterations = it or (3 if q else 50)
        self.grid_seeds = a.grid_seeds or ([1, 2] if q else [1, 2, 3])
        self.box_seeds = a.box_seeds or [1]
        self.species_seeds = a.species_seeds or ([1, 2] if q else [1, 2, 3, 4, 5, 6])
        self.sweep_seed = a.sweep_seed
        # Quick: every part at box_resolution 1; the grid study on a coarser base
        # grid (cells of 3.2 cm, the same 38.4 x 38.4 x 28.8 box) so that its
        # three levels stay cheap.
        self.extra = {"box_resolution": "1"} if q else {}
        if q:
            self.grid_base = {"box_base_cell": "3.2", "box_cells_x": "12", "box_cells_y": "12", "box_cells_z": "9"}
            self.grid_cell = 3.2
        else:
            self.grid_base = {}
            self.grid_cell = 1.2
        self.grid_jitter = a.grid_jitter if a.grid_jitter is not None else self.grid_cell
        self.grid_levels = [1, 2, 3]
        self.species_jitter = "4"
        # current, literal: crella against radiate under other pipelines
        # (pipelines.py); the flow solve of every iteration makes them costly,
        # so they run at box_resolution 1 unless told otherwise.
        self.compare_iterations = it or (3 if q else 20)
        self.compare_seeds = a.compare_seeds or ([1, 2] if q else [1, 2, 3, 4, 5, 6])
        self.compare_resolution = "1" if q else a.compare_resolution
        self.compare_extra = {"box_resolution": self.compare_resolution}
        self.literal_current = a.literal_current
        self.current_seeds = a.current_seeds or self.compare_seeds
        self.compare_modes = [m.strip() for m in a.compare_modes.split(",") if m.strip()]
        self.height_iterations = it or (3 if q else 20)
        self.height_resolution = "1" if q else a.height_resolution
        self.height_extra = {"box_resolution": self.height_resolution}

    def describe(self):
        return {k: v for k, v in self.__dict__.items()}


def plan_grid(P, mk):
    runs = {}
    for s in P.grid_seeds:
        for r in P.grid_levels:
            sets = dict(P.grid_base, box_resolution=str(r), position_jitter=str(P.grid_jitter))
            runs[(s, r)] = mk("radiate", s, P.grid_iterations, sets)
    return runs


BOX_CASES = [  # (label, far_field, cells)
    ("height, 32x32x24 (38.4 cm)", "height", (32, 32, 24)),
    ("height, 48x48x36 (57.6 cm)", "height", (48, 48, 36)),
    ("walls, 32x32x24 (38.4 cm)", "walls", (32, 32, 24)),
    ("walls, 48x48x36 (57.6 cm)", "walls", (48, 48, 36)),
]


def plan_box(P, mk):
    runs = {}
    for s in P.box_seeds:
        for label, ff, (cx, cy, cz) in BOX_CASES:
            sets = dict(P.extra, far_field=ff, box_cells_x=str(cx), box_cells_y=str(cy), box_cells_z=str(cz))
            if ff == "height":
                sets["far_field_height"] = "28.8"
            runs[(s, label)] = mk("radiate", s, P.box_iterations, sets)
    return runs


def plan_sweeps(P, mk):
    runs = {}
    for name, _, values, preset in SWEEPS:
        for v in values:
            runs[(name, v)] = mk(preset, P.sweep_seed, P.sweep_iterations, dict(P.extra, **{name: v}))
    return runs


def plan_species(P, mk):
    runs = {}
    for s in P.species_seeds:
        runs[("crella", s)] = mk("crella", s, P.species_iterations, dict(P.extra))
        runs[("radiate", s)] = mk("radiate", s, P.species_iterations,
                                  dict(P.extra, position_jitter=P.species_jitter))
    return runs


GRID_METRICS = [("volume_added_cm3", "volume added (cm³)"), ("height_cm", "height (cm)"),
                ("surface_to_volume_per_cm", "surface/volume (1/cm)")]


def convergence(f1, f2, f3):
    """Relative differences of a metric on three levels (h, h/2, h/4), the
    observed order and, where the differences shrink monotonically, the
    Richardson estimate and Roache's grid convergence index of the finest."""
    d12 = (f2 - f1) / abs(f2) if f2 else float("nan")
    d23 = (f3 - f2) / abs(f3) if f3 else float("nan")
    e12, e23 = f2 - f1, f3 - f2
    out = {"values": [f1, f2, f3], "rel_1_2": d12, "rel_2_3": d23, "order": float("nan"),
           "monotone": bool(e12 * e23 > 0), "shrinking": bool(abs(e23) < abs(e12)),
           "richardson": float("nan"), "gci_fine": float("nan")}
    if e23 != 0 and e12 != 0:
        out["order"] = math.log(abs(e12 / e23)) / math.log(2.0)
    if out["monotone"] and out["shrinking"] and out["order"] > 0:
        p = out["order"]
        out["richardson"] = f3 + e23 / (2 ** p - 1)
        out["gci_fine"] = 1.25 * abs(d23) / (2 ** p - 1)
    return out


def analyse_grid(P, runs):
    res = {"levels": P.grid_levels, "seeds": P.grid_seeds, "spacing_cm": [], "per_seed": {}, "mean": {}, "spread": {}}
    res["spacing_cm"] = [runs[(P.grid_seeds[0], r)].metrics["box_spacing_cm"] for r in P.grid_levels]
    for key, _ in GRID_METRICS:
        per = {}
        for s in P.grid_seeds:
            per[s] = convergence(*[runs[(s, r)].metrics[key] for r in P.grid_levels])
        means = [float(np.mean([runs[(s, r)].metrics[key] for s in P.grid_seeds])) for r in P.grid_levels]
        res["per_seed"][key] = per
        res["mean"][key] = convergence(*means)
        res["spread"][key] = [stats([runs[(s, r)].metrics[key] for s in P.grid_seeds]) for r in P.grid_levels]
    return res


def analyse_box(P, runs):
    res = {"cases": [c[0] for c in BOX_CASES], "seeds": P.box_seeds, "per_case": {}, "size_effect": {}}
    keys = ["volume_added_cm3", "height_cm", "surface_to_volume_per_cm", "drift_x_cm", "drift_y_cm", "drift_cm"]
    for label, _, _ in BOX_CASES:
        res["per_case"][label] = {k: stats([runs[(s, label)].metrics[k] for s in P.box_seeds]) for k in keys}
    for ff in ("height", "walls"):
        small = [c[0] for c in BOX_CASES if c[1] == ff][0]
        large = [c[0] for c in BOX_CASES if c[1] == ff][1]
        eff = {}
        for k in ("volume_added_cm3", "height_cm", "surface_to_volume_per_cm"):
            a = res["per_case"][small][k]["mean"]
            b = res["per_case"][large][k]["mean"]
            eff[k] = (b - a) / abs(a) if a else float("nan")
        res["size_effect"][ff] = eff
    return res


SWEEP_METRICS = [("volume_added_cm3", "volume added (cm³)"), ("height_cm", "height (cm)"),
                 ("surface_to_volume_per_cm", "S/V (1/cm)"), ("base_area_cm2", "base area (cm²)"),
                 ("tips", "tips"), ("tip_spacing_cm", "tip spacing (cm)"), ("vertices", "vertices")]


def analyse_sweeps(P, runs):
    res = {}
    for name, sym, values, preset in SWEEPS:
        rows = []
        for v in values:
            m = runs[(name, v)].metrics
            rows.append({"value": float(v), "run": runs[(name, v)].name, **{k: m[k] for k, _ in SWEEP_METRICS}})
        trend = {}
        for k, _ in SWEEP_METRICS:
            ys = [r[k] for r in rows]
            if any(y is None or not math.isfinite(y) for y in ys):
                trend[k] = {"direction": "undefined", "change_low_high": float("nan")}
                continue
            dif = np.diff(ys)
            direction = ("increasing" if np.all(dif > 0) else "decreasing" if np.all(dif < 0)
                         else "constant" if np.all(dif == 0) else "not monotone")
            trend[k] = {"direction": direction, "change_low_high": (ys[-1] - ys[0]) / abs(ys[0]) if ys[0] else float("nan")}
        res[name] = {"symbol": sym, "preset": preset, "rows": rows, "trend": trend}
    return res


SPECIES_METRICS = [("height_cm", "height (cm)"), ("volume_cm3", "volume (cm³)"),
                   ("surface_to_volume_per_cm", "surface/volume (1/cm)"), ("base_area_cm2", "base area (cm²)"),
                   ("base_hull_area_cm2", "base hull area (cm²)"), ("tips", "extrusions (tips)"),
                   ("tip_spacing_cm", "tip spacing (cm)")]


def paired_tests(a, b):
    """a, b: paired samples (crella, radiate).  Mean difference a - b, the paired
    t-test and the exact two-sided Wilcoxon signed-rank test (scipy)."""
    import warnings
    from scipy import stats as st
    pairs = [(x, y) for x, y in zip(a, b) if x is not None and y is not None and math.isfinite(x) and math.isfinite(y)]
    n = len(pairs)
    out = {"n": n, "mean_diff": float("nan"), "sd_diff": float("nan"), "t_p": float("nan"),
           "wilcoxon_p": float("nan"), "wilcoxon_method": None, "note": ""}
    if n == 0:
        out["note"] = "no complete pairs"
        return out
    x = np.array([p[0] for p in pairs], dtype=float)
    y = np.array([p[1] for p in pairs], dtype=float)
    d = x - y
    out["mean_diff"] = float(d.mean())
    out["sd_diff"] = float(d.std(ddof=1)) if n > 1 else float("nan")
    if n < 2:
        out["note"] = "fewer than 2 pairs"
        return out
    if np.all(d == 0):
        out.update(t_p=1.0, wilcoxon_p=1.0, wilcoxon_method="all differences 0", note="identical in every pair")
        return out
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if np.all(d == d[0]):
            out["t_p"] = 0.0  # a constant non-zero difference: t is infinite
            out["note"] = "the same difference in every pair"
        else:
            out["t_p"] = float(st.ttest_rel(x, y).pvalue)
        nz = d[d != 0]
        ties = len(np.unique(np.abs(nz))) < len(nz)
        if len(nz) < len(d) or ties:
            # scipy's exact distribution assumes no zeros and no ties; with
            # them the normal approximation is the honest choice.
            r = st.wilcoxon(x, y, zero_method="wilcox", method="approx")
            out["wilcoxon_method"] = "normal approximation (zero or tied differences)"
        else:
            r = st.wilcoxon(x, y, method="exact")
            out["wilcoxon_method"] = "exact"
        out["wilcoxon_p"] = float(r.pvalue)
    return out


def analyse_species(P, runs):
    res = {"seeds": P.species_seeds, "per_species": {}, "pairs": {},
           "wilcoxon_min_p": 2.0 / 2 ** len(P.species_seeds)}
    for sp in ("crella", "radiate"):
        res["per_species"][sp] = {k: stats([runs[(sp, s)].metrics[k] for s in P.species_seeds])
                                  for k, _ in SPECIES_METRICS}
        res["per_species"][sp]["values"] = {k: [runs[(sp, s)].metrics[k] for s in P.species_seeds]
                                            for k, _ in SPECIES_METRICS}
    for k, _ in SPECIES_METRICS:
        res["pairs"][k] = paired_tests([runs[("crella", s)].metrics[k] for s in P.species_seeds],
                                       [runs[("radiate", s)].metrics[k] for s in P.species_seeds])
    return res


# ---------------------------------------------------------------------------
# Pictures
# ---------------------------------------------------------------------------

def render_png(sessile, args):
    """`sessile render ARGS --quiet`; raises RuntimeError with its one-line message."""
    p = subprocess.run([sessile.path, "render"] + args + ["--quiet"], stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        raise RuntimeError(p.stderr.strip() or f"sessile render exited {p.returncode}")


def pictures(P, runs, out, picdir, sessile):
    """Every species' final surface per seed and a sheet of them, drawn by
    `sessile render` (docs/render.md): 640 x 480, oblique, the grid's spacing
    written in the corner; the sheet of 320 x 240 tiles (crella above radiate,
    seeds left to right) by `sessile render --sheet`, captioned with the height.
    The camera is fitted to each surface, so the pictures are not at one scale:
    the grid label and the caption give it."""
    os.makedirs(picdir, exist_ok=True)
    files, tiles = {}, []
    with tempfile.TemporaryDirectory(prefix="study-tiles-") as tmp:
        for sp in ("crella", "radiate"):
            for s in P.species_seeds:
                r = runs[(sp, s)]
                ply = os.path.join(r.folder(out), "sponge", "final.ply")
                name = f"{sp}-seed{s}.png"
                render_png(sessile, [ply, "-o", os.path.join(picdir, name), "--size", "640x480"])
                files[f"{sp}-{s}"] = name
                tile = os.path.join(tmp, name)
                render_png(sessile, [ply, "-o", tile, "--size", "320x240"])
                tiles += [tile, "--caption", f"{sp} {s}: {r.metrics['height_cm']:.1f} cm tall"]
        render_png(sessile, ["--sheet", str(len(P.species_seeds)), "-o", os.path.join(picdir, "species.png")] + tiles)
    files["sheet"] = "species.png"
    return files


def plots(results, runs_by_part, out, picdir):
    """Plots of the metrics with matplotlib, when it is installed."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except Exception:
        return {}
    os.makedirs(picdir, exist_ok=True)
    files = {}
    if "grid" in results:
        g = results["grid"]
        fig, axs = plt.subplots(1, len(GRID_METRICS), figsize=(4 * len(GRID_METRICS), 3.2))
        for ax, (k, label) in zip(axs, GRID_METRICS):
            for s in g["seeds"]:
                ax.plot(g["spacing_cm"], g["per_seed"][k][s]["values"], "o-", alpha=0.6, label=f"seed {s}")
            ax.plot(g["spacing_cm"], g["mean"][k]["values"], "k*-", label="mean")
            ax.set_xlabel("node spacing (cm)")
            ax.set_title(label)
            ax.invert_xaxis()
        axs[0].legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(picdir, "grid.png"), dpi=90)
        plt.close(fig)
        files["grid"] = "grid.png"
    if "sweeps" in results:
        sw = results["sweeps"]
        keys = [("volume_added_cm3", "volume added (cm³)"), ("height_cm", "height (cm)"), ("tips", "tips")]
        fig, axs = plt.subplots(len(keys), len(sw), figsize=(3 * len(sw), 2.6 * len(keys)), squeeze=False)
        for j, (name, d) in enumerate(sw.items()):
            xs = [r["value"] for r in d["rows"]]
            for i, (k, label) in enumerate(keys):
                axs[i][j].plot(xs, [r[k] if r[k] is not None else np.nan for r in d["rows"]], "o-")
                axs[i][j].set_xlabel(f"{name} ({d['symbol']})", fontsize=8)
                if j == 0:
                    axs[i][j].set_ylabel(label, fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(picdir, "sweeps.png"), dpi=90)
        plt.close(fig)
        files["sweeps"] = "sweeps.png"
    series = [(part, r) for part, rs in runs_by_part.items() for r in rs.values()]
    if series:
        fig, ax = plt.subplots(figsize=(6, 4))
        seen = set()
        for part, r in series:
            if r.name in seen:
                continue
            seen.add(r.name)
            v = r.metrics["volume_series_cm3"]
            ax.plot(range(1, len(v) + 1), v, lw=0.8, alpha=0.7)
        ax.set_xlabel("iteration")
        ax.set_ylabel("volume (cm³)")
        ax.set_title("volume of every run")
        fig.tight_layout()
        fig.savefig(os.path.join(picdir, "volumes.png"), dpi=90)
        plt.close(fig)
        files["volumes"] = "volumes.png"
    return files


# ---------------------------------------------------------------------------
# The report
# ---------------------------------------------------------------------------

def table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(out)


def report_grid(P, g, runs):
    L = ["## Grid convergence (`grid`)", ""]
    L.append(f"Radiate preset, {P.grid_iterations} iterations, box_resolution {', '.join(map(str, P.grid_levels))} "
             f"(node spacing {', '.join(fnum(h) for h in g['spacing_cm'])} cm), seeds {', '.join(map(str, P.grid_seeds))}. "
             "The radiate preset draws no random numbers, so each seed moves the sponge by a random x/y "
             f"shift of up to ±{fnum(float(P.grid_jitter))} cm (`position_jitter`, one base cell): the seeds are "
             "different placements of the sponge on the grid, and their spread is the grid-placement noise.")
    if P.quick:
        L.append("")
        L.append("*Quick mode: a coarser base grid (cells of 3.2 cm), so these levels are not those of the full study.*")
    L.append("")
    rows = []
    for k, label in GRID_METRICS:
        c = g["mean"][k]
        sp = g["spread"][k]
        rows.append([label] + [f"{fnum(c['values'][i], 4)} ± {fnum(sp[i]['std'], 2)}" for i in range(3)]
                    + [fpct(c["rel_1_2"]), fpct(c["rel_2_3"]), fnum(c["order"], 3),
                       fnum(c["richardson"], 4), fpct(c["gci_fine"]) if math.isfinite(c["gci_fine"]) else "–"])
    L.append(table(["metric (mean ± sd over seeds)", "r = 1", "r = 2", "r = 3", "r1→r2", "r2→r3",
                    "observed order", "Richardson", "GCI (r = 3)"], rows))
    L.append("")
    L.append("Relative differences are (f(r+1) − f(r)) / |f(r+1)|; the observed order is "
             "log2(|f2 − f1| / |f3 − f2|); the Richardson estimate and Roache's grid convergence index "
             "(safety factor 1.25) are given only where the differences shrink without changing sign.")
    L.append("")
    rows = []
    for k, label in GRID_METRICS:
        for s in P.grid_seeds:
            c = g["per_seed"][k][s]
            rows.append([label, s] + [fnum(v, 4) for v in c["values"]] + [fpct(c["rel_1_2"]), fpct(c["rel_2_3"]),
                                                                           fnum(c["order"], 3)])
    L.append("<details><summary>per seed</summary>\n")
    L.append(table(["metric", "seed", "r = 1", "r = 2", "r = 3", "r1→r2", "r2→r3", "order"], rows))
    L.append("\n</details>")
    L.append("")
    L.append("**What holds, what does not:**")
    L.append("")
    for k, label in GRID_METRICS:
        c = g["mean"][k]
        sd3 = g["spread"][k][2]["std"]
        f1, f2, f3 = c["values"]
        e23 = abs(f3 - f2)
        same = lambda u, v: abs(u - v) <= 1e-9 * max(abs(u), abs(v))  # noqa: E731
        if same(f1, f2) and same(f2, f3):
            s = f"- {label}: the same at every level ({fnum(f3, 4)})."
            if k == "height_cm":
                r = runs[(P.grid_seeds[0], P.grid_levels[-1])]
                cap = r.metrics["initial_height_cm"] + float(r.table["max_growth"]) * r.iterations
                if abs(f3 - cap) < 1e-3:
                    s += (" That is the growth cap (initial height + max_growth × iterations): the top grew "
                          "by max_growth every iteration at every level, so this says nothing about convergence.")
        elif same(f2, f3):
            s = f"- {label}: unchanged from r2 to r3 after a change of {fpct(c['rel_1_2'])} from r1 to r2."
        elif c["shrinking"] and c["monotone"]:
            s = (f"- {label}: the change shrinks from {fpct(c['rel_1_2'])} (r1→r2) to {fpct(c['rel_2_3'])} (r2→r3), "
                 f"same sign: converging, observed order {fnum(c['order'], 2)}.")
        elif c["shrinking"]:
            s = (f"- {label}: the change shrinks from {fpct(c['rel_1_2'])} to {fpct(c['rel_2_3'])} but changes sign "
                 f"(oscillating); the observed order {fnum(c['order'], 2)} is only indicative.")
        else:
            s = (f"- {label}: **not converged** — the change from r2 to r3 ({fpct(c['rel_2_3'])}) is not smaller "
                 f"than from r1 to r2 ({fpct(c['rel_1_2'])}).")
        if math.isfinite(sd3) and sd3 > 0:
            s += (f" The r2→r3 difference is {'below' if e23 < sd3 else 'above'} the spread between seeds at r = 3 "
                  f"(sd {fnum(sd3, 3)}).")
        L.append(s)
    return L


def report_box(P, b):
    L = ["## Box size and far field (`box`)", ""]
    L.append(f"Radiate preset, {P.box_iterations} iterations, seed{'s' if len(P.box_seeds) > 1 else ''} "
             f"{', '.join(map(str, P.box_seeds))}, the sponge at the box centre. `far_field=height`: c = 1 at "
             "far_field_height = 28.8 cm, zero flux through the side walls; `far_field=walls`: c = 1 on every wall "
             "but the substratum (the paper's box). Cells of 1.2 cm at the base level"
             + (", box_resolution 1 (quick mode)." if P.quick else "."))
    L.append("")
    rows = []
    for label in b["cases"]:
        c = b["per_case"][label]
        rows.append([label, fnum(c["volume_added_cm3"]["mean"], 4), fnum(c["height_cm"]["mean"], 4),
                     fnum(c["surface_to_volume_per_cm"]["mean"], 4), fnum(c["drift_x_cm"]["mean"], 3),
                     fnum(c["drift_y_cm"]["mean"], 3), fnum(c["drift_cm"]["mean"], 3)])
    L.append(table(["far field, box", "volume added (cm³)", "height (cm)", "S/V (1/cm)",
                    "centroid drift x (cm)", "drift y (cm)", "|drift| (cm)"], rows))
    L.append("")
    L.append("Drift: the final solid's centroid minus the initial sponge's centre, in x and y.")
    L.append("")
    L.append("**What holds, what does not:**")
    L.append("")
    eh, ew = b["size_effect"]["height"], b["size_effect"]["walls"]
    L.append(f"- Enlarging the box from 38.4 to 57.6 cm changes the volume added by {fpct(eh['volume_added_cm3'])} "
             f"and the height by {fpct(eh['height_cm'])} with `far_field=height`, against "
             f"{fpct(ew['volume_added_cm3'])} and {fpct(ew['height_cm'])} with `far_field=walls`.")
    if math.isfinite(eh["volume_added_cm3"]) and math.isfinite(ew["volume_added_cm3"]):
        if abs(eh["volume_added_cm3"]) < abs(ew["volume_added_cm3"]):
            L.append("- The height far field depends less on the box size than the paper's walls do, as intended.")
        else:
            L.append("- **The height far field does not depend less on the box size than the walls do.**")
    for thr in (0.02,):
        ok = abs(eh["volume_added_cm3"]) < thr if math.isfinite(eh["volume_added_cm3"]) else False
        L.append(f"- With `far_field=height` the box-size effect on the volume added is "
                 f"{'below' if ok else '**not below**'} {100 * thr:.0f} %.")
    dmax = max(b["per_case"][lab]["drift_cm"]["max"] for lab in b["cases"])
    L.append(f"- The largest centroid drift is {fnum(dmax, 3)} cm "
             f"({'under' if dmax < 0.1 * 1.2 else '**over**'} a tenth of a base cell): "
             + ("the centred sponge stays centred." if dmax < 0.12 else "the growth is not symmetric about the start."))
    return L


def report_sweeps(P, sw):
    L = ["## Parameter sweeps (`sweeps`)", ""]
    L.append(f"The supplement's sweeps, {P.sweep_iterations} iterations, seed {P.sweep_seed}: one parameter varied, "
             "the others at their defaults (radiate; R on the crella preset)" + (", box_resolution 1 (quick mode)." if P.quick else "."))
    for name, d in sw.items():
        L.append("")
        L.append(f"### {name} ({d['symbol']}, {d['preset']})")
        L.append("")
        rows = [[fnum(r["value"])] + [fnum(r[k], 4) for k, _ in SWEEP_METRICS] for r in d["rows"]]
        L.append(table([d["symbol"]] + [lab for _, lab in SWEEP_METRICS], rows))
        L.append("")
        tr = d["trend"]
        L.append(f"From {fnum(d['rows'][0]['value'])} to {fnum(d['rows'][-1]['value'])}: volume added "
                 f"{tr['volume_added_cm3']['direction']} ({fpct(tr['volume_added_cm3']['change_low_high'])}), "
                 f"height {tr['height_cm']['direction']} ({fpct(tr['height_cm']['change_low_high'])}), "
                 f"surface/volume {tr['surface_to_volume_per_cm']['direction']} "
                 f"({fpct(tr['surface_to_volume_per_cm']['change_low_high'])}), tips {tr['tips']['direction']}.")
    return L


def report_species(P, sp, picfiles, picrel):
    L = ["## Crella against radiate (`species`)", ""]
    n = len(P.species_seeds)
    L.append(f"{P.species_iterations} iterations, seeds {', '.join(map(str, P.species_seeds))}; crella preset "
             "(Halichondrid normals, R = 0.5, position jitter 4 cm) against radiate with the same position jitter "
             f"(`position_jitter=4`): the same seed puts both at the same place, so the runs are paired by seed"
             + (", box_resolution 1 (quick mode)." if P.quick else "."))
    L.append("")
    rows = []
    for k, label in SPECIES_METRICS:
        c, r = sp["per_species"]["crella"][k], sp["per_species"]["radiate"][k]
        t = sp["pairs"][k]
        sig_t = math.isfinite(t["t_p"]) and t["t_p"] < 0.05
        sig_w = math.isfinite(t["wilcoxon_p"]) and t["wilcoxon_p"] < 0.05
        rows.append([label, fsummary(c), fsummary(r),
                     fnum(t["mean_diff"], 3), fp(t["t_p"]), fp(t["wilcoxon_p"]),
                     ("yes" if sig_t and sig_w else "t-test only" if sig_t else "Wilcoxon only" if sig_w else "no")])
    L.append(table(["metric", "crella: mean ± sd (min–max)", "radiate: mean ± sd (min–max)",
                    "mean difference (crella − radiate)", "paired t p", "Wilcoxon p", "significant at 5 %"], rows))
    L.append("")
    notes = [f"{lab}: Wilcoxon by {sp['pairs'][k]['wilcoxon_method']}" for k, lab in SPECIES_METRICS
             if sp["pairs"][k]["wilcoxon_method"] not in (None, "exact")]
    L.append(f"Wilcoxon: exact two-sided signed-rank test; with {n} pair{'s' if n != 1 else ''} its smallest possible p is "
             f"{fp(sp['wilcoxon_min_p'])}" + (" — it cannot reach 5 % with so few pairs." if sp["wilcoxon_min_p"] >= 0.05 else ".")
             + (" " + "; ".join(notes) + "." if notes else ""))
    L.append("")
    L.append("**What holds, what does not:**")
    L.append("")
    for k, label in SPECIES_METRICS:
        t = sp["pairs"][k]
        if not math.isfinite(t["mean_diff"]):
            L.append(f"- {label}: undefined (fewer than two tips in a run).")
            continue
        if t["mean_diff"] == 0:
            L.append(f"- {label}: the same for both in every pair.")
            continue
        word = "larger" if t["mean_diff"] > 0 else "smaller"
        sig_t = math.isfinite(t["t_p"]) and t["t_p"] < 0.05
        sig_w = math.isfinite(t["wilcoxon_p"]) and t["wilcoxon_p"] < 0.05
        tests = f"t-test p = {fp(t['t_p'])}, Wilcoxon p = {fp(t['wilcoxon_p'])}"
        if sig_t and sig_w:
            verdict = "significant at 5 % by both tests"
        elif sig_t:
            verdict = "significant at 5 % by the t-test only"
        elif sig_w:
            verdict = "significant at 5 % by the Wilcoxon test only"
        else:
            verdict = "not significant at 5 %"
        L.append(f"- {label}: crella's is {word} by {fnum(abs(t['mean_diff']), 3)} on average ({tests}): {verdict}.")
    if picfiles:
        L.append("")
        L.append(f"Final surfaces by `sessile render`, each fitted to its sponge (grid label and caption give the "
                 f"scale; top row crella, bottom row radiate; seeds left to right): "
                 f"![species]({picrel}/{picfiles['sheet']})")
        L.append("")
        L.append(" · ".join(f"[{key}]({picrel}/{f})" for key, f in picfiles.items() if key != "sheet"))
    return L


def source_state():
    """The sessile source's commit (from git, where the script lives in a checkout)."""
    try:
        c = subprocess.run(["git", "-C", HERE, "rev-parse", "--short=12", "HEAD"], capture_output=True, text=True)
        if c.returncode != 0:
            return None
        dirty = subprocess.run(["git", "-C", HERE, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True).stdout.strip()
        return c.stdout.strip() + (" (with uncommitted changes)" if dirty else "")
    except OSError:
        return None


def write_report(path, P, args, results, part_times, runs_by_part, info, picfiles, plotfiles, picrel):
    L = ["# The sponge model: a study", ""]
    L.append("Written by `tools/science/study.py` (tools/science/README.md: how to run it, what each metric is). "
             "Every number below comes from the runs' files; rerunning the study with the same sessile gives the same "
             "numbers.")
    L.append("")
    L.append(f"- date: {datetime.datetime.now(datetime.timezone.utc).strftime('%Y-%m-%d %H:%M UTC')}")
    L.append(f"- sessile {info.get('version')}, source {info.get('source') or 'unknown'}, binary sha256 "
             f"{info['sha256'][:16]}…")
    L.append(f"- device: {info.get('device')}")
    L.append(f"- parts: {', '.join(results)}{' (quick mode: a smoke test, not results)' if P.quick else ''}; "
             f"`-j {args.jobs}`")
    L.append("- every run: `--every 0 --no-fields --slices '' --set fluid_at_snapshots=false` (no flow solve "
             "where diffusion_limited: it would not feed the growth; with the current on the flow is solved every "
             "iteration)")
    L.append("")
    rows = [[p, f"{part_times[p]['runs']}", f"{part_times[p]['ran']}", f"{part_times[p]['wall_s']:.0f} s",
             f"{part_times[p]['run_seconds']:.0f} s"] for p in results]
    L.append(table(["part", "runs", "run now", "wall time", "sum of run times"], rows))
    L.append("")
    L.append("Metrics: volume by the divergence theorem, area, height = largest z, surface/volume = area/volume "
             "(the base included), base area = triangles with all vertices at z < 0.05 cm, tips = vertices higher "
             "than every vertex within 2 cm along the mesh edges and above half the height, tip spacing = mean "
             "distance from each tip to the nearest other tip.")
    checks = [r.metrics["volume_check_rel"] for rs in runs_by_part.values() for r in rs.values()
              if r.metrics.get("volume_check_rel") is not None]
    if checks:
        L.append(f"The volumes computed here from each final PLY (float32) agree with the runs' own records to "
                 f"{max(checks):.1e} (relative, worst run).")
    L.append("")
    for part in results:
        if part == "grid":
            L += report_grid(P, results["grid"], runs_by_part["grid"])
        elif part == "box":
            L += report_box(P, results["box"])
        elif part == "sweeps":
            L += report_sweeps(P, results["sweeps"])
        elif part == "species":
            L += report_species(P, results["species"], picfiles, picrel)
        elif part == "current":
            L += pipelines.report_compare(P, results["current"], "## Crella against radiate, the current on and off "
                                          "(`current`)", sys.modules[__name__])
        elif part == "literal":
            res = {k: v for k, v in results["literal"].items() if k != "calibration"}
            L += pipelines.report_compare(P, res, "## The paper's literal pipeline (`literal`)",
                                          sys.modules[__name__], cal=results["literal"].get("calibration"))
        elif part == "height":
            L += pipelines.report_height(P, results["height"], sys.modules[__name__])
        L.append("")
    if plotfiles:
        L.append("## Plots")
        L.append("")
        for k, f in plotfiles.items():
            L.append(f"![{k}]({picrel}/{f})")
            L.append("")
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w") as f:
        f.write("\n".join(L).rstrip() + "\n")


# ---------------------------------------------------------------------------

def default_sessile():
    env = os.environ.get("SESSILE")
    if env:
        return env
    return os.path.normpath(os.path.join(HERE, "..", "..", "build", "sessile"))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__.split("\n", 2)[2])
    ap.add_argument("--out", required=True, help="output folder: runs/, results.json, pictures/")
    ap.add_argument("--report", help="the Markdown report (default OUT/report.md)")
    ap.add_argument("--json", help="the machine-readable results (default OUT/results.json)")
    ap.add_argument("--pictures", help="folder of the pictures (default OUT/pictures); links in the report are "
                                       "relative to the report")
    ap.add_argument("--parts", default=",".join(DEFAULT_PARTS),
                    help=f"comma-separated parts of {', '.join(PARTS)} (default: {', '.join(DEFAULT_PARTS)})")
    ap.add_argument("-j", "--jobs", type=int, default=2, help="runs at a time (default 2)")
    ap.add_argument("--quick", action="store_true",
                    help="smoke test: 3 iterations, 2 seeds, box_resolution 1 (the grid part on a 3.2 cm base grid)")
    ap.add_argument("--iterations", type=int, help="iterations of every run (overrides the parts' own)")
    ap.add_argument("--grid-seeds", type=parse_seeds, help="seeds of the grid part (default 1-3; quick 1-2)")
    ap.add_argument("--grid-jitter", type=float,
                    help="position_jitter of the grid runs in cm (default one base cell: 1.2; quick 3.2)")
    ap.add_argument("--box-seeds", type=parse_seeds, help="seeds of the box part (default 1)")
    ap.add_argument("--species-seeds", type=parse_seeds, help="seeds of the species part (default 1-6; quick 1-2)")
    ap.add_argument("--sweep-seed", type=int, default=1, help="seed of the sweeps and of height (default 1)")
    ap.add_argument("--compare-seeds", type=parse_seeds,
                    help="seeds of the current and literal parts (default 1-6; quick 1-2)")
    ap.add_argument("--current-seeds", type=parse_seeds,
                    help="seeds of current and literal with the current on (default: --compare-seeds)")
    ap.add_argument("--compare-modes", default="current,still",
                    help="current and literal: with the current on, without it, or both (default current,still)")
    ap.add_argument("--compare-resolution", default="1", help="box_resolution of current and literal (default 1)")
    ap.add_argument("--literal-current", action="store_true",
                    help="literal: also with the current on (every iteration solves the flow)")
    ap.add_argument("--height-resolution", default="2", help="box_resolution of height (default 2)")
    ap.add_argument("--sessile", default=default_sessile(), help="the sessile binary (default: build/sessile of "
                                                                  "this checkout, or $SESSILE)")
    ap.add_argument("--any-binary", action="store_true",
                    help="keep completed runs made by another sessile binary (default: rerun them)")
    ap.add_argument("--no-run", action="store_true", help="run nothing: analyse the completed runs, fail on missing ones")
    a = ap.parse_args(argv)

    parts = [p.strip() for p in a.parts.split(",") if p.strip()]
    bad = [p for p in parts if p not in PARTS]
    if bad or not parts:
        die(f"unknown part(s) {', '.join(bad) or '(none)'}; the parts are {', '.join(PARTS)}", 2)
    parts = [p for p in PARTS if p in parts]
    if not set(P_modes := [m.strip() for m in a.compare_modes.split(",") if m.strip()]) <= {"current", "still"} \
            or not P_modes:
        die(f"--compare-modes takes current, still or both (got '{a.compare_modes}')", 2)
    if a.jobs < 1:
        die("-j needs at least 1", 2)
    if not (os.path.isfile(a.sessile) and os.access(a.sessile, os.X_OK)):
        die(f"no sessile binary at {a.sessile} (build it: cmake --build build, or pass --sessile)", 2)
    out = os.path.abspath(a.out)
    os.makedirs(out, exist_ok=True)
    report = a.report or os.path.join(out, "report.md")
    jpath = a.json or os.path.join(out, "results.json")
    picdir = os.path.abspath(a.pictures or os.path.join(out, "pictures"))
    picrel = os.path.relpath(picdir, os.path.dirname(os.path.abspath(report)))

    sessile = Sessile(os.path.abspath(a.sessile))
    P = Plan(a)
    made = {}

    def mk(preset, seed, iterations, sets):
        r = Run(sessile, preset, seed, iterations, sets)
        return made.setdefault(r.name, r)  # identical runs are one run

    planners = {"grid": plan_grid, "box": plan_box, "sweeps": plan_sweeps, "species": plan_species,
                "current": pipelines.plan_current,
                "height": lambda P, mk: pipelines.plan_height(P, mk, sessile.table("radiate", dict(COMMON_SETS)))}
    runs_by_part = {p: planners[p](P, mk) for p in parts if p != "literal"}
    literal_cal = {}
    if "literal" in parts:
        # K of the literal pipeline needs two one-iteration runs per mode first.
        cal = {m: pipelines.calibration_runs(P, mk, m) for m in pipelines.literal_modes(P)}
        calruns = [r for c in cal.values() for r in c.values()]
        if a.no_run:
            missing = [r.name for r in calruns if not r.done(sessile, out, True)]
            if missing:
                die(f"--no-run: runs not completed: {', '.join('runs/' + m for m in missing)}")
        else:
            log(f"literal: {len(calruns)} calibration runs of one iteration")
            try:
                execute(calruns, sessile, out, a.jobs, a.any_binary, {"done": 0, "total": len(calruns)})
            except RunFailed as e:
                die(f"part literal: {e}")
        table = sessile.table("radiate", dict(COMMON_SETS))
        literal_cal = {m: pipelines.literal_k(c, out, table) for m, c in cal.items()}
        runs_by_part["literal"] = pipelines.plan_literal(P, mk, {m: v["k_literal"] for m, v in literal_cal.items()})
        runs_by_part["literal"].update({("cal", m, p): r for m, c in cal.items() for p, r in c.items()})
        runs_by_part = {p: runs_by_part[p] for p in parts}
    counter = {"done": 0, "total": len(made)}
    log(f"{len(made)} runs for {', '.join(parts)}{' (quick)' if P.quick else ''}, {a.jobs} at a time, in {out}")

    part_times = {}
    started = set()
    for p in parts:
        mine = [r for r in dict.fromkeys(runs_by_part[p].values()) if r.name not in started]
        started.update(r.name for r in mine)
        t0 = time.monotonic()
        if a.no_run:
            missing = [r.name for r in mine if not r.done(sessile, out, True)]
            if missing:
                die(f"--no-run: runs not completed: {', '.join('runs/' + m for m in missing)}")
            for r in mine:
                r.skipped = True
        else:
            log(f"part {p}: {len(mine)} runs")
            try:
                execute(mine, sessile, out, a.jobs, a.any_binary, counter)
            except RunFailed as e:
                die(f"part {p}: {e}")
            except KeyboardInterrupt:
                die("interrupted; completed runs are kept, run the same command again to resume", 130)
        all_mine = list(dict.fromkeys(runs_by_part[p].values()))
        part_times[p] = {"runs": len(all_mine), "ran": sum(1 for r in mine if not r.skipped),
                         "wall_s": time.monotonic() - t0,
                         "run_seconds": sum((r.seconds or 0) for r in mine if not r.skipped)}
        log(f"part {p}: runs finished in {part_times[p]['wall_s']:.1f} s")

    log("measuring the surfaces")
    for r in made.values():
        measure(r, out)
        if r.metrics["volume_check_rel"] is not None and r.metrics["volume_check_rel"] > 1e-4:
            log(f"warning: runs/{r.name}: the PLY's volume differs from the record's by "
                f"{r.metrics['volume_check_rel']:.1e} (relative)")
        if not r.metrics["closed"]:
            log(f"warning: runs/{r.name}: the final surface is not closed; its volume is not meaningful")

    pairs = lambda P, runs: pipelines.analyse_pairs(  # noqa: E731
        P, {k: r for k, r in runs.items() if len(k) == 4}, paired_tests, stats)
    analysers = {"grid": analyse_grid, "box": analyse_box, "sweeps": analyse_sweeps, "species": analyse_species,
                 "current": pairs, "literal": pairs, "height": pipelines.analyse_height}
    results = {p: analysers[p](P, runs_by_part[p]) for p in parts}
    if literal_cal:
        results["literal"]["calibration"] = literal_cal

    picfiles = {}
    if "species" in parts:
        log("rendering the species' final surfaces")
        try:
            picfiles = pictures(P, runs_by_part["species"], out, picdir, sessile)
        except RuntimeError as e:  # e.g. a device without graphics: keep the numbers' report
            log(f"warning: no pictures of the surfaces (sessile render: {e})")
            picfiles = {}
    try:
        plotfiles = plots(results, runs_by_part, out, picdir)
    except Exception as e:  # the plots are an extra: never lose the report to them
        log(f"warning: no plots ({type(e).__name__}: {e})")
        plotfiles = {}

    any_run = next(iter(made.values()))
    info = {"version": any_run.info["version"], "device": any_run.info["device"], "sha256": sessile.sha256,
            "source": source_state()}
    write_report(report, P, a, results, part_times, runs_by_part, info, picfiles, plotfiles, picrel)
    doc = {
        "study": {"parts": parts, "quick": P.quick, "jobs": a.jobs, "plan": P.describe(), "sessile": info,
                  "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
                  "part_times": part_times,
                  "metric_definitions": {"base_z_cm": metrics.BASE_Z, "tip_radius_cm": metrics.TIP_RADIUS,
                                         "tip_min_fraction_of_height": metrics.TIP_MIN_FRACTION}},
        "runs": {r.name: {"preset": r.preset, "seed": r.seed, "iterations": r.iterations, "sets": r.differs,
                          "seconds": r.seconds, "kept": r.skipped,
                          "metrics": {k: v for k, v in r.metrics.items() if k != "volume_series_cm3"},
                          "volume_series_cm3": r.metrics["volume_series_cm3"]} for r in made.values()},
        "parts": results,
        "part_runs": {p: {" / ".join(map(str, k)): r.name for k, r in rs.items()} for p, rs in runs_by_part.items()},
        "pictures": picfiles, "plots": plotfiles,
    }
    with open(jpath, "w") as f:
        json.dump(jsonable(doc), f, indent=1, allow_nan=False)
    log(f"report: {report}")
    log(f"results: {jpath}")
    return 0


def _terminate(signum, frame):
    raise KeyboardInterrupt


if __name__ == "__main__":
    signal.signal(signal.SIGTERM, _terminate)
    sys.exit(main())
