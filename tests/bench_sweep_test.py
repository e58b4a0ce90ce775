#!/usr/bin/env python3
"""The benchmark end to end on a tiny sweep: one ci scene, 2 policies, 2 budgets, 3 frames,
2 repeats, the last frame after 2 frames moving along the path. Checks the CSV columns, that `all` matches the reference (zero error) and `none`
does not, that every repeat is imaged, that the stage time covers its passes, and that the
summary, oracle, headline and plots are written. Then order independence: with the time
scale at its prior (no timing feedback), every configuration selects the same objects
frame by frame whether its repeat's order is shuffled or not, and alone; and a sweep that
replays the canonical sweep's camera paths (--replay-paths) selects alike and writes the same
paths.

usage: bench_sweep_test.py RAYBUDGET OUT_DIR   (exit 77: skipped, the ci scenes are absent)
"""
import csv
import pathlib
import shutil
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
SCENE = ROOT.parent / "shared" / "scenes" / "ci" / "CornellBox"

FRAME_COLUMNS = ["scene", "path", "policy", "budget_index", "budget_ms", "repeat", "order", "frame", "lead_in", "coverage_ms", "select_ms",
                 "trace_ms", "trace_shadows_ms", "trace_effects_ms", "fill_effects_ms", "rt_stage_ms", "shadow_maps_ms", "frame_ms", "predicted_trace_ms", "trace_budget_ms",
                 "candidates_ms", "selected_objects", "rays", "selected_value", "optimal_value_bound", "selection_changes", "item_option_changes", "partial_share", "deadline_cut_pixels", "fill_cut_pixels", "rmse",
                 "psnr", "image", "flip"]
