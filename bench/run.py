#!/usr/bin/env python3
"""Run time against error: drives `raybudget sweep` over the default scene and every scene
of ../shared/scenes/bench that loads, scores each frame with FLIP (NVIDIA's flip-evaluator)
against the full-RT reference, and writes results/<date>/: frames.csv, summary.csv,
headline.md, plots and image strips (the per-scene sweeps and their images under raw/).

usage: bench/run.py [--quick] [--out DIR] [--publish DIR] [--scenes FILE...]
                    [--policies LIST] [--budgets N] [--frames N] [--warmup N]
                    [--repeats N] [--size WxH] [--paths LIST] [--validation]

Needs numpy, matplotlib and flip-evaluator (scripts/bench-deps.sh makes .venv-bench).
"""
import argparse
import csv
import datetime
import math
import os
import pathlib
import shutil
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent
BENCH_SCENES = ROOT.parent / "shared" / "scenes" / "bench"
POLICIES = ["paper", "density", "nearest", "random"]
COLORS = {"paper": "tab:orange", "density": "tab:blue", "nearest": "tab:green", "random": "tab:purple", "none": "black", "all": "tab:red"}


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--quick", action="store_true", help="the default scene and one bench scene, fewer frames and budgets (under 5 minutes)")
    p.add_argument("--out", help="output folder (default results/<date>)")
    p.add_argument("--scenes", nargs="+", help="scene files (default: data/default/court.gltf and every bench scene)")
    p.add_argument("--policies", default=",".join(POLICIES))
    p.add_argument("--budgets", type=int)
    p.add_argument("--frames", type=int)
    p.add_argument("--warmup", type=int)
    p.add_argument("--repeats", type=int)
    p.add_argument("--size", default="320x180")
    p.add_argument("--paths", default="orbit,flythrough")
    p.add_argument("--raybudget", default=str(ROOT / "build" / "tools" / "raybudget"))
    p.add_argument("--validation", action="store_true")
    p.add_argument("--publish", help="also copy summary.csv, headline.md, plots/ and strips/ into this folder (docs/benchmarks)")
    a = p.parse_args(argv)
    full = dict(budgets=8, frames=6, warmup=3, repeats=3)
    quick = dict(budgets=6, frames=4, warmup=2, repeats=3)
    for k, v in (quick if a.quick else full).items():
        if getattr(a, k) is None:
            setattr(a, k, v)
    if a.out is None:
        a.out = str(ROOT / "results" / datetime.date.today().isoformat())
    return a


def bench_scenes():
    if not BENCH_SCENES.is_dir():
        print(f"run.py: {BENCH_SCENES} is absent: only the default scene is benchmarked", file=sys.stderr)
        return []
    found = []
    for d in sorted(BENCH_SCENES.iterdir()):
        files = sorted(list(d.glob("*.gltf")) + list(d.glob("*.glb")))
        if files:
            found.append(files[0])
    return found


def default_scenes(quick):
    scenes = [ROOT / "data" / "default" / "court.gltf"]
    bench = bench_scenes()
    if quick:
        bench = [s for s in bench if s.parent.name == "TransmissionTest"]
    return scenes + bench


class Progress:
    """Frames done over all scenes, with an ETA from the rate so far."""

    def __init__(self, scenes):
        self.scenes, self.finished_scenes, self.start = scenes, 0, time.time()
        self.tty, self.last = sys.stdout.isatty(), 0.0

    def update(self, done, total):
        # Every scene renders the same number of frames; heavier ones take longer per frame.
        all_done = self.finished_scenes * total + done
        all_total = self.scenes * total
        elapsed = time.time() - self.start
        eta = elapsed / all_done * (all_total - all_done) if all_done else 0.0
        text = f"  frames {all_done}/{all_total}  elapsed {elapsed / 60:5.1f} min  ETA {eta / 60:5.1f} min"
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
           "--paths", a.paths]
    if a.validation:
        cmd.append("--validation")
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


def score_flip(out_dir, rows):
    """FLIP (LDR, display images) of every imaged frame against the `all` frame of its path."""
    import flip_evaluator as flip
    for r in rows:
        if not r["image"]:
            r["flip"] = ""
            continue
        ref = out_dir / "images" / r["path"] / "all" / pathlib.Path(r["image"]).name
        _, mean, _ = flip.evaluate(str(ref), str(out_dir / r["image"]), "LDR", applyMagma=False)
        r["flip"] = f"{mean:.6g}"


def num(x):
    return float(x) if x not in ("", None) else math.nan


