#!/usr/bin/python3
"""Progress on every long command (docs/run.md "Progress"), at tiny sizes:
under a pseudo-terminal a status line with a percent and the time left;
piped, a few lines and no carriage returns; --progress=json one JSON object
per stderr line (percent rising to 100, the schema's members); --quiet
nothing at all.  Every command answers --help and --version with exit 0.
usage: test_progress.py SESSILE"""
import json, os, pty, re, select, shutil, subprocess, sys, tempfile

S = sys.argv[1]
T = tempfile.mkdtemp()
fails = passes = 0


def check(what, ok, why=""):
    global fails, passes
    print(("PASS " if ok else "FAIL ") + what + ("" if ok else ": " + why))
    passes, fails = passes + bool(ok), fails + (not ok)


def run_tty(args):
    """stderr (and stdin) on a pseudo-terminal, stdout piped: (rc, stdout, terminal text)."""
    master, slave = pty.openpty()
    p = subprocess.Popen([S] + args, stdin=slave, stdout=subprocess.PIPE, stderr=slave)
    os.close(slave)
    got = b""
    while True:
        # whether it had ended BEFORE this select: then all it wrote is
        # readable now (asked after a select that found nothing, a command
        # that wrote and ended in between would lose its last output)
        ended = p.poll() is not None
        r, _, _ = select.select([master], [], [], 0.2)
        if r:
            try:
                chunk = os.read(master, 65536)
            except OSError:  # EIO: the terminal's last writer is gone
                break
            if not chunk:
                break
            got += chunk
        elif ended:
            break
    os.close(master)
    out = p.stdout.read().decode()
    return p.wait(), out, got.decode(errors="replace")


