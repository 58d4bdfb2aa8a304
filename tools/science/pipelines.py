"""The study's parts on the paper's claims under other pipelines (issue 32):
crella against radiate with the ocean current on (`current`), the paper's
literal pipeline beside today's (`literal`), and the far-field height swept
(`height`).  study.py plans, runs and measures; this file says which runs
each part makes, analyses them and writes their sections of the report.
"""
import math

import numpy as np

# The metrics of the paper's claims (§5: "less dense, more spread out, and
# taller extrusions"), then the rest of the species table.
CLAIM_METRICS = [("height_cm", "height (cm)"), ("spread_cm", "spread (cm)"), ("tips", "extrusions (tips)"),
                 ("base_area_cm2", "base area (cm²)"), ("volume_cm3", "volume (cm³)"),
                 ("surface_to_volume_per_cm", "surface/volume (1/cm)"), ("tip_spacing_cm", "tip spacing (cm)")]

# The paper's pipeline, literally: eq 6's probe (K rescaled, below), the
# sequential translocation of eqs 7-8, the box's walls at c = 1.
LITERAL = {"probe": "paper", "translocate_mode": "sequential", "far_field": "walls"}
MODES = {"current": {"diffusion_limited": "false"}, "still": {"diffusion_limited": "true"}}
MODE_WORDS = {"current": "current on (`diffusion_limited=false`)", "still": "diffusion limited (no current)"}

HEIGHT_FACTORS = ["0.5", "1", "1.5", "2"]
HEIGHT_METRICS = [("volume_added_cm3", "volume added (cm³)"), ("height_cm", "height (cm)"),
                  ("spread_cm", "spread (cm)"), ("surface_to_volume_per_cm", "S/V (1/cm)"),
                  ("base_area_cm2", "base area (cm²)"), ("tips", "tips")]


def seeds_of(P, mode):
    return P.current_seeds if mode == "current" else P.compare_seeds


def _pair_runs(P, mk, tag, sets, modes):
    """crella and radiate, paired by seed (the same position jitter), per mode."""
    runs = {}
    for mode in modes:  # the current first: its runs are the long ones
        for s in seeds_of(P, mode):
            base = dict(P.compare_extra, **sets, **MODES[mode])
            runs[(tag, mode, "crella", s)] = mk("crella", s, P.compare_iterations, base)
            runs[(tag, mode, "radiate", s)] = mk("radiate", s, P.compare_iterations,
                                                 dict(base, position_jitter=P.species_jitter))
    return runs


def plan_current(P, mk):
    """Today's pipeline with the current on, and the same runs without it."""
    return _pair_runs(P, mk, "today", {}, [m for m in ("current", "still") if m in P.compare_modes])


def literal_modes(P):
    return [m for m in ("current", "still") if m in P.compare_modes and (m == "still" or P.literal_current)]


def calibration_runs(P, mk, mode):
    """One iteration of radiate under the literal far field, probed both ways:
    the ratio of their mean probed C on the initial dome rescales K."""
    base = dict(P.compare_extra, far_field=LITERAL["far_field"], **MODES[mode])
    return {p: mk("radiate", 1, 1, dict(base, probe=p)) for p in ("flux", "paper")}


def probed_mean(run, out):
    import json
    import os
    with open(os.path.join(run.folder(out), "records.jsonl")) as f:
        first = json.loads(f.readline())
    return first["growth"]["probed_nutrient"]["mean"]


def literal_k(cal, out, table):
    """K for eq 6's probe in the flux probe's units: with C_paper = a C_flux,
    C_paper^n / (K' + C_paper^n) = C_flux^n / (K'/a^n + C_flux^n), so K' = K a^n
    keeps eq 10's curve where it acts on the flux probe's C."""
    a = probed_mean(cal["paper"], out) / probed_mean(cal["flux"], out)
    n, k = float(table["kinetic_order"]), float(table["growth_constant"])
    return {"ratio": a, "kinetic_order": n, "k_today": k, "k_literal": float(f"{k * a ** n:.4g}")}


def plan_literal(P, mk, ks):
    """ks: {mode: K of the literal pipeline} from the calibration runs."""
    runs = {}
    for mode in literal_modes(P):
        runs.update(_pair_runs(P, mk, "literal", dict(LITERAL, growth_constant=str(ks[mode])), [mode]))
    return runs


def default_height(table):
    """far_field_height as the run resolves it (-1: the box top), cm."""
    h = float(table["far_field_height"])
    return h if h > 0 else float(table["box_base_cell"]) * int(table["box_cells_z"])


