#!/usr/bin/env python3
"""Writes raybudget's generated scenes: the default scene data/default/court.gltf + court.bin
and a larger level for the benchmark, data/plaza/plaza.gltf + plaza.bin.

The court: a walled court: a floor, three walls, a mirror panel and a chrome sphere, a glass sphere
and a tinted glass block, pillars, crates and several dozen smaller objects from near to
far, lit by a sun, two point lights and a spot light. Some objects carry
extras.raybudget {K, Q, I} so that the budget has authored priorities to respect.
The plaza: a game level of some 150 objects of mixed size, distance and material on a 64 x 64
square, with mirrors, chrome, glass, market stalls, arcades of pillars, crates and a crowd of
small props, lit by a sun, three point lights and a spot light.
Deterministic: the same bytes on every run (a fixed LCG, no library randomness).

usage: make_default_scene.py [DATA_DIR]   (default: data/ beside this repo's tools/)
"""
import json
import math
import os
import struct
import sys


class Lcg:
    """Numerical Recipes LCG: reproducible across Python versions and platforms."""

    def __init__(self, seed):
        self.state = seed & 0xFFFFFFFF

    def uniform(self, lo, hi):
        self.state = (1664525 * self.state + 1013904223) & 0xFFFFFFFF
        return lo + (hi - lo) * (self.state / 4294967296.0)


def box_mesh():
    """Unit cube centred at the origin: 24 vertices (flat normals), 12 triangles."""
    pos, nrm, uv, idx = [], [], [], []
    faces = [((1, 0, 0), (0, 0, -1), (0, 1, 0)), ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
             ((0, 1, 0), (1, 0, 0), (0, 0, -1)), ((0, -1, 0), (1, 0, 0), (0, 0, 1)),
             ((0, 0, 1), (1, 0, 0), (0, 1, 0)), ((0, 0, -1), (-1, 0, 0), (0, 1, 0))]
    for n, u, v in faces:
        base = len(pos)
        for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            pos.append(tuple(0.5 * (n[k] + su * u[k] + sv * v[k]) for k in range(3)))
            nrm.append(n)
            uv.append(((su + 1) / 2, (1 - sv) / 2))
        idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return pos, nrm, uv, idx


def sphere_mesh(slices=32, stacks=16):
    """Unit-radius UV sphere; the poles are fans so no triangle has zero area."""
    pos, nrm, uv, idx = [], [], [], []
    for i in range(stacks + 1):
        theta = math.pi * i / stacks
        for j in range(slices + 1):
            phi = 2 * math.pi * j / slices
            p = (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))
            pos.append(p)
            nrm.append(p)
            uv.append((j / slices, i / stacks))
    row = slices + 1
    for i in range(stacks):
        for j in range(slices):
            a, b = i * row + j, (i + 1) * row + j
            if i != 0:
                idx += [a, a + 1, b]
            if i != stacks - 1:
                idx += [a + 1, b + 1, b]
    return pos, nrm, uv, idx


def cylinder_mesh(slices=24):
    """Unit cylinder (radius 1, height 1, base at y=0) with caps."""
    pos, nrm, uv, idx = [], [], [], []
    for j in range(slices + 1):
        phi = 2 * math.pi * j / slices
        c, s = math.cos(phi), math.sin(phi)
        for y in (0.0, 1.0):
            pos.append((c, y, s))
            nrm.append((c, 0.0, s))
            uv.append((j / slices, 1 - y))
    for j in range(slices):
        a = 2 * j
        idx += [a, a + 1, a + 2, a + 2, a + 1, a + 3]
    for y, ny in ((0.0, -1.0), (1.0, 1.0)):
        centre = len(pos)
        pos.append((0.0, y, 0.0))
        nrm.append((0.0, ny, 0.0))
        uv.append((0.5, 0.5))
        ring = len(pos)
        for j in range(slices):
            phi = 2 * math.pi * j / slices
            pos.append((math.cos(phi), y, math.sin(phi)))
            nrm.append((0.0, ny, 0.0))
            uv.append((0.5 + 0.5 * math.cos(phi), 0.5 + 0.5 * math.sin(phi)))
        for j in range(slices):
            a, b = ring + j, ring + (j + 1) % slices
            idx += [centre, b, a] if ny > 0 else [centre, a, b]
    return pos, nrm, uv, idx


