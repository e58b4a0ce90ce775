#!/usr/bin/env python3
"""The raster frame's cost: the GPU time of `none`'s whole frame (every fallback, no rays)
per benchmark scene for one or more builds, interleaved so that the machine's load falls on
all alike. Each run renders an orbit of --frames frames; the first frame pays the one-time
passes (the environment, cached shadow maps, reflection probes) and is reported apart, the
others' median is the steady frame. Prints per scene each build's first and steady frame
(the median over --repeats runs) and the steady frame's ratio to the first build's.

    .venv-bench/bin/python bench/raster_frame.py --raybudget OLD NEW [--scenes ...] [--repeats 3]

Builds of any age work: the frame's time is stats.csv's total_ms.
"""
import argparse
import csv
import pathlib
import shlex
import statistics
import subprocess
import sys
import tempfile

import run  # the benchmark's scene list


def frame_times(build, scene, out, a):
    cmd = [build, "render", str(scene), "--policy", "none", "--camera", "orbit", "--frames", str(a.frames), "--width", str(a.width),
           "--height", str(a.height), "--out", str(out)] + shlex.split(a.extra)
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"raster_frame.py: {' '.join(cmd)} failed:\n{r.stdout[-2000:]}{r.stderr[-2000:]}")
    with open(out / "stats.csv") as f:
        return [float(row["total_ms"]) for row in csv.DictReader(f)]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--raybudget", nargs="+", default=[str(run.ROOT / "build" / "tools" / "raybudget")])
    p.add_argument("--scenes", nargs="+", help="scene files (default: the benchmark's)")
    p.add_argument("--width", type=int, default=1280)
    p.add_argument("--height", type=int, default=720)
    p.add_argument("--frames", type=int, default=6, help="orbit frames per run; the first is the one-time frame")
    p.add_argument("--repeats", type=int, default=3, help="runs per build and scene, the builds alternating")
    p.add_argument("--extra", default="", help="more raybudget render options for every run")
    a = p.parse_args()
    if a.frames < 2:
        sys.exit("raster_frame.py: --frames needs 2 or more (the first is the one-time frame)")
    scenes = [pathlib.Path(s) for s in a.scenes] if a.scenes else run.default_scenes(False)
    builds = a.raybudget
    print(f"none's frame at {a.width}x{a.height}, GPU ms, median of {a.repeats} runs of {a.frames} orbit frames; "
          "first: the one-time frame, steady: the median of the others")
    print(f"{'scene':28s} " + " ".join(f"{'first':>8s} {'steady':>8s}" for _ in builds) + "  steady / first build's")
    with tempfile.TemporaryDirectory() as tmp:
        for scene in scenes:
            first, steady = [[] for _ in builds], [[] for _ in builds]
            for rep in range(a.repeats):
                order = list(range(len(builds)))
                if rep % 2:
                    order.reverse()
                for b in order:
                    times = frame_times(builds[b], scene, pathlib.Path(tmp) / f"b{b}", a)
                    first[b].append(times[0])
                    steady[b].append(statistics.median(times[1:]))
            f = [statistics.median(x) for x in first]
            s = [statistics.median(x) for x in steady]
            print(f"{scene.stem[:28]:28s} " + " ".join(f"{f[b]:8.1f} {s[b]:8.1f}" for b in range(len(builds))) + "  " +
                  " ".join(f"{s[b] / s[0]:.2f}" for b in range(1, len(builds))), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
