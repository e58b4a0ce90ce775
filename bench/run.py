#!/usr/bin/env python3
"""Run time against error: drives `raybudget sweep` over the generated scenes (data/default,
data/plaza) and every scene of ../shared/scenes/bench that loads, scores each frame with FLIP
(NVIDIA's flip-evaluator) against the full-RT reference, computes the oracle bound, and writes
results/<date>/: frames.csv, summary.csv, headline.md, headline.json, plots and image strips
(the per-scene sweeps and their images under raw/). docs/BENCHMARKS.md defines every figure.

usage: bench/run.py [--quick] [--out DIR] [--publish DIR] [--scenes FILE...]
                    [--policies LIST] [--budgets N] [--frames N] [--warmup N] [--lead-in N]
                    [--repeats N] [--size WxH] [--paths LIST] [--order-seed S]
                    [--validation] [--budget-confidence C] [--no-stage-deadline]
                    [--compare OTHER_RUN_DIR]

Needs numpy, matplotlib and flip-evaluator (scripts/bench-deps.sh makes .venv-bench).
"""
import argparse
import csv
import datetime
import json
import math
import pathlib
import shutil
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent
BENCH_SCENES = ROOT.parent / "shared" / "scenes" / "bench"
GENERATED = [ROOT / "data" / "default" / "court.gltf", ROOT / "data" / "plaza" / "plaza.gltf"]
POLICIES = ["paper", "density", "nearest", "random", "benefit", "benefit-rates"]
# `benefit` with one part left out (docs/SELECTION.md), with --ablations.
ABLATIONS = ["benefit-no-centrality", "benefit-no-hysteresis", "benefit-prior-only", "benefit-no-classifier", "benefit-no-probe"]
FRACTIONS = [0.10, 0.25, 0.50]  # of `all`'s stage cost
# A recorded frame whose fallback's FLIP is within this of full RT's says little of a policy
# alone (its share of a tiny gap is mostly noise): the by-frame figures leave it out.
FRAME_GAP = 0.001
ADHERENCE_SLACK = 1.05          # the promise: rt_stage_ms <= T + 5%
COLORS = {"paper": "tab:orange", "density": "tab:blue", "nearest": "tab:green", "random": "tab:purple", "benefit": "tab:brown", "benefit-rates": "black",
          "benefit-no-centrality": "tab:pink", "benefit-no-hysteresis": "tab:cyan", "benefit-prior-only": "gold",
          "benefit-no-classifier": "darkgreen", "benefit-no-probe": "sienna",
          "none": "black", "all": "tab:red", "classified": "tab:olive", "oracle": "tab:gray"}


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--quick", action="store_true", help="court and one bench scene, fewer frames and budgets (under 5 minutes)")
    p.add_argument("--out", help="output folder (default results/<date>)")
    p.add_argument("--scenes", nargs="+", help="scene files (default: the generated scenes and every bench scene)")
    p.add_argument("--policies", default=",".join(POLICIES))
    p.add_argument("--ablations", action="store_true", help="also run benefit with each of its parts left out: " + ", ".join(ABLATIONS))
    p.add_argument("--budgets", type=int)
    p.add_argument("--frames", type=int)
    p.add_argument("--warmup", type=int)
    p.add_argument("--lead-in", type=int, help="frames of the camera moving along the path before the last recorded frame "
                   "(the others follow the still warm-up or a jump; default 8, --quick 0)")
    p.add_argument("--repeats", type=int)
    p.add_argument("--size")
    p.add_argument("--paths", default="orbit,flythrough")
    p.add_argument("--order-seed", type=int, default=1, help="shuffles each repeat's configurations (0: a fixed order)")
    p.add_argument("--raybudget", default=str(ROOT / "build" / "tools" / "raybudget"))
    p.add_argument("--validation", action="store_true")
    p.add_argument("--no-screen-space-transmission", action="store_true", help="passed to the sweep: glass falls back to the environment alone")
    p.add_argument("--no-reflection-probes", action="store_true", help="passed to the sweep: reflections fall back to the sky alone")
    p.add_argument("--no-screen-space-reflections", action="store_true", help="passed to the sweep: no screen-space reflections")
    p.add_argument("--prior-time-scale", action="store_true", help="passed to the sweep: never learn the time scale")
    p.add_argument("--no-temporal-fill", action="store_true", help="passed to the sweep: reduced rates fill from traced "
                   "neighbours alone")
    p.add_argument("--budget-list", help="passed to the sweep: explicit budgets in ms")
    p.add_argument("--budget-confidence", help="passed to the sweep: the headroom's quantile (default 0.9)")
    p.add_argument("--no-stage-deadline", action="store_true", help="passed to the sweep: trace all that was selected even past T")
    p.add_argument("--publish", help="also copy summary.csv, headline.md, headline.json, plots/ and strips/ into this folder")
    p.add_argument("--compare", help="a finished run's folder: its headline figures beside this run's and the per-case differences (compare.md)")
    p.add_argument("--resume", action="store_true", help="keep the sweeps of --out that finished (raw/<scene>/sweep.ok)")
    p.add_argument("--aggregate-only", action="store_true", help="no sweeps: recompute the tables, plots and strips from --out's "
                   "frames.csv and oracle.csv")
    a = p.parse_args(argv)
    if a.ablations:
        a.policies = ",".join([a.policies] + ABLATIONS)
    # 14 warm-up frames: the headroom (engine/src/select/cost_model.h) waits for 8 measured
    # frames after a restart, and the first recorded frame's still view has had most of 1/16's
    # period (docs/BENCHMARKS.md).
    # --lead-in N: the last recorded frame follows N frames of the camera moving along the
    # path (the learned costs and values and the temporal fill following the view) instead of
    # a jump, so that the three recorded frames are the three cases an engine meets: a still
    # view, a camera cut and a moving camera (--quick keeps jumps alone: under 5 minutes).
    full = dict(budgets=6, frames=3, warmup=14, lead_in=8, repeats=2, size="640x360")
    quick = dict(budgets=5, frames=3, warmup=5, lead_in=0, repeats=2, size="320x180")
    for k, v in (quick if a.quick else full).items():
        if getattr(a, k) is None:
            setattr(a, k, v)
    if a.out is None:
        a.out = str(ROOT / "results" / datetime.date.today().isoformat())
    return a