def plane_mesh():
    """Unit square in XZ facing +Y."""
    pos = [(-0.5, 0, -0.5), (0.5, 0, -0.5), (0.5, 0, 0.5), (-0.5, 0, 0.5)]
    return pos, [(0, 1, 0)] * 4, [(0, 0), (1, 0), (1, 1), (0, 1)], [0, 2, 1, 0, 3, 2]


class GltfWriter:
    def __init__(self, name):
        self.bin = bytearray()
        self.doc = {"asset": {"version": "2.0", "generator": "raybudget tools/make_default_scene.py"},
                    "scene": 0, "scenes": [{"name": name, "nodes": []}], "nodes": [], "meshes": [],
                    "materials": [], "accessors": [], "bufferViews": [], "buffers": [],
                    "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior",
                                       "KHR_materials_volume", "KHR_materials_emissive_strength"],
                    "extensions": {"KHR_lights_punctual": {"lights": []}}, "cameras": []}

    def _view(self, data, target):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data), "target": target})
        self.bin += data
        return len(self.doc["bufferViews"]) - 1

    def _accessor(self, values, kind, minmax=False):
        comps = {"VEC2": 2, "VEC3": 3, "SCALAR": 1}[kind]
        if kind == "SCALAR":
            data = struct.pack("<%dI" % len(values), *values)
            acc = {"componentType": 5125, "count": len(values), "type": kind, "bufferView": self._view(data, 34963)}
        else:
            flat = [c for v in values for c in v]
            data = struct.pack("<%df" % len(flat), *flat)
            acc = {"componentType": 5126, "count": len(values), "type": kind, "bufferView": self._view(data, 34962)}
            if minmax:
                acc["min"] = [min(v[k] for v in values) for k in range(comps)]
                acc["max"] = [max(v[k] for v in values) for k in range(comps)]
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def mesh(self, name, geometry, material):
        pos, nrm, uv, idx = geometry
        prim = {"attributes": {"POSITION": self._accessor(pos, "VEC3", True), "NORMAL": self._accessor(nrm, "VEC3"),
                               "TEXCOORD_0": self._accessor(uv, "VEC2")},
                "indices": self._accessor(idx, "SCALAR"), "material": material}
        self.doc["meshes"].append({"name": name, "primitives": [prim]})
        return len(self.doc["meshes"]) - 1

    def material(self, name, color, metallic=0.0, roughness=0.6, transmission=0.0, ior=None, volume=None, emissive=None):
        m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(color) + [1.0], "metallicFactor": metallic,
                                                    "roughnessFactor": roughness}}
        ext = {}
        if transmission > 0:
            ext["KHR_materials_transmission"] = {"transmissionFactor": transmission}
        if ior is not None:
            ext["KHR_materials_ior"] = {"ior": ior}
        if volume is not None:
            ext["KHR_materials_volume"] = volume
        if emissive is not None:
            m["emissiveFactor"] = list(emissive[0])
            ext["KHR_materials_emissive_strength"] = {"emissiveStrength": emissive[1]}
        if ext:
            m["extensions"] = ext
        self.doc["materials"].append(m)
        return len(self.doc["materials"]) - 1

    def node(self, name, mesh=None, t=(0, 0, 0), s=(1, 1, 1), r=None, params=None, light=None, camera=None):
        n = {"name": name, "translation": [round(v, 4) for v in t]}
        if s != (1, 1, 1):
            n["scale"] = [round(v, 4) for v in s]
        if r is not None:
            # glTF requires unit quaternions (the loader normalizes others with a warning).
            length = math.sqrt(sum(v * v for v in r))
            n["rotation"] = [round(v / length, 7) for v in r]
        if mesh is not None:
            n["mesh"] = mesh
        if params is not None:
            n["extras"] = {"raybudget": params}
        if light is not None:
            n["extensions"] = {"KHR_lights_punctual": {"light": light}}
        if camera is not None:
            n["camera"] = camera
        self.doc["nodes"].append(n)
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)

    def light(self, light):
        self.doc["extensions"]["KHR_lights_punctual"]["lights"].append(light)
        return len(self.doc["extensions"]["KHR_lights_punctual"]["lights"]) - 1

    def write(self, out_dir, name):
        os.makedirs(out_dir, exist_ok=True)
        self.doc["buffers"] = [{"uri": name + ".bin", "byteLength": len(self.bin)}]
        with open(os.path.join(out_dir, name + ".bin"), "wb") as f:
            f.write(bytes(self.bin))
        with open(os.path.join(out_dir, name + ".gltf"), "w", newline="\n") as f:
            json.dump(self.doc, f, indent=1, sort_keys=True)
            f.write("\n")