def median(v):
    v = sorted(x for x in v if not math.isnan(x))
    return v[len(v) // 2] if v else math.nan


def mean(v):
    v = [x for x in v if not math.isnan(x) and not math.isinf(x)]
    return sum(v) / len(v) if v else math.nan


def summarize(rows):
    """One row per scene/path/policy/budget: timings as the median over repeats of each
    repeat's mean; errors from the imaged repeat."""
    groups = {}
    for r in rows:
        groups.setdefault((r["scene"], r["path"], r["policy"], int(r["budget_index"])), []).append(r)
    out = []
    for (scene, path, policy, b), g in sorted(groups.items()):
        repeats = {}
        for r in g:
            repeats.setdefault(r["repeat"], []).append(r)
        budget = num(g[0]["budget_ms"])
        trace = median([mean([num(r["trace_ms"]) for r in rr]) for rr in repeats.values()])
        frame = median([mean([num(r["frame_ms"]) for r in rr]) for rr in repeats.values()])
        within = [num(r["trace_ms"]) <= budget * 1.2 for r in g] if budget > 0 else []
        over = [num(r["trace_ms"]) / budget for r in g] if budget > 0 else []
        ratio = [num(r["selected_value"]) / num(r["optimal_value_bound"]) for r in g if num(r["optimal_value_bound"]) > 0]
        imaged = [r for r in g if r["image"]]
        out.append({
            "scene": scene, "path": path, "policy": policy, "budget_index": b, "budget_ms": budget,
            "trace_ms": trace, "frame_ms": frame,
            "within_1.2T": sum(within) / len(within) if within else math.nan,
            "trace_over_T": median(over) if over else math.nan,
            "objects": mean([num(r["selected_objects"]) for r in g]), "rays": mean([num(r["rays"]) for r in g]),
            "value_over_bound": mean(ratio) if ratio else math.nan,
            "changes_per_frame": mean([num(r["selection_changes"]) for r in g]),
            "flip": mean([num(r["flip"]) for r in imaged]), "rmse": mean([num(r["rmse"]) for r in imaged]),
            "psnr": mean([num(r["psnr"]) for r in imaged]),
        })
    return out


def write_csv(path, rows, fields=None):
    fields = fields or list(rows[0].keys())
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})


def curve(summary, scene, path, policy):
    pts = [(s["trace_ms"], s["flip"]) for s in summary if (s["scene"], s["path"], s["policy"]) == (scene, path, policy)]
    return sorted(p for p in pts if not math.isnan(p[0]) and not math.isnan(p[1]))


def error_at(pts, t):
    """The policy's error at trace time t: interpolated in log time along its budget sweep
    (sorted by measured time); nan outside the measured range."""
    if not pts or t < pts[0][0] or t > pts[-1][0]:
        return math.nan
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if t0 <= t <= t1:
            if t1 - t0 < 1e-9:
                return min(e0, e1)
            k = (math.log(max(t, 1e-6)) - math.log(max(t0, 1e-6))) / (math.log(max(t1, 1e-6)) - math.log(max(t0, 1e-6)))
            return e0 + k * (e1 - e0)
    return pts[-1][1]


def equal_time_errors(summary, case, policies):
    """Each policy's mean FLIP over the trace times that any of them measured inside the
    range all of them cover (each curve interpolated in log time). None when a policy has
    no curve."""
    curves = {p: curve(summary, *case, p) for p in policies}
    if not all(curves.values()):
        return None, math.nan, math.nan, []
    lo, hi = max(v[0][0] for v in curves.values()), min(v[-1][0] for v in curves.values())
    times = sorted({t for v in curves.values() for t, _ in v if lo <= t <= hi})
    return [mean([error_at(curves[p], t) for t in times]) if times else math.nan for p in policies], lo, hi, times


