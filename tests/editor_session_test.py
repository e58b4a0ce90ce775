"""The editor as a person uses it, under Xvfb on lavapipe with validation on (any validation
message makes the editor exit with status 3):
  1. a scripted session on a copy of the default scene: a low K leaves the mirror on its
     fallback, raising K makes the budget trace it, bad values are refused, undo and redo
     restore, save writes the new K (tests/editor/raise_mirror_k.script);
  2. the saved .gltf keeps everything else: its JSON equals the original but for the mirror
     node's extras, and its buffer file is untouched; reloading it in the editor shows K 20;
  3. the same for a .glb: the BIN chunk is kept byte for byte; closing the window with the
     edit unsaved opens the prompt; the tracer switched, undone and redone (a new core each time);
  4. the screenshot: the viewport region equals the standalone renderer's frame for the same
     camera and policy, and the panel region is the panels (their background and text);
  5. bad input: an unknown script command names the file and line; a missing scene its path.
Usage: editor_session_test.py EDITOR RAYBUDGET SCENE_DIR SCRIPT_DIR WORK"""
import json
import shutil
import struct
import subprocess
import sys
from pathlib import Path

import numpy as np
from PIL import Image

EDITOR, CLI, SCENE_DIR, SCRIPT_DIR, WORK = sys.argv[1:6]
WORK = Path(WORK)
SIZE, PANEL = (1000, 560), 420
VIEWPORT = (SIZE[0] - PANEL, SIZE[1])
failures = []


def check(ok, what):
    print(("ok:   " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def editor(args, cwd, expect_rc=0, xvfb=True):
    cmd = [EDITOR] + args
    if xvfb:
        cmd = ["xvfb-run", "-a", "-s", "-screen 0 1280x720x24"] + cmd
    run = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=600)
    out = run.stdout + run.stderr
    print("\n".join(line for line in out.splitlines() if not line.startswith("  ")))
    check(run.returncode == expect_rc, f"editor {' '.join(args)} exits {expect_rc} (got {run.returncode})")
    return out


def glb_from_gltf(gltf: Path, glb: Path):
    doc = json.loads(gltf.read_text())
    binary = (gltf.parent / doc["buffers"][0]["uri"]).read_bytes()
    del doc["buffers"][0]["uri"]
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    binary += b"\0" * (-len(binary) % 4)
    chunks = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(binary), 0x004E4942) + binary
    glb.write_bytes(b"glTF" + struct.pack("<II", 2, 12 + len(chunks)) + chunks)


def read_glb(path: Path):
    data = path.read_bytes()
    length = struct.unpack_from("<I", data, 12)[0]
    return json.loads(data[20:20 + length]), data[20 + length:]


def node_index(doc, name):
    return next(i for i, n in enumerate(doc["nodes"]) if n.get("name") == name)


def without_mirror_extras(doc):
    doc = json.loads(json.dumps(doc))
    doc["nodes"][node_index(doc, "mirror_panel")].get("extras", {}).pop("raybudget", None)
    return doc


if WORK.exists():
    shutil.rmtree(WORK)
WORK.mkdir(parents=True)
for f in Path(SCENE_DIR).glob("court.*"):
    shutil.copy(f, WORK / f.name)
original = json.loads((WORK / "court.gltf").read_text())
original_bin = (WORK / "court.bin").read_bytes()
budgeted = ["--size", f"{SIZE[0]}x{SIZE[1]}", "--policy", "benefit", "--budget-ms", "6", "--fixed-time-scale", "--validation"]

# 1. The scripted session.
editor(["court.gltf", "--script", str(Path(SCRIPT_DIR) / "raise_mirror_k.script")] + budgeted, WORK)

# 2. The saved .gltf and its reload.
saved = json.loads((WORK / "court_edited.gltf").read_text())
mirror = saved["nodes"][node_index(saved, "mirror_panel")]
check(mirror.get("extras", {}).get("raybudget", {}).get("K") == 20, "save wrote the mirror's new K into extras.raybudget")
check(without_mirror_extras(saved) == without_mirror_extras(original), "the saved JSON equals the original but for the mirror's extras")
check((WORK / "court.bin").read_bytes() == original_bin, "the buffer file is untouched")
(WORK / "reload.script").write_text("pick mirror_panel\nexpect K 20\nquit\n")
editor(["court_edited.gltf", "--script", "reload.script", "--frames", "3"] + budgeted, WORK)

