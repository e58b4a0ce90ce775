#!/usr/bin/env python3
"""The Khronos glTF-Validator as the loader's oracle. Makes mutants of valid glTF files (field
deletions, type swaps, out-of-range and non-finite numbers, truncated and resized buffers and
GLB chunks, offset/stride/alignment, componentType, type, count and version changes, dangling
references), asks the validator (validate.mjs) and the loader (`raybudget check`) about each,
and tables the outcomes:

  refused      the validator reports errors and the loader refuses the file
  repaired     the validator reports errors and the loader loads it with a warning
  silent       the validator reports errors and the loader loads it without a word: a failure
  stricter     the validator reports no error and the loader refuses the file
  agree        neither finds anything
  crash/hang   the loader died or took over 20 s: a failure

    python3 tests/validator/mutants.py --raybudget build/tools/raybudget [--count 320] [--seed 1]
        [--out DIR] [--scenes FILE.gltf ...] [--list silent,stricter]

Exit 0 when nothing crashed, hung or loaded silently, 1 otherwise; 77 when the validator is not installed
(npm install --prefix tests/validator).
"""
import argparse
import json
import pathlib
import random
import shutil
import struct
import subprocess
import sys
import tempfile
from collections import Counter

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parents[1]
INF_MARK = "__RB_INFINITE__"


def sources(explicit):
    if explicit:
        return [pathlib.Path(s) for s in explicit]
    out = [ROOT / "data" / "default" / "court.gltf"]
    ci = ROOT.parent / "shared" / "scenes" / "ci"
    for name in ("Box", "BoxTextured", "Duck", "CornellBox", "SimpleInstancing", "TransmissionRoughnessTest", "MeshPrimitiveModes"):
        found = sorted((ci / name).glob("*.gltf")) if (ci / name).is_dir() else []
        if found:
            out.append(found[0])
    return out


