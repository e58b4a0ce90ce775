#!/usr/bin/env python3
"""What whole items can buy at best: per scene and camera path, renders `classified` (every
item traced) with `raybudget render --item-stats`, which writes per item (an object's
shadows, reflections or refractions) the display error its tracing removed against the
fallback and the subgroup-clock ticks it cost, then packs the items greedily by error per
tick, as a selector that knew both exactly would, into 10, 25 and 50% of the ticks.

The figure is the share of the items' error sum recovered: an upper estimate of what any
policy that traces whole items can reach at that share of the trace cost (greedy by
density is within one item of the knapsack optimum). The error is the trace passes' own
display-space measure (docs/SELECTION.md), not FLIP; the cost is the ticks inside the
traced pixels, not the whole stage.

    .venv-bench/bin/python bench/item_bound.py [--size 320x180] [--frames 3] [--scenes ...]
"""
import argparse
import csv
import pathlib
import statistics
import subprocess
import sys
import tempfile

import run  # the benchmark's scene list

FRACTIONS = [0.10, 0.25, 0.50]
EFFECTS = ["shadows", "reflections", "refractions"]


def greedy_share(items, fraction):
    """The error share recovered by packing items by error per tick into `fraction` of the ticks."""
    total_error = sum(e for e, _ in items)
    budget = fraction * sum(t for _, t in items)
    used = got = 0.0
    for e, t in sorted(items, key=lambda x: -x[0] / max(x[1], 1)):
        if used + t <= budget:
            used += t
            got += e
    return got / total_error


def main(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--scenes", nargs="+", help="scene files (default: the benchmark's)")
    p.add_argument("--size", default="320x180")
    p.add_argument("--frames", type=int, default=3, help="frames of each path (as the benchmark records them); the last one is measured")
    p.add_argument("--paths", default="orbit,flythrough")
    p.add_argument("--raybudget", default=str(run.ROOT / "build" / "tools" / "raybudget"))
    a = p.parse_args(argv)
    scenes = [pathlib.Path(s) for s in a.scenes] if a.scenes else run.default_scenes(False)
    w, h = a.size.split("x")
    print(f"| scene | path | items | error share: shadows / reflections / refractions | cost share | "
          + " | ".join(f"at {f:.0%}" for f in FRACTIONS) + " |")
    print("|---|---|---|---|---|" + "---|" * len(FRACTIONS))
    shares = {f: [] for f in FRACTIONS}
    with tempfile.TemporaryDirectory() as tmp:
        for scene in scenes:
            for path in a.paths.split(","):
                out = pathlib.Path(tmp) / f"{scene.stem}-{path}"
                subprocess.run([a.raybudget, "render", str(scene), "--policy", "classified", "--item-stats", "--camera", path,
                                "--frames", str(a.frames), "--width", w, "--height", h, "--out", str(out)],
                               check=True, capture_output=True)
                with open(out / "items.csv") as f:
                    rows = [r for r in csv.DictReader(f) if r["traced"] == "1"]
                items = [(float(r["error"]), int(r["ticks"])) for r in rows]
                error, ticks = sum(e for e, _ in items), sum(t for _, t in items)
                if error <= 0 or ticks <= 0:
                    print(f"| {scene.stem} | {path} | {len(rows)} | nothing traced or nothing to remove | | " + " | " * len(FRACTIONS))
                    continue
                by = {e: (sum(float(r["error"]) for r in rows if r["effect"] == e) / error,
                          sum(int(r["ticks"]) for r in rows if r["effect"] == e) / ticks) for e in EFFECTS}
                cells = []
                for f in FRACTIONS:
                    s = greedy_share(items, f)
                    shares[f].append(s)
                    cells.append(f"{s:.2f}")
                print(f"| {scene.stem} | {path} | {len(rows)} | " + " / ".join(f"{by[e][0]:.2f}" for e in EFFECTS) + " | "
                      + " / ".join(f"{by[e][1]:.2f}" for e in EFFECTS) + " | " + " | ".join(cells) + " |")
    print("\nmedian over cases with something to remove: " + ", ".join(
        f"{statistics.median(shares[f]):.2f} at {f:.0%}" for f in FRACTIONS if shares[f]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
