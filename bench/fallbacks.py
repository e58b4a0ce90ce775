#!/usr/bin/env python3
"""The raster fallbacks, one at a time: for every benchmark scene (bench/run.py's set), the
FLIP of `none` against `all` along both camera paths with the sky alone, with each fallback
switched on alone (screen-space transmission, reflection probes, screen-space reflections)
and with all of them; then the fallback passes' GPU time per frame of `none` at a larger size.
Writes OUT/fallbacks.csv, OUT/timings.csv and OUT/fallbacks.md (the sweeps under OUT/raw/);
what an earlier run into OUT measured is kept but for the scenes measured again.

usage: bench/fallbacks.py [--out DIR] [--scenes FILE...] [--size WxH] [--timing-size WxH]
                          [--frames N] [--warmup N] [--timing-frames N] [--only flip|timings]
                          [--configs NAME...] [--extra 'OPTIONS'] [--replay-paths DIR]

`none` renders no rays and `all` no budget, so their images, and the FLIP between them, do
not depend on the machine's speed; the timings do. Needs flip-evaluator (.venv-bench).
"""

import argparse
import csv
import pathlib
import re
import statistics
import subprocess
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import run  # noqa: E402  (the benchmark's scene list, paths and FLIP scoring)

OFF = {"transmission": "--no-screen-space-transmission", "probes": "--no-reflection-probes", "ssr": "--no-screen-space-reflections"}
CONFIGS = {  # name: the fallbacks switched on
    "sky": [],
    "+transmission": ["transmission"],
    "+probes": ["probes"],
    "+ssr": ["ssr"],
    "all": ["transmission", "probes", "ssr"],
}
TIMED_PASSES = ["shadow_maps", "environment", "reflection_probes", "behind_glass", "ssr", "lighting"]


def flags(config):
    return [OFF[f] for f in OFF if f not in CONFIGS[config]]


def replayed_paths(a, name):
    """The camera paths an earlier run into a.replay_paths recorded for scene `name` (sweep --replay-paths)."""
    if not a.replay_paths:
        return []
    for config in CONFIGS:
        folder = pathlib.Path(a.replay_paths) / "raw" / name / config.lstrip("+") / "paths"
        if folder.is_dir():
            return ["--replay-paths", str(folder)]
    sys.exit(f"fallbacks.py: {a.replay_paths} recorded no camera paths for {name}")


def sweep(a, scene, config, out):
    w, h = a.size.split("x")
    cmd = [a.raybudget, "sweep", str(scene), "--out", str(out), "--width", w, "--height", h, "--frames", str(a.frames),
           "--warmup", str(a.warmup), "--repeats", "1", "--policies", "benefit", "--budget-list", "1", "--no-classified",
           "--order-seed", "0"] + flags(config) + replayed_paths(a, scene.stem) + a.extra.split()
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if proc.returncode != 0:
        print(proc.stdout[-2000:], file=sys.stderr)
        return None
    rows = [r for r in run.read_rows(out / "frames.csv") if r["policy"] == "none" and r["image"]]
    run.score_flip(out, rows)
    return rows


def pass_timings(a, scene, out):
    """Median ms per pass of `none` with every fallback, from --explain."""
    w, h = a.timing_size.split("x")
    cmd = [a.raybudget, "render", str(scene), "--policy", "none", "--camera", "orbit", "--frames", str(a.timing_frames),
           "--width", w, "--height", h, "--explain", "--out", str(out)] + a.extra.split()
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    found = {}
    for line in proc.stdout.splitlines():
        m = re.match(r"\s+(\w+)\s+ran in \d+, median ([0-9.]+) ms", line)
        if m:
            found[m.group(1)] = float(m.group(2))
    return found