SELECTION = ["selected_objects", "rays", "selected_value", "predicted_trace_ms"]


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
           "--policies", "density,random", "--budgets", "2", "--frames", "3", "--warmup", "2", "--lead-in", "2", "--repeats", "2",
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
    if sorted(by_policy) != ["all", "classified", "density", "none", "random"]:
        fail(f"policies in frames.csv: {sorted(by_policy)}")
    if any(len(by_policy[p]) != 2 * 3 for p in ("all", "none", "classified")) or len(by_policy["density"]) != 2 * 2 * 3:
        fail("expected 3 frames per configuration, 2 budgets, 2 repeats: " + str({k: len(v) for k, v in by_policy.items()}))
    for r in rows:
        if r["lead_in"] != ("2" if r["frame"] == "2" else "0"):
            fail(f"the last recorded frame follows the 2 lead-in frames, the others none: frame {r['frame']}, lead_in {r['lead_in']}")
        if not r["image"] or not (out / r["image"]).is_file():
            fail(f"every recorded frame of every repeat is imaged: {r['policy']} repeat {r['repeat']} frame {r['frame']}")
        stage = float(r["rt_stage_ms"])
        parts = sum(float(r[k]) for k in ("coverage_ms", "select_ms") if r[k]) + float(r["trace_ms"])
        if abs(stage - parts) > 1e-3 * max(1.0, stage):
            fail(f"rt_stage_ms {stage} is not coverage + select + trace ({parts})")
        passes = sum(float(r[k]) for k in ("trace_shadows_ms", "trace_effects_ms", "fill_effects_ms") if r[k])
        if abs(float(r["trace_ms"]) - passes) > 1e-3 * max(1.0, stage):
            fail(f"trace_ms {r['trace_ms']} is not its passes' sum ({passes})")
    for r in by_policy["all"]:
        if float(r["flip"]) != 0.0 or float(r["rmse"]) != 0.0:
            fail(f"`all` against the reference: flip {r['flip']}, rmse {r['rmse']} (repeat {r['repeat']}, frame {r['frame']})")
        if float(r["trace_ms"]) <= 0.0 or int(r["rays"]) <= 0 or not r["coverage_ms"] or not r["select_ms"]:
            fail(f"`all` traced nothing, or its stage was not timed, in frame {r['frame']}")
        if r["shadow_maps_ms"]:
            fail("`all` traces every shadow: its shadow-map pass should be skipped")
    for r in by_policy["none"]:
        if float(r["rt_stage_ms"]) != 0.0:
            fail(f"`none` runs no ray-tracing stage: {r}")
    classified_rays, all_rays = (sum(int(r["rays"]) for r in by_policy[p]) for p in ("classified", "all"))
    if not 0 < classified_rays < all_rays:
        fail(f"`classified` traces shadow rays only where the shadow map is uncertain: {classified_rays} rays, all {all_rays}")
    none_flip = sum(float(r["flip"]) for r in by_policy["none"]) / 6
    none_rmse = sum(float(r["rmse"]) for r in by_policy["none"]) / 6
    if not (none_flip > 0.0 and none_rmse > 0.0):
        fail(f"`none` should differ from the full-RT reference: flip {none_flip}, rmse {none_rmse}")
    with open(out / "raw" / scenes[0].stem / "calibration.csv") as f:
        calibration = next(csv.DictReader(f))
    full_ms, budgets = float(calibration["full_rt_stage_ms"]), [float(b) for b in calibration["budgets_ms"].split(";")]
    if len(budgets) != 2 or any(abs(b - share * full_ms) > 1e-3 * full_ms for b, share in zip(budgets, (0.25, 1.0))):
        fail(f"two budgets are the headline's 25% and 100% of full RT's stage cost ({full_ms} ms): {budgets}")
    for r in by_policy["density"]:
        if float(r["budget_ms"]) <= 0.0 or float(r["optimal_value_bound"]) < float(r["selected_value"]) * (1 - 1e-5):
            fail(f"density row without a budget or above the optimal bound: {r}")
    with open(out / "summary.csv") as f:
        summary = list(csv.DictReader(f))
    if len(summary) != 3 + 2 * 2:
        fail(f"summary.csv has {len(summary)} rows, expected 7 (all, none, classified, 2 policies x 2 budgets)")
    if any(int(r["repeats"]) != 2 for r in summary):
        fail("every summary row should come from both repeats")
    with open(out / "oracle.csv") as f:
        oracle = list(csv.DictReader(f))
    if [float(r["fraction"]) for r in oracle] != [0.1, 0.25, 0.5] or not all(0.0 <= float(r["flip"]) < none_flip for r in oracle):
        fail(f"the oracle composites should score below `none` at 10, 25 and 50% of the pixels: {oracle}")
    for name in ["headline.md", "headline.json", "plots/adherence.png", "plots/budget_use.png", "plots/flicker.png",
                 f"plots/error_vs_time_{scenes[0].stem}.png", f"strips/{scenes[0].stem}.png"]:
        if not (out / name).is_file() or (out / name).stat().st_size == 0:
            fail(f"{name} was not written")
    check_aggregate_only(out)
    check_order_independence(raybudget, scenes[0], out / "order")
    print(f"ok: {len(rows)} frames; none: FLIP {none_flip:.4f}, RMSE {none_rmse:.4f}")
    return 0


def check_aggregate_only(out):
    """Re-aggregating a run of two policies without --policies shows those two, not empty
    columns for the default list's others."""
    cmd = [sys.executable, str(ROOT / "bench" / "run.py"), "--aggregate-only", "--out", str(out)]
    run = subprocess.run(cmd, capture_output=True, text=True)
    if run.returncode != 0:
        fail(f"--aggregate-only exited {run.returncode}: {run.stderr[-2000:]}")
    header = next(line for line in (out / "headline.md").read_text().splitlines() if line.startswith("| at |"))
    columns = [c.strip() for c in header.strip("|").split("|")]
    if columns != ["at", "oracle", "density", "random"]:
        fail(f"--aggregate-only's table shows {columns}, expected the run's policies alone")
    if "no frames of paper" not in run.stdout:
        fail("--aggregate-only should say which requested policies the frames lack")
    # --compare with a published folder (headline.json alone, as docs/benchmarks) compares the
    # figures; one without headline.json is refused before any sweep.
    published = out / "published"
    published.mkdir(exist_ok=True)
    shutil.copy(out / "headline.json", published / "headline.json")
    run = subprocess.run(cmd + ["--compare", str(published)], capture_output=True, text=True)
    if run.returncode != 0 or "Against" not in (out / "compare.md").read_text():
        fail(f"--compare with a published folder: exit {run.returncode}, {run.stderr[-2000:]}")
    run = subprocess.run(cmd + ["--compare", str(out / "nothing-here")], capture_output=True, text=True)
    if run.returncode != 2 or "no headline.json" not in run.stderr:
        fail(f"--compare with a folder without headline.json should be refused at once: exit {run.returncode}")