def plan_height(P, mk, table):
    """Radiate, diffusion limited, far_field_height at factors of its default.
    Every run gets the same box, tall enough for the largest H (nodes above H
    hold c = 1, so the box above it changes nothing but the cost)."""
    h0 = default_height(table)
    cell, cz = float(table["box_base_cell"]), int(table["box_cells_z"])
    need = math.ceil(max(float(f) for f in HEIGHT_FACTORS) * h0 / cell - 1e-9)
    cz = max(cz, need + need % 2)  # even: the multigrid halves it
    runs = {}
    for f in HEIGHT_FACTORS:
        sets = dict(P.height_extra, far_field="height", far_field_height=f"{float(f) * h0:.6g}", box_cells_z=str(cz))
        runs[f] = mk("radiate", P.sweep_seed, P.height_iterations, sets)
    P.height_default_cm, P.height_cells_z = h0, cz
    return runs


# ---------------------------------------------------------------------------
# Analysis
# ---------------------------------------------------------------------------

def mean_ci(d, level=0.95):
    """Mean of the paired differences d and its two-sided t interval."""
    from scipy import stats as st
    d = np.asarray([x for x in d if x is not None and math.isfinite(x)], float)
    n = len(d)
    if n == 0:
        return float("nan"), float("nan"), float("nan")
    m = float(d.mean())
    if n < 2:
        return m, float("nan"), float("nan")
    half = float(st.t.ppf(0.5 + level / 2, n - 1) * d.std(ddof=1) / math.sqrt(n))
    return m, m - half, m + half


def verdict(lo, hi, want_positive=True):
    """The paper's direction against a 95 % interval of crella - radiate."""
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return "no interval (fewer than 2 pairs)"
    if lo > 0:
        return "holds" if want_positive else "opposite"
    if hi < 0:
        return "opposite" if want_positive else "holds"
    return "not resolved (the interval holds 0)"


def analyse_pairs(P, runs, paired_tests, stats):
    """{tag/mode: {seeds, per_species, pairs}}; pairs carry the 95 % interval."""
    res = {}
    for tag, mode in sorted({(k[0], k[1]) for k in runs}):
        seeds = seeds_of(P, mode)
        r = {"tag": tag, "mode": mode, "seeds": seeds, "per_species": {}, "pairs": {},
             "runs": {f"{sp}-{s}": runs[(tag, mode, sp, s)].name for sp in ("crella", "radiate") for s in seeds}}
        for sp in ("crella", "radiate"):
            r["per_species"][sp] = {k: stats([runs[(tag, mode, sp, s)].metrics[k] for s in seeds])
                                    for k, _ in CLAIM_METRICS}
        for k, _ in CLAIM_METRICS:
            c = [runs[(tag, mode, "crella", s)].metrics[k] for s in seeds]
            d = [runs[(tag, mode, "radiate", s)].metrics[k] for s in seeds]
            t = paired_tests(c, d)
            diffs = [x - y for x, y in zip(c, d) if x is not None and y is not None]
            t["mean"], t["ci_lo"], t["ci_hi"] = mean_ci(diffs)
            base = r["per_species"]["radiate"][k]["mean"]
            t["rel"] = t["mean"] / abs(base) if base and math.isfinite(base) else float("nan")
            t["verdict"] = verdict(t["ci_lo"], t["ci_hi"])
            r["pairs"][k] = t
        res[f"{tag}/{mode}"] = r
    return res


def analyse_height(P, runs):
    rows = []
    ref = runs["1"].metrics
    for f in HEIGHT_FACTORS:
        m = runs[f].metrics
        row = {"factor": float(f), "far_field_height_cm": float(f) * P.height_default_cm, "run": runs[f].name}
        for k, _ in HEIGHT_METRICS:
            row[k] = m[k]
            row[k + "_rel"] = (m[k] - ref[k]) / abs(ref[k]) if ref[k] else float("nan")
        rows.append(row)
    return {"default_cm": P.height_default_cm, "box_cells_z": P.height_cells_z, "rows": rows}


# ---------------------------------------------------------------------------
# Report
# ---------------------------------------------------------------------------

def _ci(t, fnum):
    if not math.isfinite(t["mean"]):
        return "–"
    if not math.isfinite(t["ci_lo"]):
        return fnum(t["mean"], 3)
    return f"{fnum(t['mean'], 3)} [{fnum(t['ci_lo'], 3)}, {fnum(t['ci_hi'], 3)}]"


def _pair_table(r, f):
    rows = []
    for k, label in CLAIM_METRICS:
        t = r["pairs"][k]
        rows.append([label, f.fsummary(r["per_species"]["crella"][k]), f.fsummary(r["per_species"]["radiate"][k]),
                     _ci(t, f.fnum), f.fpct(t["rel"]), f.fp(t["t_p"]), f.fp(t["wilcoxon_p"])])
    return f.table(["metric", "crella: mean ± sd (min–max)", "radiate: mean ± sd (min–max)",
                    "crella − radiate [95 % CI]", "relative to radiate", "paired t p", "Wilcoxon p"], rows)