def headline(summary, policies):
    """The figures the issue asks for, per scene/path and overall."""
    cases = sorted({(s["scene"], s["path"]) for s in summary})
    lines = []
    ref = {c: next((s for s in summary if (s["scene"], s["path"]) == c and s["policy"] == "all"), None) for c in cases}
    none = {c: next((s for s in summary if (s["scene"], s["path"]) == c and s["policy"] == "none"), None) for c in cases}
    # 1. At equal trace time: each policy's FLIP, interpolated along its measured sweep, at
    # every trace time any policy measured inside the range all of them cover.
    lines.append("### At equal trace time: mean FLIP at the trace times inside the range every policy covers\n")
    lines.append("| scene | path | common range ms | none | " + " | ".join(policies) + " |")
    lines.append("|---|---|---|---|" + "---|" * len(policies))
    agg = {p: [] for p in policies}
    for c in cases:
        cells, lo, hi, times = equal_time_errors(summary, c, policies)
        if cells is None:
            continue
        for p, m in zip(policies, cells):
            agg[p].append(m)
        n = none[c]["flip"] if none[c] else math.nan
        lines.append(f"| {c[0]} | {c[1]} | {lo:.2f}-{hi:.2f} ({len(times)} points) | {n:.4f} | " + " | ".join(f"{x:.4f}" for x in cells) + " |")
    lines.append("| **mean** | | | " + f"{mean([none[c]['flip'] for c in cases if none[c]]):.4f} | " +
                 " | ".join(f"**{mean(agg[p]):.4f}**" for p in policies) + " |\n")
    # 2. At equal error: trace time to remove half of the fallback's error, against full RT.
    lines.append("### At equal error: trace time to halve the raster fallback's FLIP, as a speed-up over full RT\n")
    lines.append("| scene | path | full RT ms | " + " | ".join(policies) + " |")
    lines.append("|---|---|---|" + "---|" * len(policies))
    speed = {p: [] for p in policies}
    for c in cases:
        if not ref[c] or not none[c]:
            continue
        target = 0.5 * none[c]["flip"]
        cells = []
        for p in policies:
            pts = curve(summary, *c, p)
            t = next((t for t, e in pts if e <= target), math.nan)
            s = ref[c]["trace_ms"] / t if t and not math.isnan(t) and t > 0 else math.nan
            speed[p].append(s)
            cells.append("not reached" if math.isnan(s) else f"{s:.1f}x")
        lines.append(f"| {c[0]} | {c[1]} | {ref[c]['trace_ms']:.2f} | " + " | ".join(cells) + " |")
    lines.append("| **median** | | | " + " | ".join(
        f"**{median(speed[p]):.1f}x** ({sum(not math.isnan(x) for x in speed[p])}/{len(speed[p])} reached)" for p in policies) + " |\n")
    # 3. Value against the optimal bound; adherence; flicker.
    lines.append("### Selected value against the 0/1-knapsack bound, budget adherence and flicker (all budgets)\n")
    lines.append("| policy | ΣR / bound (mean) | frames within 1.2 T (all budgets) | within 1.2 T (budgets >= 1 ms) | "
                 "median trace / T | selection changes per frame |")
    lines.append("|---|---|---|---|---|---|")
    for p in policies:
        g = [s for s in summary if s["policy"] == p]
        big = [s for s in g if s["budget_ms"] >= 1.0]
        lines.append(f"| {p} | {mean([s['value_over_bound'] for s in g]):.3f} | {mean([s['within_1.2T'] for s in g]):.3f} | "
                     f"{mean([s['within_1.2T'] for s in big]):.3f} | {median([s['trace_over_T'] for s in g]):.2f} | "
                     f"{mean([s['changes_per_frame'] for s in g]):.2f} |")
    # 4. Density against the paper's graph.
    if "density" in policies and "paper" in policies:
        wins = []
        for c in cases:
            cells, _, _, times = equal_time_errors(summary, c, ["density", "paper"])
            if cells is not None and times:
                wins.append((c, cells[1] - cells[0]))  # paper's error minus density's
        better = sum(1 for _, x in wins if x > 0)
        lines.append(f"\n### density against paper\n\nAt equal trace time (both interpolated over the range both cover) density's "
                     f"mean FLIP is lower than paper's in {better} of {len(wins)} scene/path cases; higher in: "
                     + (", ".join(f"{c[0]}/{c[1]} (+{-x:.4f})" for c, x in wins if x < 0) or "none") + ".")
    return "\n".join(lines) + "\n"


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


def plots(out_dir, summary, rows, policies):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plot_dir = out_dir / "plots"
    plot_dir.mkdir(exist_ok=True)
    cases = sorted({(s["scene"], s["path"]) for s in summary})
    scenes = sorted({c[0] for c in cases})
    for scene in scenes:
        paths = [c[1] for c in cases if c[0] == scene]
        fig, axes = plt.subplots(1, len(paths), figsize=(5.5 * len(paths), 4), squeeze=False)
        for ax, path in zip(axes[0], paths):
            for p in policies:
                pts = curve(summary, scene, path, p)
                if pts:
                    ax.plot([t for t, _ in pts], [e for _, e in pts], "o-", color=COLORS.get(p), label=p, ms=4)
            for p in ("none", "all"):
                s = next((s for s in summary if (s["scene"], s["path"], s["policy"]) == (scene, path, p)), None)
                if s:
                    ax.plot([max(s["trace_ms"], 1e-3)], [s["flip"]], "s", color=COLORS[p], label=p, ms=7)
            ax.set_xscale("log")
            label(ax, "trace-pass GPU time per frame (ms, log)", "mean FLIP against full RT", f"{scene}: {path}")
        save(plt, fig, plot_dir / f"error_vs_time_{scene}.png")
    # Adherence and flicker per policy against the budget index, over all scenes.
    for key, ylabel, name in (("within_1.2T", "frames with trace time <= 1.2 T", "adherence"),
                              ("changes_per_frame", "selection changes per frame", "flicker")):
        fig, ax = plt.subplots(figsize=(6, 4))
        for p in policies:
            by_b = {}
            for s in summary:
                if s["policy"] == p:
                    by_b.setdefault(s["budget_index"], []).append(s[key])
            bs = sorted(by_b)
            ax.plot(bs, [mean(by_b[b]) for b in bs], "o-", color=COLORS.get(p), label=p)
        label(ax, "budget point (0 = cheapest object ... last = full-RT trace time)", ylabel, f"{name}, mean over scenes and paths")
        save(plt, fig, plot_dir / f"{name}.png")