def leaves(node, path=()):
    """Every (path, value) in a JSON tree, containers included."""
    yield path, node
    if isinstance(node, dict):
        for k, v in node.items():
            yield from leaves(v, path + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from leaves(v, path + (i,))


def set_at(doc, path, value):
    node = doc
    for k in path[:-1]:
        node = node[k]
    node[path[-1]] = value


def delete_at(doc, path):
    node = doc
    for k in path[:-1]:
        node = node[k]
    del node[path[-1]]


def pick(rng, doc, where):
    found = [(p, v) for p, v in leaves(doc) if p and where(p, v)]
    return rng.choice(found) if found else (None, None)


# Each mutation edits (doc, bin) in place and returns a label, or None when it does not apply.
def delete_field(rng, doc, data):
    p, _ = pick(rng, doc, lambda p, v: isinstance(p[-1], str))
    if p is None:
        return None
    delete_at(doc, p)
    return "delete " + "/".join(map(str, p))


def swap_type(rng, doc, data):
    p, v = pick(rng, doc, lambda p, v: not isinstance(v, (dict, list)) or len(p) > 1)
    if p is None:
        return None
    choices = [x for x in ("x", {}, [], True, 1.5, -3) if type(x) is not type(v)]
    set_at(doc, p, rng.choice(choices))
    return "type " + "/".join(map(str, p))


def bad_number(rng, doc, data):
    p, v = pick(rng, doc, lambda p, v: isinstance(v, (int, float)) and not isinstance(v, bool))
    if p is None:
        return None
    value = rng.choice([-1, -0.001, 1.5, 2 ** 32, 1e40, -1e40, INF_MARK, 0])
    set_at(doc, p, value)
    return f"number {'/'.join(map(str, p))} = {value if value != INF_MARK else 'inf'}"


def truncate_buffer(rng, doc, data):
    if not data:
        return None
    keep = rng.randrange(0, len(data))
    del data[keep:]
    if rng.random() < 0.5:
        doc["buffers"][0]["byteLength"] = len(data)
    return f"truncate buffer to {keep}"


def resize_buffer_length(rng, doc, data):
    if not doc.get("buffers"):
        return None
    b = doc["buffers"][0]
    b["byteLength"] = max(0, b.get("byteLength", 0) + rng.choice([-4, -1, 1, 4, 1 << 20]))
    return f"byteLength {b['byteLength']}"


def shift_offsets(rng, doc, data):
    kind = rng.choice(["bufferViews", "accessors"])
    items = doc.get(kind, [])
    if not items:
        return None
    i = rng.randrange(len(items))
    items[i]["byteOffset"] = items[i].get("byteOffset", 0) + rng.choice([1, 2, 3, 4, 6])
    return f"{kind}[{i}].byteOffset {items[i]['byteOffset']}"


def change_stride(rng, doc, data):
    views = doc.get("bufferViews", [])
    if not views:
        return None
    i = rng.randrange(len(views))
    stride = rng.choice([1, 2, 6, 8, 12, 16, 256, 1 << 30])
    views[i]["byteStride"] = stride
    return f"bufferViews[{i}].byteStride {stride}"


def change_component_type(rng, doc, data):
    acc = doc.get("accessors", [])
    if not acc:
        return None
    i = rng.randrange(len(acc))
    acc[i]["componentType"] = rng.choice([5120, 5121, 5122, 5123, 5124, 5125, 5126, 5130])
    if rng.random() < 0.3:
        acc[i]["normalized"] = True
    return f"accessors[{i}].componentType {acc[i]['componentType']}{' normalized' if acc[i].get('normalized') else ''}"


def change_accessor_type(rng, doc, data):
    acc = doc.get("accessors", [])
    if not acc:
        return None
    i = rng.randrange(len(acc))
    acc[i]["type"] = rng.choice(["SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4", "VEC5"])
    return f"accessors[{i}].type {acc[i]['type']}"


def change_count(rng, doc, data):
    acc = doc.get("accessors", [])
    if not acc:
        return None
    i = rng.randrange(len(acc))
    acc[i]["count"] = max(0, acc[i]["count"] + rng.choice([-acc[i]["count"], -1, 1, 1000]))
    return f"accessors[{i}].count {acc[i]['count']}"


def change_version(rng, doc, data):
    field, value = rng.choice([("version", "1.0"), ("version", "3.0"), ("version", "2.1"), ("version", "two"), ("minVersion", "2.1"),
                               ("minVersion", "3.0")])
    doc.setdefault("asset", {})[field] = value
    return f"asset.{field} {value}"


def dangling_reference(rng, doc, data):
    p, v = pick(rng, doc, lambda p, v: isinstance(v, int) and not isinstance(v, bool) and isinstance(p[-1], str)
                and p[-1] in ("mesh", "material", "indices", "POSITION", "NORMAL", "TEXCOORD_0", "bufferView", "buffer", "source",
                              "index", "camera", "scene"))
    if p is None:
        return None
    set_at(doc, p, v + rng.choice([1000, -v - 1]))
    return "reference " + "/".join(map(str, p))


MUTATIONS = [delete_field, swap_type, bad_number, truncate_buffer, resize_buffer_length, shift_offsets, change_stride,
             change_component_type, change_accessor_type, change_count, change_version, dangling_reference]


def glb(doc, data):
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    data = bytes(data) + b"\0" * (-len(data) % 4)
    chunks = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(data), 0x004E4942) + data
    return bytearray(b"glTF" + struct.pack("<II", 2, 12 + len(chunks)) + chunks)


def mutate_glb(rng, blob):
    kind = rng.choice(["truncate", "chunk length", "total length", "magic", "version", "chunk type"])
    if kind == "truncate":
        del blob[rng.randrange(12, len(blob)):]
    elif kind == "chunk length":
        offset = rng.choice([12, 20 + struct.unpack_from("<I", blob, 12)[0]])
        if offset + 4 <= len(blob):
            struct.pack_into("<I", blob, offset, struct.unpack_from("<I", blob, offset)[0] + rng.choice([-4, -1, 4, 1 << 24]))
    elif kind == "total length":
        struct.pack_into("<I", blob, 8, len(blob) + rng.choice([-8, -1, 1, 8]))
    elif kind == "magic":
        blob[0:4] = b"gLTF"
    elif kind == "version":
        struct.pack_into("<I", blob, 4, rng.choice([1, 3]))
    else:
        struct.pack_into("<I", blob, 16, 0x12345678)
    return "glb " + kind