def lead_in_text(a):
    return f" (the last after {a.lead_in} frames moving)" if a.lead_in else ""


def bench_scenes():
    if not BENCH_SCENES.is_dir():
        print(f"run.py: {BENCH_SCENES} is absent: only the generated scenes are benchmarked", file=sys.stderr)
        return []
    found = []
    for d in sorted(BENCH_SCENES.iterdir()):
        files = sorted(list(d.glob("*.gltf")) + list(d.glob("*.glb")))
        if files:
            found.append(files[0])
    return found


def default_scenes(quick):
    bench = bench_scenes()
    if quick:
        return GENERATED[:1] + [s for s in bench if s.parent.name == "TransmissionTest"]
    return GENERATED + bench


class Progress:
    """Frames done over all scenes, with an ETA from the rate so far."""

    def __init__(self, scenes):
        self.scenes, self.finished_scenes, self.start = scenes, 0, time.time()
        self.tty, self.last = sys.stdout.isatty(), 0.0

    def update(self, done, total):
        # Every scene renders about the same number of frames; heavier ones take longer per frame.
        all_done = self.finished_scenes * total + done
        all_total = self.scenes * total
        elapsed = time.time() - self.start
        eta = elapsed / all_done * (all_total - all_done) if all_done else 0.0
        text = f"  frames {all_done}/{all_total}  elapsed {elapsed / 60:5.1f} min  ETA {eta / 60:5.1f} min (rendering)"
        if self.tty:
            sys.stdout.write("\r" + text + " ")
        elif time.time() - self.last > 30 or done == total:  # a log: a line every 30 s
            self.last = time.time()
            sys.stdout.write(text + "\n")
        sys.stdout.flush()


def run_sweep(a, scene, out, progress):
    w, h = a.size.split("x")
    cmd = [a.raybudget, "sweep", str(scene), "--out", str(out), "--width", w, "--height", h, "--frames", str(a.frames),
           "--warmup", str(a.warmup), "--budgets", str(a.budgets), "--repeats", str(a.repeats), "--policies", a.policies,
           "--paths", a.paths, "--order-seed", str(a.order_seed)]
    if a.lead_in:  # only where > 0: builds before the option refuse it (--raybudget OLD --lead-in 0)
        cmd += ["--lead-in", str(a.lead_in)]
    if a.validation:
        cmd.append("--validation")
    if a.prior_time_scale:
        cmd.append("--prior-time-scale")
    if a.no_temporal_fill:
        cmd.append("--no-temporal-fill")
    if a.no_screen_space_transmission:
        cmd.append("--no-screen-space-transmission")
    if a.no_reflection_probes:
        cmd.append("--no-reflection-probes")
    if a.no_screen_space_reflections:
        cmd.append("--no-screen-space-reflections")
    if a.budget_list:
        cmd += ["--budget-list", a.budget_list]
    if a.budget_confidence:
        cmd += ["--budget-confidence", a.budget_confidence]
    if a.no_stage_deadline:
        cmd.append("--no-stage-deadline")
    log = []
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    for line in proc.stdout:
        if line.startswith("progress "):
            done, total = map(int, line.split()[1:3])
            progress.update(done, total)
        else:
            log.append(line.rstrip())
    proc.wait()
    print()
    for line in log:
        print("  " + line)
    return proc.returncode


def reference_image(base_dir, image):
    """The reference frame of an imaged frame: images/PATH/LABEL/rK/F.png -> images/PATH/reference/F.png."""
    p = pathlib.Path(image)
    return base_dir / p.parents[2] / "reference" / p.name


def score_flip(out_dir, rows):
    """FLIP (LDR, display images) of every imaged frame against the path's reference frame
    (flip-evaluator already uses every core)."""
    import flip_evaluator as flip
    for r in rows:
        if not r["image"]:
            r["flip"] = ""
            continue
        _, err, _ = flip.evaluate(str(reference_image(out_dir, r["image"])), str(out_dir / r["image"]), "LDR", applyMagma=False)
        r["flip"] = f"{err:.6g}"


def oracle_bound(out_dir, scene, rows):
    """Per path: the FLIP of composites that take the reference's pixels where `none` is most
    wrong (the top 10/25/50% of its per-pixel FLIP) and `none`'s elsewhere, averaged over
    the frames. What a selector that knew the reference could reach at a cost proportional to
    pixels."""
    import flip_evaluator as flip
    import numpy as np
    out = []
    for path in sorted({r["path"] for r in rows}):
        none = sorted((r for r in rows if r["path"] == path and r["policy"] == "none" and r["repeat"] == "0" and r["image"]),
                      key=lambda r: int(r["frame"]))
        per_fraction = {f: [] for f in FRACTIONS}
        for r in none:
            ref = flip.load(str(reference_image(out_dir, r["image"])))
            test = flip.load(str(out_dir / r["image"]))
            errmap, _, _ = flip.evaluate(ref, test, "LDR", applyMagma=False)
            order = np.argsort(-errmap.reshape(-1), kind="stable")
            for f in FRACTIONS:
                composite = test.reshape(-1, test.shape[-1]).copy()
                top = order[: int(round(f * order.size))]
                composite[top] = ref.reshape(-1, ref.shape[-1])[top]
                _, err, _ = flip.evaluate(ref, composite.reshape(test.shape), "LDR", applyMagma=False)
                per_fraction[f].append(err)
        for f in FRACTIONS:
            out.append({"scene": scene, "path": path, "fraction": f, "flip": mean(per_fraction[f])})
    return out