def run_pipe(args):
    p = subprocess.run([S] + args, capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


SMALL_GROW = ["--set", "box_resolution=1", "--set", "box_cells_x=16", "--set", "box_cells_y=16", "--set",
              "box_cells_z=12", "--set", "sponge_radius=3", "--set", "fluid_at_snapshots=false", "--no-fields",
              "--iterations", "2", "--every", "0"]
SMALL_SPONGE = ["--set", "mesh_detail=3", "--set", "nutrients_per_iteration=120", "--set", "cube_size=3",
                "--iterations", "3"]
# (name, command words, options); each run adds --out=DIR (the '=' form) and --no-preview
GENERATORS = [
    ("grow", ["grow"], SMALL_GROW),
    ("sphere", ["sphere"], ["--iterations", "3"]),
    ("coral venation", ["coral", "venation"], ["--iterations", "20", "--set", "search=host"]),
    ("sponge particles", ["sponge", "particles"], SMALL_SPONGE),
    ("sds run", ["sds", "run", "limb"], ["--t-end", "1", "--frames", "2"]),
    ("reef", ["reef", os.path.join(T, "reef.json")], ["--seed", "5"]),
    ("coral lsystem", ["coral", "lsystem"], ["--iterations", "6"]),
]
# a reef of a few pebbles: its organisms are grown in the final outputs
REEF = {"seabed": {"noise": {"seed": 2, "resolution": [17, 17], "extent": [10, 10], "height_scale": 1, "base": -6,
                             "wavelength": 5, "octaves": 2}},
        "sea_level": 0, "growth": {"steps": 2, "spacing": 0.8}, "brushes": [{"points": [[5, 5]], "size": 2, "density": 2}],
        "pool": [{"name": "pebble", "generator": "sphere", "parameters": ["level=1", "noise=0.1"],
                  "colour": [0.3, 0.5, 0.9, 1], "size": [0.3, 0.5]}]}
with open(os.path.join(T, "reef.json"), "w") as f:
    json.dump(REEF, f)
SWEEP = {"generator": "sphere", "iterations": 2, "options": ["--no-preview"], "base": {"level": 2},
         "axes": [{"parameter": "noise", "values": [0.01, 0.03]}], "seeds": {"count": 1, "first": 1}}
n_runs = 0


def command(name, words, opts, how):
    """The command line of one run of a long command, in a new folder."""
    global n_runs
    n_runs += 1
    out = os.path.join(T, "r%d" % n_runs)
    if name == "render":
        shutil.copytree(os.path.join(T, "base"), out)  # a run to draw, a fresh copy each time
        return ["render", out, "--size", "96x72"] + how
    if name == "sweep run":
        with open(os.path.join(T, "sweep.json"), "w") as f:
            json.dump(SWEEP, f)
        rc, _, err = run_pipe(["sweep", "plan", os.path.join(T, "sweep.json"), "--out", out])
        if rc:
            raise SystemExit("sweep plan failed: " + err)
        return ["sweep", "run", out, "-j", "2"] + how
    return words + opts + ["--out=" + out, "--no-preview"] + how


LEFT = r"[~>][0-9][0-9.]*( s|m[0-9][0-9]s|h[0-9][0-9]m) left"
rc, _, err = run_pipe(["sphere", "--iterations", "3", "--out", os.path.join(T, "base"), "--quiet"])
check("a run for render to draw", rc == 0, err)
LONG = GENERATORS + [("render", [], []), ("sweep run", [], [])]

for name, words, opts in LONG:
    helpwords = words[:2] if name != "sds run" else ["sds", "run"]
    if name in ("render", "sweep run"):
        helpwords = name.split()
    for flag in ("--help", "--version"):
        rc, out, err = run_pipe(helpwords + [flag])
        check("%s %s: exit 0 with text on stdout" % (name, flag), rc == 0 and out and not err, "rc %d %s" % (rc, err))
    rc, out, _ = run_pipe(helpwords + ["--help"])
    check("%s --help names --progress and --quiet" % name, "--progress" in out and "--quiet" in out, out[-300:])

    # a terminal: the status line rewritten in place, with a percent and the time left
    rc, out, term = run_tty(command(name, words, opts, []))
    status = [s for s in re.split(r"[\r\n]+", term.replace("\033[K", "")) if s.strip()]
    ok = rc == 0 and "\r\033[K" in term and any(re.search(r"[0-9]+%", s) for s in status) and \
        any(re.search(LEFT, s) for s in status)
    check("%s on a terminal: a status line with a percent and the time left" % name, ok,
          "rc %d, terminal %r" % (rc, term[-400:]))

    # piped: lines, no carriage return, at most ~11 for a stage
    rc, out, err = run_pipe(command(name, words, opts, []))
    lines = [l for l in err.splitlines() if l.startswith(name + ":")]
    ok = rc == 0 and "\r" not in err and lines and len(lines) <= 12 and re.search(LEFT, lines[-1]) and \
        "100%" in lines[-1]
    check("%s piped: a few lines, the last at 100%% with the time left" % name, ok, "rc %d, stderr %r" % (rc, err[-400:]))

    # --progress=json: every stderr line one JSON object of the schema
    rc, out, err = run_pipe(command(name, words, opts, ["--progress=json"]))
    recs, why = [], ""
    for l in err.splitlines():
        try:
            recs.append(json.loads(l))
        except ValueError:
            why = "not JSON: %r" % l
    keys = {"command", "stage", "step", "steps", "percent", "elapsed_s", "left_s", "left_min", "ended"}
    ended = [r for r in recs if r.get("ended")]
    ok = rc == 0 and not why and recs and all(keys <= set(r) for r in recs) and ended and \
        all(r["command"] == name for r in recs) and ended[-1]["percent"] == 100 and \
        all(a["percent"] <= b["percent"] for a, b in zip(ended, ended[1:])) and \
        all(r["left_s"] is None or r["left_s"] >= 0 for r in recs) and \
        any(r["left_s"] is not None for r in ended)
    check("%s --progress=json: each stderr line parses, percent rises to 100" % name, ok,
          why or "rc %d, stderr %r" % (rc, err[-400:]))

    # --quiet: nothing at all on success
    rc, out, err = run_pipe(command(name, words, opts, ["--quiet"]))
    check("%s --quiet: exit 0, nothing on stdout or stderr" % name, rc == 0 and not out and not err,
          "rc %d, stdout %r, stderr %r" % (rc, out[-200:], err[-200:]))

# --quiet --progress=json: the reports without the summary
rc, out, err = run_pipe(command("sphere", ["sphere"], ["--iterations", "2"], ["--quiet", "--progress", "json"]))
check("--quiet --progress json: JSON on stderr, stdout empty",
      rc == 0 and not out and err and all(l.startswith("{") for l in err.splitlines()), err[-300:])
# a resumed run starts part way: its first report is past 0
first = os.path.join(T, "resume")
run_pipe(["sphere", "--iterations", "2", "--every", "1", "--out", first, "--quiet", "--no-preview"])
rc, out, err = run_pipe(["sphere", "--resume", first, "--iterations", "4", "--progress=json"])
recs = [json.loads(l) for l in err.splitlines() if l.startswith("{")]
check("a resumed run's reports start at its checkpoint (iteration 3 of 4, 75%)",
      rc == 0 and recs and recs[0]["step"] == 3 and recs[0]["percent"] == 75, err[-300:])

shutil.rmtree(T, ignore_errors=True)
print("%d passed, %d failed" % (passes, fails))
sys.exit(1 if fails else 0)
