#!/usr/bin/env python3
"""Writes issue 65's heavy-instancing case: a glTF with COUNT nodes that all
reference one 14-triangle mesh (a heptagonal bipyramid, closed and convex)
at one place above a ground quad, and a two-job config for it.

    bench/instanced_case.py OUT_DIR [COUNT [TECHNIQUE]] [--flat] [--scale=S]

COUNT defaults to 200000 (2.8 M triangles after instancing), TECHNIQUE to
shadow_map. OUT_DIR gets instances.glb (a few MB: never commit it) and
instances.json: `none` and TECHNIQUE at 160x120 with the default frame
counts, the 16-spp Monte Carlo reference, no cache. Timed by hand:

    /usr/bin/time build/shadowbench run OUT_DIR/instances.json --out OUT_DIR/run

(docs/performance.md, "Heavy instancing"). --scale=S scales the shared mesh
(default 1: 1 wide, 1.2 tall, over an 8 × 8 ground). At either scale
shadow_map's frames are fill-bound on llvmpipe: every copy covers the same
texels of the light map (200,000-fold overdraw; at 0.1 a copy still covers
about 1 % of the map, at 1 about a quarter), which is the technique's
measured work, not the harness's. With --flat the same triangles
are written as COUNT separate meshes (one node each) instead of one shared
mesh: the flattened twin the instanced scene must trace the same as.
"""
import json
import math
import os
import struct
import sys


def bipyramid():
    """9 vertices, 14 triangles, counter-clockwise seen from outside."""
    ring = [(0.5 * math.cos(2 * math.pi * k / 7), 0.0, -0.5 * math.sin(2 * math.pi * k / 7))
            for k in range(7)]
    pos = ring + [(0.0, 0.6, 0.0), (0.0, -0.6, 0.0)]
    idx = []
    for k in range(7):
        a, b = k, (k + 1) % 7
        idx += [a, b, 7]  # upper cone
        idx += [b, a, 8]  # lower cone
    return pos, idx


def ground():
    h = 4.0
    return [(-h, 0.0, -h), (h, 0.0, -h), (h, 0.0, h), (-h, 0.0, h)], [0, 2, 1, 0, 3, 2]


def pad4(b):
    return b + b"\0" * (-len(b) % 4)


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    flat = "--flat" in sys.argv
    scale = float(next((a.split("=", 1)[1] for a in sys.argv if a.startswith("--scale=")), 1.0))
    out = os.path.abspath(args[0])
    count = int(args[1]) if len(args) > 1 else 200000
    technique = args[2] if len(args) > 2 else "shadow_map"
    os.makedirs(out, exist_ok=True)

    binary = bytearray()
    views, accessors = [], []

    def add_mesh_data(pos, idx):
        nonlocal binary
        p = pad4(struct.pack("<%df" % (3 * len(pos)), *[c for v in pos for c in v]))
        views.append({"buffer": 0, "byteOffset": len(binary), "byteLength": 12 * len(pos)})
        binary += p
        lo = [min(v[i] for v in pos) for i in range(3)]
        hi = [max(v[i] for v in pos) for i in range(3)]
        accessors.append({"bufferView": len(views) - 1, "componentType": 5126,
                          "count": len(pos), "type": "VEC3", "min": lo, "max": hi})
        i = pad4(struct.pack("<%dI" % len(idx), *idx))
        views.append({"buffer": 0, "byteOffset": len(binary), "byteLength": 4 * len(idx)})
        binary += i
        accessors.append({"bufferView": len(views) - 1, "componentType": 5125,
                          "count": len(idx), "type": "SCALAR"})
        return {"primitives": [{"attributes": {"POSITION": len(accessors) - 2},
                                "indices": len(accessors) - 1}]}

    gpos, gidx = ground()
    meshes = [add_mesh_data(gpos, gidx)]
    bpos, bidx = bipyramid()
    bpos = [(scale * x, scale * y, scale * z) for x, y, z in bpos]
    # All instances at one place: 1.2 above the ground, the bipyramid's
    # centre at y = 1.2 (apex 1.8, bottom 0.6).
    place = [0.0, 1.2, 0.0]
    nodes = [{"name": "ground", "mesh": 0}]
    if flat:  # the same triangles, every one its own mesh, already in place
        moved = [(x + place[0], y + place[1], z + place[2]) for x, y, z in bpos]
        for _ in range(count):
            meshes.append(add_mesh_data(moved, bidx))
            nodes.append({"mesh": len(meshes) - 1})
    else:
        meshes.append(add_mesh_data(bpos, bidx))
        nodes += [{"mesh": 1, "translation": place} for _ in range(count)]

    doc = {"asset": {"version": "2.0", "generator": "bench/instanced_case.py"},
           "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes,
           "meshes": meshes, "buffers": [{"byteLength": len(binary)}],
           "bufferViews": views, "accessors": accessors}
    js = json.dumps(doc, separators=(",", ":")).encode()
    js += b" " * (-len(js) % 4)  # the JSON chunk is padded with spaces
    glb_name = "instances_flat.glb" if flat else "instances.glb"
    with open(os.path.join(out, glb_name), "wb") as f:
        total = 12 + 8 + len(js) + 8 + len(binary)
        f.write(struct.pack("<III", 0x46546C67, 2, total))
        f.write(struct.pack("<II", len(js), 0x4E4F534A) + js)
        f.write(struct.pack("<II", len(binary), 0x004E4942) + bytes(binary))

    config = {"name": "instances" + ("_flat" if flat else ""),
              "description": "issue 65: %d instances of one 14-triangle mesh at one place "
                             "(bench/instanced_case.py)" % count,
              "scenes": [{"type": "gltf", "label": "instances",
                          "params": {"file": glb_name}}],
              "techniques": ["none", technique] if technique != "none" else ["none"],
              "resolutions": [[160, 120]],
              "reference": {"spp": 16, "seed": 1, "cache": False}}
    with open(os.path.join(out, config["name"] + ".json"), "w") as f:
        json.dump(config, f, indent=2)
    print(os.path.join(out, config["name"] + ".json"))


if __name__ == "__main__":
    main()