def num(x):
    return float(x) if x not in ("", None) else math.nan


def median(v):
    """The median (the mean of the two middle values for an even count); nan when empty."""
    v = sorted(x for x in v if not math.isnan(x))
    if not v:
        return math.nan
    k = len(v) // 2
    return v[k] if len(v) % 2 else 0.5 * (v[k - 1] + v[k])


def mean(v):
    v = [x for x in v if not math.isnan(x) and not math.isinf(x)]
    return sum(v) / len(v) if v else math.nan


def spread(v):
    """(median, min, max) over the values that are numbers."""
    v = [x for x in v if not math.isnan(x)]
    return (median(v), min(v), max(v)) if v else (math.nan, math.nan, math.nan)


# What a recorded frame follows: the still warm-up on its camera (the first), a jump from the
# frame before (a cut), or frames of the camera moving along the path to it (its `lead_in`).
FRAME_KIND_LABELS = {"still": "the first recorded frame (after the still warm-up)", "jumps": "after a camera jump",
                     "moving": "after the camera moved along the path"}


def frame_kinds(points):
    """The recorded frames' ids of each kind present: still, jumps, moving (runs before the
    lead-in had no `lead_in` column: their later frames all follow a jump)."""
    ids = {x["frame"] for q in points for x in q["frames"]}
    moving = {x["frame"] for q in points for x in q["frames"] if num(x.get("lead_in") or "0") > 0}
    kinds = {"still": sorted((ids & {"0"}) - moving), "jumps": sorted(ids - {"0"} - moving), "moving": sorted(moving)}
    return {k: v for k, v in kinds.items() if v}


def stage_budget_frames(rows):
    """Frames whose candidates' predicted stage time (their summed trace cost plus the
    stage's overhead the selection took off T) exceeds T: the budget binds, so it should be used."""
    return [r for r in rows if num(r["candidates_ms"]) > num(r["trace_budget_ms"])]


def repeat_points(rows):
    """One point per scene/path/policy/budget/repeat: each repeat's means over its frames."""
    groups = {}
    for r in rows:
        groups.setdefault((r["scene"], r["path"], r["policy"], int(r["budget_index"]), int(r["repeat"])), []).append(r)
    points = []
    for (scene, path, policy, b, rep), g in sorted(groups.items()):
        budget = num(g[0]["budget_ms"])
        points.append({
            "scene": scene, "path": path, "policy": policy, "budget_index": b, "repeat": rep, "budget_ms": budget,
            "rt_stage_ms": mean([num(r["rt_stage_ms"]) for r in g]), "trace_ms": mean([num(r["trace_ms"]) for r in g]),
            "frame_ms": mean([num(r["frame_ms"]) for r in g]), "shadow_maps_ms": mean([num(r["shadow_maps_ms"]) for r in g]),
            "flip": mean([num(r["flip"]) for r in g]), "rmse": mean([num(r["rmse"]) for r in g]),
            "frames": g,
        })
    return points


def summarize(points):
    """One row per scene/path/policy/budget: median over repeats with min and max."""
    groups = {}
    for p in points:
        groups.setdefault((p["scene"], p["path"], p["policy"], p["budget_index"]), []).append(p)
    out = []
    for (scene, path, policy, b), g in sorted(groups.items()):
        frames = [r for p in g for r in p["frames"]]
        budget = g[0]["budget_ms"]
        row = {"scene": scene, "path": path, "policy": policy, "budget_index": b, "budget_ms": budget, "repeats": len(g)}
        for key in ("rt_stage_ms", "flip"):
            row[key], row[key + "_min"], row[key + "_max"] = spread([p[key] for p in g])
        for key in ("trace_ms", "frame_ms", "shadow_maps_ms", "rmse"):
            row[key] = median([p[key] for p in g])
        budgeted = budget > 0
        row["within_T+5%"] = mean([float(num(r["rt_stage_ms"]) <= ADHERENCE_SLACK * budget) for r in frames]) if budgeted else math.nan
        binding = stage_budget_frames(frames) if budgeted else []
        row["binding_frames"] = len(binding)
        row["budget_use"] = median([num(r["rt_stage_ms"]) / budget for r in binding]) if binding else math.nan
        row["objects"] = mean([num(r["selected_objects"]) for r in frames])
        row["rays"] = mean([num(r["rays"]) for r in frames])
        # Frames with `benefit`'s partial item left out: its share is a fraction of an option,
        # which the 0/1 bound does not offer (older runs have no such column).
        ratios = [num(r["selected_value"]) / num(r["optimal_value_bound"]) for r in frames
                  if num(r["optimal_value_bound"]) > 0 and not num(r.get("partial_share", "0")) > 0]
        row["value_over_bound"] = mean(ratios) if ratios else math.nan
        row["changes_per_frame"] = mean([num(r["selection_changes"]) for r in frames])
        # Items changing option (left out, or a rate) per frame: `benefit`'s flicker (older runs: none).
        row["option_changes_per_frame"] = mean([num(r.get("item_option_changes", "nan")) for r in frames])
        out.append(row)
    return out


def write_csv(path, rows, fields=None):
    fields = fields or list(rows[0].keys())
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})


# --- The aggregations (docs/BENCHMARKS.md defines them) -----------------------------------

def curve(points, case, policy, repeat, none_flip):
    """A policy's measured (stage ms, FLIP) points of one repeat, sorted by cost, with `none`
    at cost 0: below its cheapest budget a budgeted renderer traces nothing."""
    pts = [(p["rt_stage_ms"], p["flip"]) for p in points
           if (p["scene"], p["path"], p["policy"], p["repeat"]) == (*case, policy, repeat) and not math.isnan(p["flip"])]
    return [(0.0, none_flip)] + sorted(pts)


