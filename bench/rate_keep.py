#!/usr/bin/env python3
"""How much of full rate's benefit a reduced ray rate keeps, after its fill. Per scene and view
(the default camera, and the orbit's last frame after 2 and 3 frames), renders `all` at full
rate (the reference), `none` (the fallbacks) and `all` at 1/4 and 1/16 (every item at that
rate, the others filled, docs/SELECTION.md "Ray rates"), and prints the share of `none`'s FLIP
the rate removes: keep = 1 - FLIP(rate) / FLIP(none). 1: as full rate; 0: no better than the
fallback; below 0: the fill made the image worse. The `benefit` policy prices a rate's value as
a share of full rate's (RB_KEEP_* in shaders/shared/selection.h); this says what a change to
the fill buys, scene by scene.

    .venv-bench/bin/python bench/rate_keep.py [--scenes ...] [--size 480x270]
        [--extra "--no-rt-shadows"] [--views static:1,orbit:2,orbit:3] [--out results/rate-keep]

`--views static:20` measures a still camera whose temporal fill has had every rate's period
(1/16: 16 frames) to cover the image: what a rate keeps on a still view.
"""
import argparse
import pathlib
import statistics
import subprocess
import sys

import flip_evaluator as flip

import run  # the benchmark's paths and scene list

VIEWS = "static:1,orbit:2,orbit:3"  # camera:frames, the last frame scored
RATES = ["quarter", "sixteenth"]


def render(raybudget, scene, out, args):
    subprocess.run([raybudget, "render", str(scene), "--out", str(out)] + args, check=True, capture_output=True)
    return str(out / "frame.png")


def flip_of(reference, image):
    _, err, _ = flip.evaluate(reference, image, "LDR", applyMagma=False)
    return err


def main(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--scenes", nargs="+", help="scene files (default: the generated scenes and every bench scene)")
    p.add_argument("--size", default="480x270")
    p.add_argument("--extra", default="", help="more raybudget render options for every run (e.g. --no-rt-shadows)")
    p.add_argument("--views", default=VIEWS, help="camera:frames views, comma-separated (default %(default)s)")
    p.add_argument("--out", default="results/rate-keep")
    p.add_argument("--raybudget", default=str(run.ROOT / "build" / "tools" / "raybudget"))
    a = p.parse_args(argv)
    scenes = [pathlib.Path(s) for s in a.scenes] if a.scenes else run.GENERATED + run.bench_scenes()
    w, h = a.size.split("x")
    out = pathlib.Path(a.out)
    keeps = {rate: [] for rate in RATES}
    print(f"at {a.size}; options: {a.extra or '(defaults)'}\n")
    print("| scene | view | none FLIP | keep at 1/4 | keep at 1/16 |")
    print("|---|---|---|---|---|")
    for scene in scenes:
        for camera, frames in [(v.split(":")[0], int(v.split(":")[1])) for v in a.views.split(",")]:
            common = ["--width", w, "--height", h, "--frames", str(frames), "--camera", camera] + a.extra.split()
            base = out / f"{scene.stem}-{camera}{frames}"
            reference = render(a.raybudget, scene, base.with_name(base.name + "-full"), common + ["--policy", "all"])
            gap = flip_of(reference, render(a.raybudget, scene, base.with_name(base.name + "-none"), common + ["--policy", "none"]))
            if gap <= 0.0:
                continue  # nothing for a rate to keep
            row = []
            for rate in RATES:
                image = render(a.raybudget, scene, base.with_name(f"{base.name}-{rate}"), common + ["--policy", "all", "--rate", rate])
                keep = 1.0 - flip_of(reference, image) / gap
                keeps[rate].append(keep)
                row.append(keep)
            print(f"| {scene.stem} | {camera} {frames} | {gap:.4f} | {row[0]:.3f} | {row[1]:.3f} |", flush=True)
    for rate in RATES:
        if keeps[rate]:
            print(f"\n{rate}: keep mean {statistics.mean(keeps[rate]):.3f}, median {statistics.median(keeps[rate]):.3f} "
                  f"over {len(keeps[rate])} views", end="")
    print()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