def write_mutants(out, count, seed, srcs):
    """Writes `count` mutants spread over `srcs` into `out`; returns [(path, label)]."""
    rng = random.Random(seed)
    made = []
    per = max(1, count // len(srcs))
    for s_index, src in enumerate(srcs):
        folder = out / f"s{s_index}"
        shutil.copytree(src.parent, folder, dirs_exist_ok=True)
        doc0 = json.loads(src.read_text())
        uri = doc0["buffers"][0].get("uri") if doc0.get("buffers") else None
        data0 = bytearray((src.parent / uri).read_bytes()) if uri and not uri.startswith("data:") else bytearray()
        for k in range(per):
            doc, data = json.loads(json.dumps(doc0)), bytearray(data0)
            as_glb = data and rng.random() < 0.2
            label = None
            while label is None:
                label = rng.choice(MUTATIONS)(rng, doc, data)
            name = f"m{k:03d}"
            if as_glb and isinstance(doc.get("buffers"), list) and doc["buffers"] and isinstance(doc["buffers"][0], dict):
                doc["buffers"][0].pop("uri", None)
                blob = glb(doc, data)
                if rng.random() < 0.5:
                    label += "; " + mutate_glb(rng, blob)
                path = folder / f"{name}.glb"
                path.write_bytes(bytes(blob).replace(json.dumps(INF_MARK).encode(), b"1e400 "))
            else:
                if data != data0 and doc.get("buffers") and isinstance(doc["buffers"][0], dict):
                    doc["buffers"][0]["uri"] = f"{name}.bin"
                    (folder / f"{name}.bin").write_bytes(bytes(data))
                path = folder / f"{name}.gltf"
                path.write_text(json.dumps(doc).replace(json.dumps(INF_MARK), "1e400"))
            made.append((path, f"{src.stem}: {label}"))
    return made


def run_loader(raybudget, path):
    try:
        p = subprocess.run([raybudget, "check", str(path)], capture_output=True, text=True, timeout=20)
    except subprocess.TimeoutExpired:
        return "hang", ""
    if p.returncode == 0:
        return ("repaired" if "warning:" in p.stdout else "loaded"), p.stdout.strip().splitlines()[0] if p.stdout.strip() else ""
    if p.returncode == 1 and "raybudget: error:" in p.stderr:
        return "refused", p.stderr.strip().splitlines()[0]
    return "crash", f"exit {p.returncode}: {p.stderr.strip()[-300:]}"


def main(argv):
    a = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    a.add_argument("--raybudget", required=True)
    a.add_argument("--count", type=int, default=320)
    a.add_argument("--seed", type=int, default=1)
    a.add_argument("--out")
    a.add_argument("--list", default="silent,stricter,crash,hang", help="outcomes to list file by file")
    a.add_argument("--scenes", nargs="+", help="the files to mutate (default: the default scene and the ci scenes present)")
    args = a.parse_args(argv)
    if not (HERE / "node_modules" / "gltf-validator").is_dir() or not shutil.which("node"):
        print("skipped: the glTF-Validator is not installed (npm install --prefix tests/validator)")
        return 77
    with tempfile.TemporaryDirectory() as tmp:
        out = pathlib.Path(args.out) if args.out else pathlib.Path(tmp)
        out.mkdir(parents=True, exist_ok=True)
        mutants = write_mutants(out, args.count, args.seed, sources(args.scenes))
        report = subprocess.run(["node", str(HERE / "validate.mjs")] + [str(p) for p, _ in mutants], capture_output=True, text=True)
        if report.returncode != 0:
            print("the validator failed: " + report.stderr[-2000:])
            return 1
        verdicts = {r["file"]: r for r in map(json.loads, report.stdout.splitlines())}
        table, rows = Counter(), []
        for path, label in mutants:
            v = verdicts[str(path)]
            loader, message = run_loader(args.raybudget, path)
            invalid = v["errors"] > 0
            if loader in ("crash", "hang"):
                outcome = loader
            elif invalid:
                outcome = {"refused": "refused", "repaired": "repaired", "loaded": "silent"}[loader]
            else:
                outcome = "stricter" if loader == "refused" else "agree"
            table[outcome] += 1
            rows.append((outcome, label, ",".join(v["codes"][:4]), message))
    print(f"{len(mutants)} mutants of {len(sources(args.scenes))} files (seed {args.seed}):")
    print("| outcome | files |\n|---|---|")
    for outcome in ("refused", "repaired", "silent", "stricter", "agree", "crash", "hang"):
        print(f"| {outcome} | {table[outcome]} |")
    listed = args.list.split(",")
    for outcome, label, codes, message in rows:
        if outcome in listed:
            print(f"{outcome}: {label} [validator: {codes or 'no error'}] {message[:200]}")
    return 1 if table["crash"] or table["hang"] or table["silent"] else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