def error_at_cost(pts, cost):
    """The error at `cost`: interpolated in log cost between the measured points around it
    when they are no further apart than a factor 2, else the last measured point at or below it."""
    below = [p for p in pts if p[0] <= cost]
    above = [p for p in pts if p[0] > cost]
    c0, e0 = below[-1]
    if above and c0 > 0 and above[0][0] <= 2 * c0:
        c1, e1 = above[0]
        return e0 + (e1 - e0) * (math.log(cost) - math.log(c0)) / (math.log(c1) - math.log(c0))
    return e0


def recovered(e, none_flip, all_flip):
    gap = none_flip - all_flip
    return (none_flip - e) / gap if gap > 1e-9 else math.nan


def cost_at_error(pts, target):
    """The cost where the curve first reaches `target`, interpolated linearly between the two
    measured points around the crossing; nan when it never does."""
    for (c0, e0), (c1, e1) in zip(pts, pts[1:]):
        if e0 > target >= e1:
            return c0 + (c1 - c0) * (e0 - target) / (e0 - e1)
    return math.nan


class Cases:
    """Per scene/path: `all`'s stage cost and FLIP, `none`'s FLIP, per repeat and as medians."""

    def __init__(self, points):
        self.points = points
        self.list = sorted({(p["scene"], p["path"]) for p in points})
        self.repeats = sorted({p["repeat"] for p in points})

    def of(self, case, policy):
        return [p for p in self.points if (p["scene"], p["path"], p["policy"]) == (*case, policy)]

    def value(self, case, policy, key):
        return median([p[key] for p in self.of(case, policy)])

    def none_flip(self, case, repeat):
        return next((p["flip"] for p in self.of(case, "none") if p["repeat"] == repeat), math.nan)

    def all_flip(self, case, repeat):
        return next((p["flip"] for p in self.of(case, "all") if p["repeat"] == repeat), math.nan)

    def full_cost(self, case):
        return self.value(case, "all", "rt_stage_ms")

    def recovered_at(self, case, policy, repeat, fraction):
        n, a = self.none_flip(case, repeat), self.all_flip(case, repeat)
        pts = curve(self.points, case, policy, repeat, n)
        return recovered(error_at_cost(pts, fraction * self.full_cost(case)), n, a)

    def frames_of(self, case, policy, repeat, frame):
        """A policy's recorded frame `frame` of one repeat, at each of its budgets."""
        return [x for q in self.of(case, policy) if q["repeat"] == repeat for x in q["frames"] if x["frame"] == frame]

    def recovered_in_frame(self, case, policy, repeat, frame, fraction):
        """recovered_at over one recorded frame alone: its points, and `none`'s and `all`'s FLIP in
        it; nan where the fallback's error there is under FRAME_GAP."""
        flip = lambda p: median([num(x["flip"]) for x in self.frames_of(case, p, repeat, frame)])
        n, a = flip("none"), flip("all")
        if not n - a > FRAME_GAP:
            return math.nan
        pts = sorted((num(x["rt_stage_ms"]), num(x["flip"])) for x in self.frames_of(case, policy, repeat, frame)
                     if not math.isnan(num(x["flip"])))
        return recovered(error_at_cost([(0.0, n)] + pts, fraction * self.full_cost(case)), n, a)

    def half_gap_cost(self, case, policy, repeat, left=0.5):
        """The cost where the policy's curve first leaves `left` of `none`'s error gap (0.5: halves
        it; nan: never)."""
        n, a = self.none_flip(case, repeat), self.all_flip(case, repeat)
        return cost_at_error(curve(self.points, case, policy, repeat, n), a + left * (n - a))

    def speedup(self, case, policy, repeat, left=0.5):
        """Equal error: full RT's stage cost over the cost of leaving `left` of the gap; 1.0 (full
        RT) when never reached."""
        c = self.half_gap_cost(case, policy, repeat, left)
        return self.full_cost(case) / c if c and not math.isnan(c) and c > 0 else 1.0

    def reached(self, case, policy, repeat, left=0.5):
        return not math.isnan(self.half_gap_cost(case, policy, repeat, left))


def fmt_spread(s, digits=2, suffix=""):
    m, lo, hi = s
    if math.isnan(m):
        return "n/a"
    if abs(hi - lo) < 0.5 * 10 ** -digits:
        return f"{m:.{digits}f}{suffix}"
    return f"{m:.{digits}f}{suffix} ({lo:.{digits}f}-{hi:.{digits}f})"