def _claims(res, keys, f):
    """One row per claim, one column per pipeline/mode: the difference with
    its interval and whether the paper's direction holds."""
    claims = [("height_cm", "taller"), ("spread_cm", "more spread out"), ("tips", "more extrusions"),
              ("base_area_cm2", "larger base")]
    head = ["the paper: crella is …"] + [f"{res[k]['tag']}, {res[k]['mode']}" for k in keys]
    rows = []
    for m, word in claims:
        rows.append([f"{word} ({m})"] + [f"{_ci(res[k]['pairs'][m], f.fnum)}: {res[k]['pairs'][m]['verdict']}"
                                         for k in keys])
    return f.table(head, rows)


def describe_pipeline(tag, ks=None):
    if tag == "today":
        return ("today's pipeline (the flux probe, the order-independent translocation, far_field=height: "
                "docs/model.md)")
    k = "" if not ks else "; K = " + ", ".join(f"{v['k_literal']:.4g} ({m})" for m, v in ks.items())
    return ("the paper's literal pipeline (`probe=paper`: eq 6, `translocate_mode=sequential`: eqs 7-8 vertex by "
            f"vertex, `far_field=walls`: c = 1 on every wall but the substratum{k})")


def report_compare(P, res, title, f, ks=None, cal=None):
    L = [title, ""]
    seeds = "; ".join(f"{MODE_WORDS[m].split(' (')[0]}: seeds {', '.join(map(str, seeds_of(P, m)))}"
                      for m in sorted({r["mode"] for r in res.values()}))
    L.append(f"{P.compare_iterations} iterations, box_resolution {P.compare_resolution} ({seeds}); crella (Halichondrid normals, R = 0.5) against radiate with "
             "the same position jitter (4 cm), paired by seed. The interval is the 95 % t interval of the mean "
             "paired difference (crella − radiate); \"holds\" means the whole interval lies on the paper's side "
             "of 0, \"opposite\" on the other.")
    L.append("")
    if cal:
        L.append("K of the literal pipeline: eq 6's probe reads C in other units than the flux probe (a uniform "
                 "c = 1 probes to 0.22 with 8 samples, and c is near 0 next to the surface). Its mean over the "
                 "initial dome, over the flux probe's there (radiate, one iteration, the walls' far field), is a; "
                 "C_paper = a·C_flux turns eq 10's curve into the same curve of C_flux when K' = K·aⁿ:")
        L.append("")
        L.append(f.table(["mode", "a = mean C (eq 6) / mean C (flux)", "n", "K today", "K' = K·aⁿ"],
                         [[m, f.fnum(v["ratio"], 4), f.fnum(v["kinetic_order"]), f.fnum(v["k_today"]),
                           f.fnum(v["k_literal"], 4)] for m, v in cal.items()]))
        L.append("")
    keys = sorted(res, key=lambda k: (k.split("/")[0] != "today", k.split("/")[1] != "current"))
    L.append("**The paper's claims, crella − radiate [95 % CI]:**")
    L.append("")
    L.append(_claims(res, keys, f))
    L.append("")
    for k in keys:
        r = res[k]
        L.append(f"### {describe_pipeline(r['tag']).split(' (')[0].capitalize()}, {MODE_WORDS[r['mode']]}")
        L.append("")
        L.append(_pair_table(r, f))
        L.append("")
    return L


def report_height(P, h, f):
    L = ["## The far-field height (`height`)", ""]
    L.append(f"Radiate, diffusion limited, {P.height_iterations} iterations, seed {P.sweep_seed}, box_resolution "
             f"{P.height_resolution}: far_field_height H at {', '.join(HEIGHT_FACTORS)} times its default "
             f"({f.fnum(h['default_cm'], 4)} cm), every run in a box of {h['box_cells_z']} base cells in z (tall "
             "enough for the largest H; c = 1 at and above H, so the box above H changes nothing). The flux "
             "probe's C is the flux over the bare substratum's, 1/H, so C's scale follows H. Changes are against "
             "the default H.")
    L.append("")
    rows = []
    for r in h["rows"]:
        rows.append([f.fnum(r["factor"]), f.fnum(r["far_field_height_cm"], 4)]
                    + [f"{f.fnum(r[k], 4)} ({f.fpct(r[k + '_rel'])})" for k, _ in HEIGHT_METRICS])
    L.append(f.table(["H / default", "H (cm)"] + [lab for _, lab in HEIGHT_METRICS], rows))
    return L