def yaw(angle):
    """Quaternion (x, y, z, w) rotating `angle` radians about +Y."""
    return (0.0, math.sin(angle / 2), 0.0, math.cos(angle / 2))


def materials(g):
    return {
        "floor": g.material("floor", (0.55, 0.52, 0.48), roughness=0.85),
        "wall": g.material("wall", (0.75, 0.72, 0.66), roughness=0.9),
        "mirror": g.material("mirror", (0.95, 0.95, 0.97), metallic=1.0, roughness=0.02),
        "chrome": g.material("chrome", (0.9, 0.9, 0.92), metallic=1.0, roughness=0.08),
        "gold": g.material("gold", (1.0, 0.78, 0.34), metallic=1.0, roughness=0.3),
        "glass": g.material("glass", (1.0, 1.0, 1.0), roughness=0.0, transmission=1.0, ior=1.5),
        "tinted": g.material("tinted glass", (1.0, 1.0, 1.0), roughness=0.05, transmission=1.0, ior=1.45,
                             volume={"thicknessFactor": 0.8, "attenuationDistance": 1.2,
                                     "attenuationColor": [0.4, 0.85, 0.7]}),
        "stone": g.material("stone", (0.62, 0.6, 0.57), roughness=0.7),
        "red": g.material("red plastic", (0.75, 0.12, 0.1), roughness=0.35),
        "blue": g.material("blue plastic", (0.1, 0.25, 0.7), roughness=0.4),
        "wood": g.material("wood", (0.45, 0.3, 0.18), roughness=0.75),
        "lamp": g.material("lamp", (1.0, 0.9, 0.7), emissive=((1.0, 0.85, 0.6), 6.0)),
    }