def headline(points, summary, oracle, calibration, policies):
    """The headline figures and their tables. Returns (markdown, figures as a dict)."""
    cases = Cases(points)
    figures = {"recovered": {}, "speedup": {}, "adherence": {}, "budget_use": {}, "oracle": {}}
    lines = []
    orc = {(o["scene"], o["path"], o["fraction"]): o["flip"] for o in oracle}

    def oracle_recovered(case, fraction):
        n, a = cases.value(case, "none", "flip"), cases.value(case, "all", "flip")
        return recovered(orc.get((*case, fraction), math.nan), n, a)

    # 1. Error recovered at a fraction of full RT's stage cost: median over cases, per repeat.
    lines.append("### Error recovered at a fraction of full RT's ray-tracing stage cost (median over cases; "
                 "range over repeats)\n")
    lines.append("| at | oracle | " + " | ".join(policies) + " |")
    lines.append("|---|---|" + "---|" * len(policies))
    for f in FRACTIONS:
        o = median([oracle_recovered(c, f) for c in cases.list])
        figures["oracle"][f"{f:.2f}"] = o
        cells = []
        for p in policies:
            per_repeat = [median([cases.recovered_at(c, p, r, f) for c in cases.list]) for r in cases.repeats]
            s = spread(per_repeat)
            figures["recovered"].setdefault(p, {})[f"{f:.2f}"] = list(s)
            cells.append(fmt_spread(s, 3) + (f", {s[0] / o:.0%} of oracle" if o and not math.isnan(o) and o > 0 else ""))
        lines.append(f"| {f:.0%} | {o:.3f} | " + " | ".join(cells) + " |")
    # 1a. The same per recorded frame: the first follows the warm-up on its camera, over which
    # the temporal fill carried what each reduced rate traced; the others follow a camera jump,
    # or the camera moving along the path (--lead-in).
    kinds = frame_kinds(points)
    lines.append(f"\n### Error recovered at {' / '.join(f'{f:.0%}' for f in FRACTIONS)} of full RT's stage cost, by recorded frame "
                 f"(median over the cases whose `none` FLIP exceeds `all`'s by {FRAME_GAP} in that frame; range over repeats)\n")
    lines.append("| policy | " + " | ".join(FRAME_KIND_LABELS[k] for k in kinds) + " |")
    lines.append("|---|" + "---|" * len(kinds))
    for p in policies:
        cells = []
        for name, frames in kinds.items():
            per_fraction = [spread([median([cases.recovered_in_frame(c, p, r, fr, f) for c in cases.list for fr in frames])
                                    for r in cases.repeats]) for f in FRACTIONS]
            figures.setdefault("recovered_by_frame", {}).setdefault(p, {})[name] = [list(s) for s in per_fraction]
            cells.append(" / ".join(fmt_spread(s, 3) for s in per_fraction))
        lines.append(f"| {p} | " + " | ".join(cells) + " |")
    # 1b. The classifier alone: every item traced, shadow rays only where the map is uncertain.
    if any(p["policy"] == "classified" for p in points):
        lines.append("\n### `classified`: every item traced, shadow rays only where the shadow map is uncertain "
                     "(median over cases; range over repeats)\n")
        lines.append("| stage cost / full RT's | error recovered |")
        lines.append("|---|---|")
        cost, rec = [], []
        for r in cases.repeats:
            per_case = [(q["rt_stage_ms"] / cases.full_cost(c), recovered(q["flip"], cases.none_flip(c, r), cases.all_flip(c, r)))
                        for c in cases.list for q in cases.of(c, "classified") if q["repeat"] == r]
            cost.append(median([x for x, _ in per_case]))
            rec.append(median([y for _, y in per_case]))
        figures["classified"] = {"cost": list(spread(cost)), "recovered": list(spread(rec))}
        lines.append(f"| {fmt_spread(spread(cost), 3)} | {fmt_spread(spread(rec), 3)} |")
    # 2. Equal error.
    lines.append("\n### Speed-up over full RT at half and at a quarter of the fallback's error gap (median over cases, "
                 "not reached = 1.0x; range over repeats)\n")
    lines.append("| | " + " | ".join(policies) + " |")
    lines.append("|---|" + "---|" * len(policies))
    for left, label in ((0.5, "half the gap left"), (0.25, "a quarter left")):
        cells = []
        for p in policies:
            per_repeat = [median([cases.speedup(c, p, r, left) for c in cases.list]) for r in cases.repeats]
            reached = [sum(cases.reached(c, p, r, left) for c in cases.list) for r in cases.repeats]
            s = spread(per_repeat)
            figures.setdefault("speedup" if left == 0.5 else "speedup_quarter", {})[p] = list(s)
            cells.append(fmt_spread(s, 2, "x") + f", reached in {min(reached)}-{max(reached)} of {len(cases.list)}")
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
    # Where the fallback is visibly wrong (none's FLIP over 0.005): the share of cases where
    # half the gap is reached at least 4x faster than full RT.
    visible = [c for c in cases.list if cases.value(c, "none", "flip") > 0.005]
    if visible:
        cells = []
        for p in policies:
            shares = [sum(cases.speedup(c, p, r) >= 4.0 for c in visible) / len(visible) for r in cases.repeats]
            figures.setdefault("speedup4_share", {})[p] = list(spread(shares))
            cells.append(fmt_spread(spread(shares), 2))
        lines.append(f"| share of the {len(visible)} cases with `none` FLIP > 0.005 at 4x or more (half left) | " + " | ".join(cells) + " |")
    # 3. Two-sided adherence.
    # The first recorded frame of a path follows the warm-up on the same camera (the steady
    # case); the others a jump along the path (a view new to the learned costs) or the camera
    # moving along it (--lead-in).
    # The promise covers T from twice the stage's fixed cost t0 (the case's calibrated one) up:
    # below it the fixed passes alone are most of T.
    lines.append("\n### Budget adherence, both sides (range over repeats)\n")
    lines.append("| policy | frames with stage <= T + 5% | of them at T >= 2 t0 | "
                 + " | ".join(FRAME_KIND_LABELS[k] for k in kinds) + " | budget use: median stage / T where the candidates exceed T |")
    lines.append("|---|---|---|" + "---|" * len(kinds) + "---|")
    for p in policies:
        within, ranged, by_kind, use = [], [], {k: [] for k in kinds}, []
        for r in cases.repeats:
            frames = [x for q in points if q["policy"] == p and q["repeat"] == r for x in q["frames"]]
            held = lambda fs: mean([float(num(x["rt_stage_ms"]) <= ADHERENCE_SLACK * num(x["budget_ms"])) for x in fs])
            within.append(held(frames))
            ranged.append(held([x for x in frames if num(x["budget_ms"]) >= 2.0 * calibration.get((x["scene"], x["path"]), 0.0)]))
            for k, ids in kinds.items():
                by_kind[k].append(held([x for x in frames if x["frame"] in ids]))
            use.append(median([num(x["rt_stage_ms"]) / num(x["budget_ms"]) for x in stage_budget_frames(frames)]))
        figures["adherence"][p], figures["budget_use"][p] = list(spread(within)), list(spread(use))
        figures.setdefault("adherence_from_2t0", {})[p] = list(spread(ranged))
        for k in kinds:
            figures.setdefault(f"adherence_{k}", {})[p] = list(spread(by_kind[k]))
        lines.append(f"| {p} | {fmt_spread(spread(within), 3)} | {fmt_spread(spread(ranged), 3)} | "
                     + " | ".join(fmt_spread(spread(by_kind[k]), 3) for k in kinds) + " "
                     f"| {fmt_spread(spread(use), 2)} |")
    # 4. Per case at 25%, with the stage's cost and its fixed part.
    lines.append("\n### Per case: error recovered at 25% of full RT's stage cost (median over repeats)\n")
    lines.append("| scene | path | full-RT stage ms (range) | fixed stage ms (share) | none FLIP | oracle | "
                 + " | ".join(policies) + " |")
    lines.append("|---|---|---|---|---|---|" + "---|" * len(policies))
    for c in cases.list:
        full = spread([p["rt_stage_ms"] for p in cases.of(c, "all")])
        fixed = calibration.get(c, math.nan)
        cells = [f"{median([cases.recovered_at(c, p, r, 0.25) for r in cases.repeats]):.3f}" for p in policies]
        lines.append(f"| {c[0]} | {c[1]} | {fmt_spread(full, 2)} | {fixed:.2f} ({fixed / full[0]:.0%}) | "
                     f"{cases.value(c, 'none', 'flip'):.4f} | {oracle_recovered(c, 0.25):.3f} | " + " | ".join(cells) + " |")
    # 5. Per case, equal error.
    lines.append("\n### Per case: speed-up over full RT at half of the fallback's error (median over repeats; "
                 "- : not reached in any repeat)\n")
    lines.append("| scene | path | " + " | ".join(policies) + " |")
    lines.append("|---|---|" + "---|" * len(policies))
    for c in cases.list:
        cells = []
        for p in policies:
            s = median([cases.speedup(c, p, r) for r in cases.repeats])
            cells.append(f"{s:.2f}x" if any(cases.reached(c, p, r) for r in cases.repeats) else "-")
        lines.append(f"| {c[0]} | {c[1]} | " + " | ".join(cells) + " |")
    # 6. Frame time, with the fallbacks kept or skipped.
    lines.append("\n### Frame time and the shadow-map fallback: whole-frame GPU ms (shadow-map pass ms; - : skipped), "
                 "policies at the budget nearest 25% of full RT's stage cost\n")
    lines.append("| scene | path | none | all | " + " | ".join(policies) + " |")
    lines.append("|---|---|---|---|" + "---|" * len(policies))
    for c in cases.list:
        def cell(rows):
            if not rows:
                return "n/a"
            sm = median([r["shadow_maps_ms"] for r in rows])
            return f"{median([r['frame_ms'] for r in rows]):.1f} ({'-' if math.isnan(sm) else f'{sm:.1f}'})"
        cells = [cell(cases.of(c, "none")), cell(cases.of(c, "all"))]
        for p in policies:
            rows = [s for s in summary if (s["scene"], s["path"], s["policy"]) == (*c, p)]
            target = 0.25 * cases.full_cost(c)
            b = min(rows, key=lambda s: abs(s["budget_ms"] - target))["budget_index"] if rows else None
            cells.append(cell([q for q in cases.of(c, p) if q["budget_index"] == b]))
        lines.append(f"| {c[0]} | {c[1]} | " + " | ".join(cells) + " |")
    # 7. Value against the knapsack bound and flicker.
    lines.append("\n### Selected value against the 0/1-knapsack bound and flicker (all budgets)\n")
    lines.append("| policy | ΣR / bound (mean) | objects selected or dropped per frame | items changing option per frame |")
    lines.append("|---|---|---|---|")
    for p in policies:
        g = [s for s in summary if s["policy"] == p]
        options = mean([s["option_changes_per_frame"] for s in g]) if p.startswith("benefit") else math.nan
        lines.append(f"| {p} | {mean([s['value_over_bound'] for s in g]):.3f} | {mean([s['changes_per_frame'] for s in g]):.2f} | "
                     + ("-" if math.isnan(options) else f"{options:.2f}") + " |")
    return "\n".join(lines) + "\n", figures