def main(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", default="results/fallbacks")
    p.add_argument("--scenes", nargs="*")
    p.add_argument("--size", default="640x360")
    p.add_argument("--timing-size", default="1280x720")
    p.add_argument("--frames", type=int, default=3)
    p.add_argument("--warmup", type=int, default=6)
    p.add_argument("--timing-frames", type=int, default=8)
    p.add_argument("--only", choices=["flip", "timings"], help="one half (the other's files are kept)")
    p.add_argument("--configs", nargs="*", choices=list(CONFIGS), help="measure only these configurations (default all)")
    p.add_argument("--extra", default="", help="more options for every render, e.g. --extra='--shadow-normal-offset 3'")
    p.add_argument("--replay-paths", help="an earlier run's OUT: its sweeps' cameras instead of today's paths (like for like)")
    p.add_argument("--raybudget", default=str(run.ROOT / "build" / "tools" / "raybudget"))
    a = p.parse_args(argv)
    out = pathlib.Path(a.out)
    scenes = [pathlib.Path(s) for s in a.scenes] if a.scenes else run.default_scenes(False)
    out.mkdir(parents=True, exist_ok=True)
    # What an earlier run into OUT measured is kept, but for what this run measures again.
    names = {s.stem for s in scenes}
    def earlier(name, measured):
        path = out / name
        rows = run.read_rows(path) if path.exists() else []
        return [r for r in rows if not measured or r["scene"] not in names]
    results = [dict(r, flip=float(r["flip"])) for r in earlier("fallbacks.csv", a.only != "timings")]
    timings = [dict(r, total=float(r["total"]), **{k: float(r[k]) if r[k] else "" for k in TIMED_PASSES})
               for r in earlier("timings.csv", a.only != "flip")]
    for scene in scenes:
        name = scene.stem
        for config in (a.configs or CONFIGS) if a.only != "timings" else []:
            rows = sweep(a, scene, config, out / "raw" / name / config.lstrip("+"))
            if rows is None:
                print(f"fallbacks.py: {name} {config}: the sweep failed", file=sys.stderr)
                continue
            for path in sorted({r["path"] for r in rows}):
                flips = [float(r["flip"]) for r in rows if r["path"] == path]
                results.append({"scene": name, "path": path, "config": config, "flip": statistics.mean(flips),
                                "frame_ms": statistics.median(float(r["frame_ms"]) for r in rows if r["path"] == path)})
            print(f"  {name} {config}: " + ", ".join(f"{r['path']} {r['flip']:.4f}" for r in results if r["scene"] == name and r["config"] == config),
                  flush=True)
        if a.only == "flip":
            continue
        t = pass_timings(a, scene, out / "raw" / name / "timing")
        timings.append({"scene": name, **{k: t.get(k, "") for k in TIMED_PASSES}, "total": sum(t.values())})
    if results:
        run.write_csv(out / "fallbacks.csv", results)
    if timings:
        run.write_csv(out / "timings.csv", timings)
    with open(out / "fallbacks.md", "w") as f:
        f.write(f"Command: `bench/fallbacks.py {' '.join(argv)}`; `none` FLIP against `all` at {a.size}, "
                f"{a.frames} frames per path after {a.warmup} warm-up\n\n")
        f.write("| scene | path | " + " | ".join(CONFIGS) + " |\n|---|---|" + "---|" * len(CONFIGS) + "\n")
        cases = sorted({(r["scene"], r["path"]) for r in results})
        value = {(r["scene"], r["path"], r["config"]): r["flip"] for r in results}
        for s, path in cases:
            f.write(f"| {s} | {path} | " + " | ".join(f"{value[(s, path, c)]:.4f}" if (s, path, c) in value else "" for c in CONFIGS) + " |\n")
        complete = [c for c in cases if all((c[0], c[1], k) in value for k in CONFIGS)]
        means = {k: statistics.mean(value[(s, path, k)] for s, path in complete) for k in CONFIGS} if complete else {}
        if means:
            f.write(f"| mean of {len(complete)} | | " + " | ".join(f"{means[k]:.4f}" for k in CONFIGS) + " |\n")
        f.write(f"\nGPU ms of `none`'s passes with every fallback at {a.timing_size}, median over the frames each ran in of "
                f"{a.timing_frames} orbit frames: shadow_maps, environment and reflection_probes run on the first frame only "
                "(their one-time cost), the others every frame\n\n")
        f.write("| scene | " + " | ".join(TIMED_PASSES) + " |\n|---|" + "---|" * len(TIMED_PASSES) + "\n")
        for t in timings:
            f.write(f"| {t['scene']} | " + " | ".join(f"{t[k]:.1f}" if t[k] != "" else "-" for k in TIMED_PASSES) + " |\n")
    print(f"fallbacks.py: wrote {out}/fallbacks.csv, timings.csv, fallbacks.md")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