def sweep_selections(raybudget, scene, out, *args, frames="3", expect_error=None):
    cmd = [raybudget, "sweep", str(scene), "--out", str(out), "--width", "96", "--height", "64", "--frames", frames, "--warmup", "2",
           "--paths", "orbit", "--prior-time-scale", "--validation", *args]
    run = subprocess.run(cmd, capture_output=True, text=True)
    if expect_error is not None:
        if run.returncode == 0 or expect_error not in run.stdout + run.stderr:
            fail(f"{' '.join(cmd)} should fail with '{expect_error}': exit {run.returncode}, {run.stdout[-1000:]} {run.stderr[-1000:]}")
        return None, None
    if run.returncode != 0:
        fail(f"{' '.join(cmd)} exited {run.returncode}: {run.stdout[-2000:]} {run.stderr[-2000:]}")
    with open(out / "frames.csv") as f:
        rows = [r for r in csv.DictReader(f) if r["policy"] not in ("all", "none", "classified")]
    return {(r["policy"], r["budget_ms"], r["repeat"], r["frame"]): [r[k] for k in SELECTION] for r in rows}, rows


def check_order_independence(raybudget, scene, out):
    canonical, _ = sweep_selections(raybudget, scene, out / "canonical", "--policies", "density,random", "--budget-list", "0.05,0.4",
                                    "--repeats", "2", "--order-seed", "0")
    shuffled, rows = sweep_selections(raybudget, scene, out / "shuffled", "--policies", "density,random", "--budget-list", "0.05,0.4",
                                      "--repeats", "2", "--order-seed", "9")
    alone, _ = sweep_selections(raybudget, scene, out / "alone", "--policies", "density", "--budget-list", "0.4", "--repeats", "1")
    orders = {(r["repeat"], r["policy"], r["budget_ms"]): r["order"] for r in rows}
    if all(orders[("0", p, b)] == orders[("1", p, b)] for _, p, b in orders):
        fail("the shuffled sweep ran both repeats in the same order: the test shows nothing")
    if canonical != shuffled:
        diff = [k for k in canonical if canonical[k] != shuffled.get(k)]
        fail(f"shuffling the configurations changed the selections: {diff[:5]}")
    for k, v in alone.items():
        if canonical.get(k) != v:
            fail(f"density at 0.4 ms alone selected {v}, inside the sweep {canonical.get(k)} (frame {k})")
    if len({tuple(v) for v in canonical.values()}) < 2:
        fail("every configuration selected alike: the test shows nothing")
    recorded = out / "canonical" / "paths"
    replayed, _ = sweep_selections(raybudget, scene, out / "replayed", "--policies", "density,random", "--budget-list", "0.05,0.4",
                                   "--repeats", "2", "--order-seed", "0", "--replay-paths", str(recorded))
    if replayed != canonical:
        fail("the sweep replaying the canonical sweep's camera paths selected otherwise")
    if (out / "replayed" / "paths" / "orbit.json").read_text() != (recorded / "orbit.json").read_text():
        fail("the replayed sweep wrote other cameras than it read")
    sweep_selections(raybudget, scene, out / "replay-short", "--policies", "density", "--budget-list", "0.4", "--repeats", "1",
                     "--replay-paths", str(recorded), frames="2", expect_error="holds 3 cameras, --frames asks for 2")
    sweep_selections(raybudget, scene, out / "replay-lead-in", "--policies", "density", "--budget-list", "0.4", "--repeats", "1",
                     "--replay-paths", str(recorded), "--lead-in", "2", expect_error="--lead-in follows the named camera paths")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