def compare(a_fig, b_fig):
    """The headline figures of two runs side by side (run-to-run spread)."""
    lines = ["| figure | policy | this run | other run |", "|---|---|---|---|"]

    def m(x):
        return f"{x[0]:.3f}" if isinstance(x, list) else f"{x:.3f}"
    for key in ("recovered", "speedup", "adherence", "adherence_from_2t0", "budget_use"):
        for p, v in a_fig[key].items():
            w = b_fig.get(key, {}).get(p)
            if isinstance(v, dict):
                for f, x in v.items():
                    y = w.get(f) if w else None
                    lines.append(f"| {key} at {float(f):.0%} | {p} | {m(x)} | {m(y) if y else 'n/a'} |")
            else:
                lines.append(f"| {key} | {p} | {m(v)} | {m(w) if w else 'n/a'} |")
    for f, x in a_fig["oracle"].items():
        y = b_fig.get("oracle", {}).get(f)
        lines.append(f"| oracle at {float(f):.0%} | | {m(x)} | {m(y) if y is not None else 'n/a'} |")
    return "\n".join(lines) + "\n"


def case_spread(a_points, b_points, policies):
    """Per case (scene and path), the two runs' figures compared: per policy, the median and
    the largest difference over the cases both ran, of error recovered at 25% and 50% and
    of the equal-error speed-up (each run's median over its repeats)."""
    a_cases, b_cases = Cases(a_points), Cases(b_points)
    common = [c for c in a_cases.list if c in b_cases.list]

    def figure(cases, c, p, what):
        if what == "speedup":
            return median([cases.speedup(c, p, r) for r in cases.repeats])
        return median([cases.recovered_at(c, p, r, what) for r in cases.repeats])
    lines = [f"Per-case differences between the runs over the {len(common)} cases both ran (median / largest):\n",
             "| policy | recovered at 25% | recovered at 50% | speed-up at half gap |", "|---|---|---|---|"]
    for p in policies:
        cells = []
        for what in (0.25, 0.5, "speedup"):
            d = [abs(figure(a_cases, c, p, what) - figure(b_cases, c, p, what)) for c in common]
            d = [x for x in d if not math.isnan(x)]
            cells.append(f"{median(d):.3f} / {max(d):.3f}" if d else "n/a")
        lines.append(f"| {p} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


# --- Plots and strips ------------------------------------------------------------------------

def label(ax, xlabel, ylabel, title):
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)