# 3. A .glb: edit, save, reload.
glb_from_gltf(WORK / "court.gltf", WORK / "court.glb")
# Closing with an unsaved edit opens the prompt instead of quitting.
(WORK / "glb.script").write_text("pick mirror_panel\nset Q 7\ntracer native\nwait 2\ntracer compute\nundo\nwait 1\nredo\nclose\nwait 2\nexpect prompt\nsave court_edited.glb\nquit\n")
editor(["court.glb", "--script", "glb.script"] + budgeted, WORK)
doc_before, bin_before = read_glb(WORK / "court.glb")
doc_after, bin_after = read_glb(WORK / "court_edited.glb")
check(bin_after == bin_before, "the .glb's BIN chunk is kept byte for byte")
check(doc_after["nodes"][node_index(doc_after, "mirror_panel")]["extras"]["raybudget"].get("Q") == 7, "the .glb's mirror node has Q 7")
check(without_mirror_extras(doc_after) == without_mirror_extras(doc_before), "the .glb's JSON equals the original but for the mirror's extras")
(WORK / "reload_glb.script").write_text("pick mirror_panel\nexpect Q 7\nquit\n")
editor(["court_edited.glb", "--script", "reload_glb.script"] + budgeted, WORK)

# 4. The screenshot against the standalone renderer (full RT: no learning, no budget).
editor(["court.gltf", "--size", f"{SIZE[0]}x{SIZE[1]}", "--policy", "all", "--validation", "--screenshot", "window.png"], WORK)
subprocess.run([CLI, "render", "court.gltf", "--width", str(VIEWPORT[0]), "--height", str(VIEWPORT[1]), "--policy", "all", "--frames", "3",
                "--out", "cli"], cwd=WORK, check=True, capture_output=True, timeout=600)
window = np.asarray(Image.open(WORK / "window.png").convert("RGB")).astype(int)
frame = np.asarray(Image.open(WORK / "cli" / "frame.png").convert("RGB")).astype(int)
check(window.shape == (SIZE[1], SIZE[0], 3), f"the screenshot is the window's size {SIZE}")
view = window[:, :VIEWPORT[0]]
diff = np.abs(view - frame).max(axis=2)
over = float((diff > 8).mean())
print(f"viewport vs renderer: max channel difference {diff.max()}, share over 8/255 {over:.5f}")
check(over <= 0.005, "the viewport region equals the standalone renderer's frame (at most 0.5% of pixels over 8/255)")
panel = window[:, VIEWPORT[0]:]
background = float((np.abs(panel - 15).max(axis=2) <= 2).mean())
text = float((panel.max(axis=2) >= 180).mean())
print(f"panel: background share {background:.3f}, bright (text) share {text:.4f}; means viewport {view.mean():.1f} panel {panel.mean():.1f}")
check(background >= 0.3 and 0.002 <= text <= 0.3, "the panel region shows the panels: their background and text")
check(abs(view.mean() - panel.mean()) > 40, "the panel region is not the viewport's colour")

# 5. Bad input.
(WORK / "bad.script").write_text("pick mirror_panel\nteleport 3\n")
out = editor(["court.gltf", "--script", "bad.script"], WORK, expect_rc=1, xvfb=False)
check("bad.script:2: unknown command 'teleport'" in out, "an unknown script command is reported with its file and line")
out = editor(["no_such_scene.gltf"], WORK, expect_rc=1, xvfb=False)
check("no_such_scene.gltf" in out, "a missing scene is reported with its path")
out = editor(["court.gltf", "--rate", "eighth"], WORK, expect_rc=1, xvfb=False)
check("unknown ray rate 'eighth'" in out and "auto" in out, "an unknown --rate is refused naming the choices")

print(f"{len(failures)} failures")
sys.exit(1 if failures else 0)
