#!/usr/bin/env python3
"""The benchmark end to end on a tiny sweep: one ci scene, 2 policies, 2 budgets, 3 frames.
Checks the CSV columns, that `all` against itself has zero error and `none` a positive one,
and that the summary, headline and plots are written.

usage: bench_sweep_test.py RAYBUDGET OUT_DIR   (exit 77: skipped, the ci scenes are absent)
"""
import csv
import pathlib
import shutil
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
SCENE = ROOT.parent / "shared" / "scenes" / "ci" / "CornellBox"

FRAME_COLUMNS = ["scene", "path", "policy", "budget_index", "budget_ms", "repeat", "frame", "trace_ms", "frame_ms",
                 "predicted_trace_ms", "selected_objects", "rays", "selected_value", "optimal_value_bound",
                 "selection_changes", "rmse", "psnr", "image", "flip"]


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def main(raybudget, out):
    scenes = sorted(SCENE.glob("*.gltf")) + sorted(SCENE.glob("*.glb"))
    if not scenes:
        print(f"SKIP: {SCENE} is absent (the shared ci scenes are not part of a fresh clone)")
        return 77
    shutil.rmtree(out, ignore_errors=True)
    cmd = [sys.executable, str(ROOT / "bench" / "run.py"), "--raybudget", raybudget, "--scenes", str(scenes[0]),
           "--policies", "density,random", "--budgets", "2", "--frames", "3", "--warmup", "1", "--repeats", "1",
           "--paths", "orbit", "--size", "96x64", "--validation", "--out", out]
    run = subprocess.run(cmd, capture_output=True, text=True)
    print(run.stdout[-4000:], run.stderr[-4000:])
    if run.returncode != 0:
        fail(f"run.py exited {run.returncode}")
    out = pathlib.Path(out)
    with open(out / "frames.csv") as f:
        reader = csv.DictReader(f)
        if reader.fieldnames != FRAME_COLUMNS:
            fail(f"frames.csv columns {reader.fieldnames}, expected {FRAME_COLUMNS}")
        rows = list(reader)
    by_policy = {}
    for r in rows:
        by_policy.setdefault(r["policy"], []).append(r)
    if sorted(by_policy) != ["all", "density", "none", "random"]:
        fail(f"policies in frames.csv: {sorted(by_policy)}")
    if len(by_policy["all"]) != 3 or len(by_policy["none"]) != 3 or len(by_policy["density"]) != 2 * 3:
        fail("expected 3 frames per configuration and 2 budgets: " + str({k: len(v) for k, v in by_policy.items()}))
    for r in by_policy["all"]:
        if float(r["flip"]) != 0.0 or float(r["rmse"]) != 0.0:
            fail(f"`all` against itself: flip {r['flip']}, rmse {r['rmse']} (frame {r['frame']})")
        if float(r["trace_ms"]) <= 0.0 or int(r["rays"]) <= 0:
            fail(f"`all` traced nothing in frame {r['frame']}")
    none_flip = sum(float(r["flip"]) for r in by_policy["none"]) / 3
    none_rmse = sum(float(r["rmse"]) for r in by_policy["none"]) / 3
    if not (none_flip > 0.0 and none_rmse > 0.0):
        fail(f"`none` should differ from the full-RT reference: flip {none_flip}, rmse {none_rmse}")
    for r in by_policy["density"]:
        if float(r["budget_ms"]) <= 0.0 or float(r["optimal_value_bound"]) < float(r["selected_value"]) * (1 - 1e-5):
            fail(f"density row without a budget or above the optimal bound: {r}")
    with open(out / "summary.csv") as f:
        summary = list(csv.DictReader(f))
    if len(summary) != 2 + 2 * 2:
        fail(f"summary.csv has {len(summary)} rows, expected 6 (all, none, 2 policies x 2 budgets)")
    for name in ["headline.md", "plots/adherence.png", "plots/flicker.png", f"plots/error_vs_time_{scenes[0].stem}.png",
                 f"strips/{scenes[0].stem}.png"]:
        if not (out / name).is_file() or (out / name).stat().st_size == 0:
            fail(f"{name} was not written")
    print(f"ok: {len(rows)} frames; none: FLIP {none_flip:.4f}, RMSE {none_rmse:.4f}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