def save(plt, fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def plots(out_dir, summary, oracle, policies):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plot_dir = out_dir / "plots"
    plot_dir.mkdir(exist_ok=True)
    cases = sorted({(s["scene"], s["path"]) for s in summary})
    for scene in sorted({c[0] for c in cases}):
        paths = [c[1] for c in cases if c[0] == scene]
        fig, axes = plt.subplots(1, len(paths), figsize=(5.5 * len(paths), 4), squeeze=False)
        for ax, path in zip(axes[0], paths):
            rows = [s for s in summary if (s["scene"], s["path"]) == (scene, path)]
            full = next((s for s in rows if s["policy"] == "all"), None)
            for p in policies:
                pts = sorted((s for s in rows if s["policy"] == p), key=lambda s: s["rt_stage_ms"])
                if pts:
                    x = [s["rt_stage_ms"] for s in pts]
                    y = [s["flip"] for s in pts]
                    xerr = [[s["rt_stage_ms"] - s["rt_stage_ms_min"] for s in pts], [s["rt_stage_ms_max"] - s["rt_stage_ms"] for s in pts]]
                    yerr = [[s["flip"] - s["flip_min"] for s in pts], [s["flip_max"] - s["flip"] for s in pts]]
                    ax.errorbar(x, y, xerr=xerr, yerr=yerr, fmt="o-", color=COLORS.get(p), label=p, ms=4, capsize=2)
            for p in ("none", "all", "classified"):
                s = next((s for s in rows if s["policy"] == p), None)
                if s:
                    ax.plot([max(s["rt_stage_ms"], 1e-2)], [s["flip"]], "s", color=COLORS[p], label=p, ms=7)
            if full:
                o = [(f * full["rt_stage_ms"], x["flip"]) for f in FRACTIONS for x in oracle
                     if (x["scene"], x["path"], x["fraction"]) == (scene, path, f)]
                if o:
                    ax.plot([t for t, _ in o], [e for _, e in o], "x--", color=COLORS["oracle"], label="oracle (pixels)")
            ax.set_xscale("log")
            label(ax, "ray-tracing stage GPU ms per frame (coverage + select + trace, log)", "mean FLIP against full RT", f"{scene}: {path}")
        save(plt, fig, plot_dir / f"error_vs_time_{scene}.png")
    # Adherence and budget use per policy against the budget index, over all scenes.
    for key, ylabel, name in (("within_T+5%", "frames with stage <= T + 5%", "adherence"),
                              ("budget_use", "median stage / T where the candidates exceed T", "budget_use"),
                              ("changes_per_frame", "selection changes per frame", "flicker")):
        fig, ax = plt.subplots(figsize=(6, 4))
        for p in policies:
            by_b = {}
            for s in summary:
                if s["policy"] == p:
                    by_b.setdefault(s["budget_index"], []).append(s[key])
            bs = sorted(by_b)
            ax.plot(bs, [mean(by_b[b]) for b in bs], "o-", color=COLORS.get(p), label=p)
        label(ax, "budget point (0 = twice the stage's fixed cost ... last = full RT)", ylabel, f"{name}, mean over scenes and paths")
        save(plt, fig, plot_dir / f"{name}.png")


def strips(out_dir, rows, summary):
    """Reference / hybrid (density, the budget nearest 25% of full RT) / fallback only / FLIP
    error map, for the first frame of each scene's first path, repeat 0."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import flip_evaluator as flip
    strip_dir = out_dir / "strips"
    strip_dir.mkdir(exist_ok=True)
    for scene in sorted({r["scene"] for r in rows}):
        imaged = [r for r in rows if r["scene"] == scene and r["image"] and r["frame"] == "0" and r["repeat"] == "0"]
        if not imaged:
            continue
        path = imaged[0]["path"]
        imaged = [r for r in imaged if r["path"] == path]
        full = next((s for s in summary if (s["scene"], s["path"], s["policy"]) == (scene, path, "all")), None)
        dens = [s for s in summary if (s["scene"], s["path"], s["policy"]) == (scene, path, "density")]
        fallback = next((r for r in imaged if r["policy"] == "none"), None)
        if not (full and dens and fallback):
            continue
        b = min(dens, key=lambda s: abs(s["budget_ms"] - 0.25 * full["rt_stage_ms"]))["budget_index"]
        hybrid = next((r for r in imaged if r["policy"] == "density" and int(r["budget_index"]) == b), None)
        if not hybrid:
            continue
        ref_path = str(reference_image(out_dir, hybrid["image"]))
        images = [flip.load(p) for p in (ref_path, str(out_dir / hybrid["image"]), str(out_dir / fallback["image"]))]
        errmap, _, _ = flip.evaluate(ref_path, str(out_dir / hybrid["image"]), "LDR")
        titles = ["reference (all)", f"hybrid (density, T = {num(hybrid['budget_ms']):.2f} ms)", "fallback only (none)",
                  f"FLIP hybrid vs reference ({num(hybrid['flip']):.4f})"]
        fig, axes = plt.subplots(1, 4, figsize=(16, 2.6))
        for ax, img, title in zip(axes, images + [errmap], titles):
            ax.imshow(img.clip(0, 1))
            ax.set_title(title, fontsize=9)
            ax.axis("off")
        save(plt, fig, strip_dir / f"{scene}.png")


def read_calibration(sdir, scene):
    with open(sdir / "calibration.csv") as f:
        return {(scene, r["path"]): num(r["fixed_stage_ms"]) for r in csv.DictReader(f)}


def read_rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def sweep_scenes(a, scenes, out_dir):
    """Runs and scores every scene's sweep. Returns (frame rows, oracle rows, calibration, failed scenes)."""
    progress = Progress(len(scenes))
    rows, oracle, calibration, skipped = [], [], {}, []
    for scene in scenes:
        name = scene.stem
        print(f"{name}:")
        sdir = out_dir / "raw" / name
        done = sdir / "sweep.ok"
        rc = 0 if a.resume and done.is_file() else run_sweep(a, scene, sdir, progress)
        if rc == 0:
            done.touch()
        progress.finished_scenes += 1
        if rc != 0:
            skipped.append((name, rc))
            print(f"  {name}: sweep failed (exit {rc}); scene left out of the tables, listed in headline.md")
            continue
        with open(sdir / "frames.csv") as f:
            srows = list(csv.DictReader(f))
        scoring = time.time()
        score_flip(sdir, srows)
        oracle += oracle_bound(sdir, name, srows)
        calibration.update(read_calibration(sdir, name))
        print(f"  scored {sum(1 for r in srows if r['image'])} frames with FLIP in {time.time() - scoring:.0f} s")
        for r in srows:
            r["image"] = f"raw/{name}/{r['image']}" if r["image"] else ""
        rows += srows
    return rows, oracle, calibration, skipped


def main(argv):
    a = parse_args(argv)
    out_dir = pathlib.Path(a.out)
    out_dir.mkdir(parents=True, exist_ok=True)
    scenes = [pathlib.Path(s) for s in a.scenes] if a.scenes else default_scenes(a.quick)
    policies = [p for p in a.policies.split(",") if p]
    started = time.time()
    if a.compare and not (pathlib.Path(a.compare) / "headline.json").is_file():  # before an hour of sweeps, not after
        print(f"run.py: --compare {a.compare}: no headline.json there", file=sys.stderr)
        return 2
    if a.aggregate_only:
        rows = read_rows(out_dir / "frames.csv")
        oracle = [dict(r, fraction=num(r["fraction"]), flip=num(r["flip"])) for r in read_rows(out_dir / "oracle.csv")]
        calibration, skipped = {}, []
        for sdir in sorted((out_dir / "raw").iterdir()):
            calibration.update(read_calibration(sdir, sdir.name))
        scenes = sorted({r["scene"] for r in rows})
    else:
        print(f"run.py: {len(scenes)} scenes x {a.paths} x policies {policies} x {a.budgets} budgets x {a.repeats} repeats, "
              f"{a.frames} frames (+{a.warmup} warm-up per configuration{lead_in_text(a)}) at {a.size}, order seed {a.order_seed} -> {out_dir}")
        rows, oracle, calibration, skipped = sweep_scenes(a, scenes, out_dir)
        if not rows:
            print("run.py: no scene rendered", file=sys.stderr)
            return 1
        write_csv(out_dir / "frames.csv", rows, list(rows[0].keys()))
    # The tables show the policies the frames hold (an --aggregate-only of a run of a few
    # policies, without --policies, would else show empty columns for the others).
    present = {r["policy"] for r in rows}
    absent = [p for p in policies if p not in present]
    if absent:
        print(f"run.py: no frames of {', '.join(absent)} in {out_dir / 'frames.csv'}: left out of the tables")
    policies = [p for p in policies if p in present]
    points = repeat_points(rows)
    summary = summarize(points)
    write_csv(out_dir / "summary.csv", summary)
    write_csv(out_dir / "oracle.csv", oracle)
    text, figures = headline(points, summary, oracle, calibration, policies)
    minutes = (time.time() - started) / 60
    cmd = "bench/run.py " + " ".join(argv)
    preamble = (f"Command: `{cmd.strip()}`, {minutes:.1f} min, {len(scenes) - len(skipped)} scenes"
                + (f"; failed: {', '.join(f'{n} (exit {rc})' for n, rc in skipped)}" if skipped else "")
                + f"; {a.size}, {a.frames} frames per path after {a.warmup} warm-up{lead_in_text(a)}, {a.budgets} budgets, {a.repeats} repeats\n\n")
    if a.aggregate_only:  # the sweep's own command, time and settings
        with open(out_dir / "headline.json") as f:
            preamble = json.load(f)["preamble"]
    with open(out_dir / "headline.md", "w") as f:
        f.write(preamble + text)
    with open(out_dir / "headline.json", "w") as f:
        json.dump({"preamble": preamble, "figures": figures}, f, indent=1)
    plots(out_dir, summary, oracle, policies)
    strips(out_dir, rows, summary)
    if a.publish:
        pub = pathlib.Path(a.publish)
        pub.mkdir(parents=True, exist_ok=True)
        for name in ("summary.csv", "oracle.csv", "headline.md", "headline.json"):
            shutil.copy(out_dir / name, pub / name)
        for folder in ("plots", "strips"):
            shutil.copytree(out_dir / folder, pub / folder, dirs_exist_ok=True)
    print(preamble + text)
    if a.compare:
        other = pathlib.Path(a.compare)
        with open(other / "headline.json") as f:
            text = "Against " + a.compare + ":\n\n" + compare(figures, json.load(f)["figures"])
        if (other / "frames.csv").is_file():  # a published folder (docs/benchmarks) has the figures alone
            text += "\n" + case_spread(points, repeat_points(read_rows(other / "frames.csv")), policies)
        with open(out_dir / "compare.md", "w") as f:
            f.write(text)
        print(text)
    print(f"run.py: wrote {out_dir}/frames.csv, summary.csv, oracle.csv, headline.md, headline.json, plots/, strips/ in {minutes:.1f} min")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