def build():
    g = GltfWriter("court")
    rnd = Lcg(20241124)
    m = materials(g)
    cube = {k: g.mesh("cube_" + k, box_mesh(), m[k]) for k in ("wall", "mirror", "stone", "red", "blue", "wood", "tinted", "lamp")}
    sphere = {k: g.mesh("sphere_" + k, sphere_mesh(), m[k]) for k in ("chrome", "glass", "gold", "red", "blue", "stone")}
    pillar = g.mesh("pillar", cylinder_mesh(), m["stone"])
    floor = g.mesh("floor", plane_mesh(), m["floor"])

    # The court: 24 x 24 floor, walls on three sides (open towards +z where the camera is).
    g.node("floor", floor, t=(0, 0, 0), s=(24, 1, 24))
    g.node("wall_back", cube["wall"], t=(0, 3, -12), s=(24, 6, 0.4))
    g.node("wall_left", cube["wall"], t=(-12, 3, 0), s=(0.4, 6, 24))
    g.node("wall_right", cube["wall"], t=(12, 3, 0), s=(0.4, 6, 24))
    # Mirrors and glass carry authored priorities: what a level designer would mark.
    g.node("mirror_panel", cube["mirror"], t=(0, 2.6, -11.7), s=(7, 4, 0.1), params={"K": 3.0, "I": 0.5})
    g.node("chrome_sphere", sphere["chrome"], t=(-3.2, 1.2, -3.5), s=(1.2, 1.2, 1.2), params={"K": 2.0, "I": 0.5})
    g.node("glass_sphere", sphere["glass"], t=(2.4, 1.0, -1.5), s=(1.0, 1.0, 1.0), params={"K": 2.5, "Q": 4.0, "I": 0.5})
    g.node("glass_block", cube["tinted"], t=(5.2, 0.9, -4.5), s=(1.4, 1.8, 0.8), r=yaw(0.5), params={"K": 1.5, "I": 0.5})
    g.node("gold_sphere", sphere["gold"], t=(-6.5, 0.8, 2.0), s=(0.8, 0.8, 0.8), params={"K": 1.2})
    # Pillars along the side walls.
    for i, z in enumerate((-9, -4, 1, 6)):
        for side in (-1, 1):
            g.node("pillar_%d_%s" % (i, "l" if side < 0 else "r"), pillar, t=(side * 9.5, 0, z), s=(0.45, 5.5, 0.45))
    # Crates near the back, a lamp post.
    for i, (x, z, size) in enumerate(((-7.5, -8.5, 1.6), (-5.6, -9.0, 1.1), (7.2, -8.2, 1.4))):
        g.node("crate_%d" % i, cube["wood"], t=(x, size / 2, z), s=(size, size, size), r=yaw(0.3 * i))
    g.node("lamp_post", pillar, t=(6.5, 0, 3.5), s=(0.08, 2.6, 0.08))
    g.node("lamp", cube["lamp"], t=(6.5, 2.75, 3.5), s=(0.35, 0.3, 0.35), params={"Q": 0.0})
    # Scattered small objects, near to far: the crowd the budget must choose from.
    kinds = [sphere["red"], sphere["blue"], sphere["stone"], cube["red"], cube["blue"], cube["stone"]]
    for i in range(26):
        x, z = rnd.uniform(-8.5, 8.5), rnd.uniform(-10.5, 7.5)
        size = rnd.uniform(0.25, 0.9)
        mesh = kinds[i % len(kinds)]
        is_sphere = mesh in (sphere["red"], sphere["blue"], sphere["stone"])
        y = size if is_sphere else size / 2
        s = (size, size, size) if is_sphere else (size, size * rnd.uniform(0.6, 1.8), size)
        if not is_sphere:
            y = s[1] / 2
        g.node("small_%02d" % i, mesh, t=(x, y, z), s=s, r=None if is_sphere else yaw(rnd.uniform(0, math.pi)))

    # A few objects close to the camera: large on screen, off-centre.
    g.node("near_sphere", sphere["blue"], t=(-2.2, 0.45, 8.6), s=(0.45, 0.45, 0.45))
    g.node("near_crate", cube["wood"], t=(2.6, 0.35, 8.9), s=(0.7, 0.7, 0.7), r=yaw(0.7))

    # Lights: a warm sun, two point lights, a spot on the mirror side.
    sun = g.light({"name": "sun", "type": "directional", "color": [1.0, 0.95, 0.88], "intensity": 3.0})
    g.node("sun", t=(0, 10, 0), r=(-0.3826834, 0.1830127, 0.0, 0.9054839), light=sun)
    p1 = g.light({"name": "warm point", "type": "point", "color": [1.0, 0.75, 0.45], "intensity": 18.0, "range": 14.0})
    g.node("point_warm", t=(6.5, 3.3, 3.5), light=p1)
    p2 = g.light({"name": "cool point", "type": "point", "color": [0.55, 0.7, 1.0], "intensity": 14.0, "range": 12.0})
    g.node("point_cool", t=(-6.0, 3.8, -6.0), light=p2)
    spot = g.light({"name": "spot", "type": "spot", "color": [1.0, 1.0, 0.95], "intensity": 60.0, "range": 20.0,
                    "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.5}})
    # Points down and back at the chrome sphere from above the camera.
    g.node("spot", t=(-1.5, 7.0, 4.0), r=(-0.5, 0.0, 0.0, 0.8660254), light=spot)

    g.doc["cameras"].append({"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.1, "zfar": 80.0}})
    # Standing at the open side, slightly above eye height, looking into the court.
    g.node("camera", t=(0, 3.2, 13.5), r=(-0.0998334, 0.0, 0.0, 0.9950042), camera=0)
    return g


def build_level():
    """The plaza: a level whose budget must choose among many objects at every distance."""
    g = GltfWriter("plaza")
    rnd = Lcg(20261201)
    m = materials(g)
    m["brass"] = g.material("brushed brass", (0.95, 0.8, 0.5), metallic=1.0, roughness=0.2)
    m["green"] = g.material("green paint", (0.2, 0.5, 0.25), roughness=0.55)
    m["cloth"] = g.material("awning cloth", (0.8, 0.65, 0.3), roughness=0.9)
    cube = {k: g.mesh("cube_" + k, box_mesh(), m[k])
            for k in ("wall", "mirror", "stone", "red", "blue", "wood", "tinted", "lamp", "green", "cloth")}
    sphere = {k: g.mesh("sphere_" + k, sphere_mesh(), m[k]) for k in ("chrome", "glass", "gold", "red", "blue", "stone", "brass")}
    pillar = g.mesh("pillar", cylinder_mesh(), m["stone"])
    brass_post = g.mesh("brass_post", cylinder_mesh(), m["brass"])
    floor = g.mesh("floor", plane_mesh(), m["floor"])

    # The square: 64 x 64, walls on the far and side edges, a raised centre platform.
    g.node("floor", floor, s=(64, 1, 64))
    g.node("wall_back", cube["wall"], t=(0, 4, -32), s=(64, 8, 0.6))
    g.node("wall_left", cube["wall"], t=(-32, 4, 0), s=(0.6, 8, 64))
    g.node("wall_right", cube["wall"], t=(32, 4, 0), s=(0.6, 8, 64))
    g.node("platform", cube["stone"], t=(0, 0.25, -6), s=(12, 0.5, 12))
    # Reflective and transmissive centrepieces, near and far, with authored priorities.
    g.node("mirror_back", cube["mirror"], t=(0, 3.5, -31.6), s=(14, 6, 0.1), params={"K": 3.0, "I": 0.5})
    g.node("mirror_left", cube["mirror"], t=(-31.6, 2.5, -10), s=(0.1, 4, 9), params={"K": 2.0, "I": 0.5})
    g.node("mirror_stand", cube["mirror"], t=(9, 1.6, 6), s=(3, 3, 0.1), r=yaw(-0.6), params={"K": 2.0, "I": 0.5})
    g.node("chrome_centre", sphere["chrome"], t=(0, 2.5, -6), s=(2, 2, 2), params={"K": 2.5, "I": 0.5})
    g.node("glass_centre", sphere["glass"], t=(-4, 1.7, -3), s=(1.2, 1.2, 1.2), params={"K": 2.5, "Q": 4.0, "I": 0.5})
    g.node("glass_block_centre", cube["tinted"], t=(4, 1.5, -3), s=(1.6, 2, 1), r=yaw(0.4), params={"K": 1.5, "I": 0.5})
    for i, (x, z) in enumerate(((-18, -20), (20, -22), (-12, 14), (16, 12))):
        g.node("chrome_%d" % i, sphere["chrome"], t=(x, 0.9, z), s=(0.9, 0.9, 0.9), params={"K": 1.5})
        g.node("glass_%d" % i, sphere["glass"], t=(x + 2.2, 0.7, z + 1.0), s=(0.7, 0.7, 0.7), params={"Q": 4.0})
    for i, (x, z, a) in enumerate(((-22, -4, 0.3), (24, -8, -0.5), (-6, 20, 1.1))):
        g.node("glass_pane_%d" % i, cube["tinted"], t=(x, 1.4, z), s=(2.4, 2.8, 0.2), r=yaw(a))
    # Arcades: pillars along both sides, brass posts around the platform.
    for i in range(9):
        z = -26 + 6.5 * i
        for side in (-1, 1):
            g.node("pillar_%d_%s" % (i, "l" if side < 0 else "r"), pillar, t=(side * 27, 0, z), s=(0.6, 7, 0.6))
    for i in range(8):
        a = 2 * math.pi * i / 8
        g.node("post_%d" % i, brass_post, t=(7.5 * math.cos(a), 0, -6 + 7.5 * math.sin(a)), s=(0.12, 1.4, 0.12))
    # Market stalls: a counter, an awning, goods on top.
    for i, (x, z, a) in enumerate(((-16, -8, 0.2), (-15, 2, -0.1), (15, -4, 0.4), (17, 4, -0.3), (-8, -18, 0.0), (8, -18, 0.1))):
        g.node("stall_%d_counter" % i, cube["wood"], t=(x, 0.5, z), s=(3, 1, 1.4), r=yaw(a))
        g.node("stall_%d_awning" % i, cube["cloth"], t=(x, 2.4, z), s=(3.4, 0.1, 2), r=yaw(a))
        for k in range(3):
            kind = (sphere["red"], sphere["gold"], cube["green"])[(i + k) % 3]
            g.node("stall_%d_good_%d" % (i, k), kind, t=(x + (k - 1) * 0.9, 1.2, z), s=(0.2, 0.2, 0.2))
    # Crates in stacks near the walls.
    for i in range(12):
        x, z = rnd.uniform(-29, 29), rnd.uniform(-29, -22) if i % 2 else rnd.uniform(-29, 29)
        if i % 2 == 0:
            x = rnd.uniform(-30, -24) if i % 4 == 0 else rnd.uniform(24, 30)
        size = rnd.uniform(0.8, 1.8)
        g.node("crate_%02d" % i, cube["wood"], t=(x, size / 2, z), s=(size, size, size), r=yaw(rnd.uniform(0, 1.5)))
    # Lamp posts with emissive heads.
    for i, (x, z) in enumerate(((-10, -12), (10, -12), (-10, 8), (10, 8))):
        g.node("lamp_post_%d" % i, pillar, t=(x, 0, z), s=(0.08, 3.2, 0.08))
        g.node("lamp_%d" % i, cube["lamp"], t=(x, 3.35, z), s=(0.4, 0.3, 0.4), params={"Q": 0.0})
    # The crowd: small props everywhere, near to far.
    kinds = [sphere["red"], sphere["blue"], sphere["stone"], sphere["brass"], cube["red"], cube["blue"], cube["stone"], cube["green"]]
    for i in range(60):
        x, z = rnd.uniform(-26, 26), rnd.uniform(-28, 26)
        if abs(x) < 7 and -13 < z < 1:  # off the platform
            z += 16
        size = rnd.uniform(0.2, 1.0)
        mesh = kinds[i % len(kinds)]
        if mesh in (sphere["red"], sphere["blue"], sphere["stone"], sphere["brass"]):
            g.node("prop_%02d" % i, mesh, t=(x, size, z), s=(size, size, size))
        else:
            h = size * rnd.uniform(0.6, 2.0)
            g.node("prop_%02d" % i, mesh, t=(x, h / 2, z), s=(size, h, size), r=yaw(rnd.uniform(0, math.pi)))
    # Close to the camera: large on screen.
    g.node("near_sphere", sphere["blue"], t=(-3, 0.6, 25), s=(0.6, 0.6, 0.6))
    g.node("near_crate", cube["wood"], t=(3.5, 0.45, 26), s=(0.9, 0.9, 0.9), r=yaw(0.5))
    g.node("near_chrome", sphere["chrome"], t=(6, 0.5, 23), s=(0.5, 0.5, 0.5), params={"K": 1.5})

    sun = g.light({"name": "sun", "type": "directional", "color": [1.0, 0.96, 0.9], "intensity": 3.0})
    g.node("sun", t=(0, 20, 0), r=(-0.4226183, 0.2418448, 0.1148070, 0.8660254), light=sun)
    for i, (x, z, color) in enumerate(((-10, -12, [1.0, 0.75, 0.45]), (10, 8, [1.0, 0.8, 0.55]), (-18, 10, [0.55, 0.7, 1.0]))):
        light = g.light({"name": "point %d" % i, "type": "point", "color": color, "intensity": 40.0, "range": 18.0})
        g.node("point_%d" % i, t=(x, 3.9 if i < 2 else 4.5, z), light=light)
    spot = g.light({"name": "spot", "type": "spot", "color": [1.0, 1.0, 0.95], "intensity": 120.0, "range": 30.0,
                    "spot": {"innerConeAngle": 0.25, "outerConeAngle": 0.45}})
    g.node("spot", t=(0, 12, 4), r=(-0.5, 0.0, 0.0, 0.8660254), light=spot)

    g.doc["cameras"].append({"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.1, "zfar": 150.0}})
    g.node("camera", t=(0, 4.0, 31), r=(-0.0871557, 0.0, 0.0, 0.9961947), camera=0)
    return g


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "data")
    for folder, name, scene in (("default", "court", build()), ("plaza", "plaza", build_level())):
        scene.write(os.path.join(out, folder), name)
        print("wrote", os.path.join(out, folder, name + ".gltf"))


if __name__ == "__main__":
    main()
