#!/usr/bin/env python3
"""What the shadow classifier costs in error and saves in rays: per scene and camera path,
renders the last of a few frames with `all` (every shadow ray) and `none` (the shadow maps)
and, with each given build, `classified` (shadow rays only where the shadow map is
uncertain), reflections and refractions off, and prints the classified frame's shadow rays,
the shadow pass's median time and its FLIP against `all`, with the totals per build.

    .venv-bench/bin/python bench/classifier.py [--raybudget BUILD ...] [--scenes ...] [--extra "--shadow-uncertainty 4"]

Several builds side by side compare two classifiers on the same views (the first build
renders `all` and `none`). The shadow pass's time is noisy on a busy machine; the rays and
FLIP are not.
"""
import argparse
import pathlib
import re
import shlex
import subprocess
import sys
import tempfile

import run  # the benchmark's scene list

SHADOWS_ONLY = ["--no-rt-reflections", "--no-rt-refractions"]


def render(build, scene, camera, policy, out, a):
    cmd = [build, "render", str(scene), "--width", str(a.width), "--height", str(a.height), "--frames", str(a.frames),
           "--camera", camera, "--policy", policy, "--explain", "--out", str(out)] + SHADOWS_ONLY + shlex.split(a.extra)
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"classifier.py: {' '.join(cmd)} failed:\n{r.stdout}{r.stderr}")
    rays = re.search(r"rays traced: (\d+)", r.stdout)
    ms = re.search(r"^  trace_shadows +([\d.]+) ms", r.stdout, re.M)
    return int(rays.group(1)) if rays else 0, float(ms.group(1)) if ms else 0.0


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--raybudget", nargs="+", default=[str(run.ROOT / "build" / "tools" / "raybudget")])
    p.add_argument("--scenes", nargs="+", help="scene files (default: the benchmark's)")
    p.add_argument("--width", type=int, default=640)
    p.add_argument("--height", type=int, default=360)
    p.add_argument("--frames", type=int, default=5, help="frames along each path; the last is scored")
    p.add_argument("--paths", default="orbit,flythrough")
    p.add_argument("--extra", default="", help="more raybudget render options for every run")
    a = p.parse_args()
    import flip_evaluator as flip

    scenes = [pathlib.Path(s) for s in a.scenes] if a.scenes else run.default_scenes(False)
    totals = [[0, 0.0, []] for _ in a.raybudget]
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        for scene in scenes:
            for camera in a.paths.split(","):
                reference, raster = tmp / "all", tmp / "none"
                render(a.raybudget[0], scene, camera, "all", reference, a)
                render(a.raybudget[0], scene, camera, "none", raster, a)
                score = lambda d: flip.evaluate(str(reference / "frame.png"), str(d / "frame.png"), "LDR", applyMagma=False)[1]
                line = f"{scene.stem[:24]:24s} {camera:10s} none {score(raster):.4f}"
                for i, build in enumerate(a.raybudget):
                    out = tmp / f"classified{i}"
                    rays, ms = render(build, scene, camera, "classified", out, a)
                    error = score(out)
                    totals[i][0] += rays
                    totals[i][1] += ms
                    totals[i][2].append(error)
                    line += f" | {rays:7d} rays {ms:6.2f} ms FLIP {error:.5f}"
                print(line, flush=True)
    for build, (rays, ms, errors) in zip(a.raybudget, totals):
        print(f"{build}: {rays} shadow rays, shadow pass {ms:.1f} ms, mean FLIP against all {sum(errors) / len(errors):.2e} over {len(errors)} views")


if __name__ == "__main__":
    main()