def strips(out_dir, rows):
    """Reference / hybrid (density, middle budget) / fallback-only / FLIP error map, for the
    first frame of each scene's first path."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import flip_evaluator as flip
    strip_dir = out_dir / "strips"
    strip_dir.mkdir(exist_ok=True)
    for scene in sorted({r["scene"] for r in rows}):
        imaged = [r for r in rows if r["scene"] == scene and r["image"] and r["frame"] == "0"]
        if not imaged:
            continue
        path = imaged[0]["path"]
        imaged = [r for r in imaged if r["path"] == path]
        budgets = sorted({int(r["budget_index"]) for r in imaged if r["policy"] == "density"})
        hybrid = next((r for r in imaged if r["policy"] == "density" and int(r["budget_index"]) == budgets[len(budgets) // 2]), None) if budgets else None
        ref = next((r for r in imaged if r["policy"] == "all"), None)
        fallback = next((r for r in imaged if r["policy"] == "none"), None)
        if not (hybrid and ref and fallback):
            continue
        images = [flip.load(str(out_dir / r["image"])) for r in (ref, hybrid, fallback)]
        errmap, _, _ = flip.evaluate(str(out_dir / ref["image"]), str(out_dir / hybrid["image"]), "LDR")
        titles = ["reference (all)", f"hybrid (density, T = {num(hybrid['budget_ms']):.2f} ms)", "fallback only (none)",
                  f"FLIP hybrid vs reference ({num(hybrid['flip']):.4f})"]
        fig, axes = plt.subplots(1, 4, figsize=(16, 2.6))
        for ax, img, title in zip(axes, images + [errmap], titles):
            ax.imshow(img.clip(0, 1))
            ax.set_title(title, fontsize=9)
            ax.axis("off")
        save(plt, fig, strip_dir / f"{scene}.png")


def main(argv):
    a = parse_args(argv)
    out_dir = pathlib.Path(a.out)
    out_dir.mkdir(parents=True, exist_ok=True)
    scenes = [pathlib.Path(s) for s in a.scenes] if a.scenes else default_scenes(a.quick)
    policies = [p for p in a.policies.split(",") if p]
    print(f"run.py: {len(scenes)} scenes x {a.paths} x policies {policies} x {a.budgets} budgets x {a.repeats} repeats, "
          f"{a.frames} frames (+{a.warmup} warm-up) at {a.size} -> {out_dir}")
    started = time.time()
    progress = Progress(len(scenes))
    rows, skipped = [], []
    for scene in scenes:
        name = scene.stem
        print(f"{name}:")
        sdir = out_dir / "raw" / name
        rc = run_sweep(a, scene, sdir, progress)
        progress.finished_scenes += 1
        if rc != 0:
            skipped.append((name, rc))
            print(f"  {name}: sweep failed (exit {rc}); scene left out of the tables, listed in headline.md")
            continue
        with open(sdir / "frames.csv") as f:
            srows = list(csv.DictReader(f))
        score_flip(sdir, srows)
        for r in srows:
            r["image"] = f"raw/{name}/{r['image']}" if r["image"] else ""
        rows += srows
    if not rows:
        print("run.py: no scene rendered", file=sys.stderr)
        return 1
    fields = list(rows[0].keys())
    write_csv(out_dir / "frames.csv", rows, fields)
    summary = summarize(rows)
    write_csv(out_dir / "summary.csv", summary)
    text = headline(summary, policies)
    minutes = (time.time() - started) / 60
    cmd = "bench/run.py " + " ".join(argv)
    with open(out_dir / "headline.md", "w") as f:
        f.write(f"Command: `{cmd.strip()}`, {minutes:.1f} min, {len(scenes) - len(skipped)} scenes"
                + (f"; failed: {', '.join(f'{n} (exit {rc})' for n, rc in skipped)}" if skipped else "") + "\n\n" + text)
    plots(out_dir, summary, rows, policies)
    strips(out_dir, rows)
    if a.publish:
        pub = pathlib.Path(a.publish)
        pub.mkdir(parents=True, exist_ok=True)
        for name in ("summary.csv", "headline.md"):
            shutil.copy(out_dir / name, pub / name)
        for folder in ("plots", "strips"):
            shutil.copytree(out_dir / folder, pub / folder, dirs_exist_ok=True)
    print(text)
    print(f"run.py: wrote {out_dir}/frames.csv, summary.csv, headline.md, plots/, strips/ in {minutes:.1f} min")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
