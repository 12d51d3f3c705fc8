#!/usr/bin/env python3
"""Writes a corpus of hostile inputs for test_hostile_inputs.cpp.

    make_hostile.py OUT_DIR

Every case is a config (plus, for some, a glTF file or a special path) that a
user, a script gone wrong or an attacker could hand to `shadowbench validate`
and `shadowbench run`. OUT_DIR/manifest.json lists them with the exit codes
each command may give: 0 (runs), 1 (a job failed, the others kept) or 2 (bad
input, named). None may crash, hang, exit 3 or use more than 1 GiB.
"""
import base64
import json
import os
import struct
import sys
import zlib

OUT = os.path.abspath(sys.argv[1])
HERE = os.path.dirname(os.path.abspath(__file__))
GLTF_CORPUS = os.path.join(HERE, "..", "gltf", "corpus")
cases = []


def valid(**over):
    c = {"name": "hostile",
         "scenes": [{"type": "sphere_grid", "params": {"grid": 2}}],
         "techniques": ["none"],
         "resolutions": [[24, 16]],
         "frames": {"warmup": 0, "timed": 1},
         "reference": {"spp": 4, "cache": False}}
    c.update(over)
    return c


def add(name, text, validate=(2,), run=None, path=None, out=None, seconds=None):
    """text: str/bytes written to configs/<name>.json, or None when `path` is given;
    seconds: a tighter bound than the test's wall limit on each command."""
    if path is None:
        path = os.path.join(OUT, "configs", name + ".json")
        data = text.encode() if isinstance(text, str) else text
        with open(path, "wb") as f:
            f.write(data)
    cases.append({"name": name, "config": path, "validate": list(validate),
                  "run": list(run if run is not None else validate), "out": out,
                  "seconds": seconds})


def add_json(name, doc, **kw):
    add(name, json.dumps(doc), **kw)


def scene(type_, **params):
    return {"type": type_, "params": params}


os.makedirs(os.path.join(OUT, "configs"), exist_ok=True)
os.makedirs(os.path.join(OUT, "gltf"), exist_ok=True)

# ---- JSON that is not a config ----------------------------------------------
add("empty", "")
add("null", "null")
add("array", "[]")
add("string", '"x"')
add("truncated", json.dumps(valid())[:-7])
add("bom_then_json", b"\xef\xbb\xbf" + json.dumps(valid()).encode(), validate=(0, 2))
add("nul_byte_in_text", json.dumps(valid()).replace('"hostile"', '"host\x00ile"'))
add("deep_arrays", '{"scenes": ' + "[" * 100000 + "]" * 100000 + "}")
add("deep_objects", '{"description": ' + '{"a":' * 100000 + "1" + "}" * 100000 + "}")
add("deep_65", json.dumps(valid(description=None)).replace(
    '"description": null', '"description": ' + "[" * 65 + "]" * 65))
add("invalid_utf8_in_string", json.dumps(valid()).encode().replace(b'"hostile"', b'"ho\xffst"'))
add("overlong_utf8", json.dumps(valid()).encode().replace(b'"hostile"', b'"\xc0\xaf"'))
add("number_overflow", json.dumps(valid()).replace('"spp": 4', '"spp": 1e400'))
add("negative_overflow", json.dumps(valid()).replace('"spp": 4', '"spp": -1e400'))
add("huge_integer", json.dumps(valid()).replace('"spp": 4', '"spp": 123456789012345678901234567890'))
add("tiny_float_seed", json.dumps(valid()).replace('"spp": 4', '"spp": 4, "seed": 1e-400'))
add("duplicate_key", json.dumps(valid()).replace('"spp": 4', '"spp": 4, "spp": 8'))
add("duplicate_top_key", json.dumps(valid())[:-1] + ', "name": "again"}')

# ---- names and labels ---------------------------------------------------------
add_json("name_5000", valid(name="n" * 5000))
add_json("name_dotdot", valid(name=".."))
add_json("name_slash", valid(name="a/b"))
add_json("name_nul", valid(name="a\u0000b"))
add_json("name_unicode", valid(name="schätzung"))
add_json("label_300", valid(techniques=[{"name": "none", "label": "L" * 300}]))
add_json("label_nul", valid(techniques=[{"name": "none", "label": "a\u0000b"}]))
add_json("label_newline", valid(techniques=[{"name": "none", "label": "a\nb"}]))
add_json("label_empty", valid(techniques=[{"name": "none", "label": ""}]))
add_json("label_dotdot", valid(techniques=[{"name": "none", "label": "../../x"}]), validate=(0,))
add_json("label_dot_hidden", valid(techniques=[{"name": "none", "label": ".hidden"}]), validate=(0,))
add_json("label_markup", valid(techniques=[{"name": "none", "label": "a|b <script>x</script> [l](u)"}]),
         validate=(0,))
add_json("labels_greek", valid(techniques=[{"name": "none", "label": "α"}, {"name": "none", "label": "β"}]),
         validate=(0,))
add_json("labels_space_dash", valid(techniques=[{"name": "none", "label": "x y"},
                                                {"name": "none", "label": "x-y"}]), validate=(0,))
add_json("labels_slash_dashes", valid(techniques=[{"name": "none", "label": "a/b"},
                                                  {"name": "none", "label": "a--b"}]), validate=(0,))
add_json("same_label_twice", valid(techniques=[{"name": "none", "label": "t"},
                                               {"name": "shadow_map", "label": "t"}]))
add_json("scene_label_200", valid(scenes=[{"type": "sphere_grid", "label": "S" * 200,
                                           "params": {"grid": 2}}]), validate=(0,))

# ---- sizes: checked before anything is expanded, built or allocated --------------
big = list(range(1, 100001))
add_json("sweep_1e5_by_1e5", valid(techniques=[{"name": "pcf_box",
                                                "params": {"size": big, "k": [1] * 100000}}]))
add_json("jobs_1e10", valid(scenes=[scene("sphere_grid", grid=list(range(1, 101)),
                                          layers=list(range(1, 65)))],
                            techniques=[{"name": "pcf_box", "params": {"size": list(range(16, 1016)),
                                                                        "k": [1, 3, 5, 7, 9]}}],
                            resolutions=[[w, 8] for w in range(1, 101)]))
add_json("jobs_just_over", valid(techniques=[{"name": "shadow_map",
                                              "params": {"size": list(range(16, 10017))}}]))
add_json("sphere_grid_max", valid(scenes=[scene("sphere_grid", grid=256, layers=64, slices=1024,
                                                stacks=1024)]))
add_json("foliage_max", valid(scenes=[scene("foliage", trees=256, depth=6, branches=6,
                                            leaves_per_branch=64, segments=64)]))
add_json("jeep_max", valid(scenes=[scene("jeep", count=1024, tessellation=128)]))
add_json("resolution_16k", valid(resolutions=[[16384, 16384]]))
add_json("resolution_overflow", valid(resolutions=["99999999999x1"]))
add_json("resolution_triple", valid(resolutions=["8x8x8"]))
add_json("resolution_twice", valid(resolutions=[[24, 16], "24x16"]))
add_json("spp_zero", valid(reference={"spp": 0}))
add_json("spp_over", valid(reference={"spp": 2 ** 21}))
with open(os.path.join(OUT, "configs", "big_file.json"), "w") as f:
    f.write(json.dumps(valid(description="d" * (17 << 20))))
add("big_file", None, path=os.path.join(OUT, "configs", "big_file.json"))

# ---- paths that are not config files --------------------------------------------
add("dev_zero", None, path="/dev/zero")
add("a_directory", None, path=os.path.join(OUT, "configs"))
add("missing_file", None, path=os.path.join(OUT, "configs", "no_such.json"))
fifo = os.path.join(OUT, "configs", "fifo.json")
if not os.path.exists(fifo):
    os.mkfifo(fifo)
add("fifo", None, path=fifo)
add_json("non_utf8_config_name", valid(), validate=(0,))
os.replace(os.path.join(OUT, "configs", "non_utf8_config_name.json"),
           os.path.join(OUT.encode(), b"configs", b"non_utf8_\xff.json").decode("utf-8", "surrogateescape"))
cases[-1]["config"] = os.path.join(OUT, "configs", "non_utf8_\udcff.json")
add_json("non_utf8_out", valid(), validate=(0,), out=os.path.join(OUT, "runs", "out_\udcfe"))

# ---- setups that would measure nothing ------------------------------------------
add_json("eye_is_target", valid(scenes=[{"type": "sphere_grid", "camera": {"eye": [1, 2, 3], "target": [1, 2, 3]}}]))
add_json("up_along_view", valid(scenes=[{"type": "sphere_grid", "camera": {"eye": [0, 9, 0], "target": [0, 0, 0], "up": [0, 1, 0]}}]))
add_json("up_along_default_view", valid(scenes=[{"type": "sphere_grid", "camera": {"up": [0, 0, -1]}}]),
         validate=(0, 2))
add_json("up_zero", valid(scenes=[{"type": "sphere_grid", "camera": {"up": [0, 0, 0]}}]))
add_json("fov_underflow", valid(scenes=[{"type": "sphere_grid", "camera": {"fov_y": 1e-40}}]))
add_json("near_after_far", valid(scenes=[{"type": "sphere_grid", "camera": {"near": 50, "far": 1}}]))
add_json("far_before_default_near", valid(scenes=[{"type": "sphere_grid", "camera": {"far": 0.01}}]))
add_json("eye_3e38", valid(scenes=[{"type": "sphere_grid", "camera": {"eye": [3e38, 1, 1]}}]))
add_json("light_3e38", valid(scenes=[{"type": "sphere_grid", "light": {"center": [0, 3e38, 0]}}]))
add_json("light_intensity_1e300", valid(scenes=[{"type": "sphere_grid", "light": {"intensity": 1e300}}]))
add_json("light_size_1e300", valid(scenes=[{"type": "sphere_grid", "light": {"size": 1e300}}]))
add_json("light_on_target", valid(scenes=[{"type": "sphere_grid", "light": {"center": [0, 5, 0], "target": [0, 5, 0]}}]))
add_json("unknown_technique", valid(techniques=["nope"]))
add_json("unknown_param", valid(techniques=[{"name": "pcf_box", "params": {"q": 1}}]))
add_json("param_nul_string", valid(techniques=[{"name": "shadow_map", "params": {"cull": "ba\u0000ck"}}]))


# ---- glTF files ---------------------------------------------------------------------
def gltf_config(name, gltf_path, **kw):
    add_json(name, valid(scenes=[{"type": "gltf", "params": {"file": gltf_path}}]), **kw)


def data_uri(payload):
    return "data:application/octet-stream;base64," + base64.b64encode(payload).decode()


def tri_gltf(positions, extra_node=None):
    binary = struct.pack("<9f", *positions) + struct.pack("<3H", 0, 1, 2) + b"\0\0"
    node = {"mesh": 0}
    node.update(extra_node or {})
    return {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [node],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
            "buffers": [{"byteLength": len(binary), "uri": data_uri(binary)}],
            "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                            {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                           "min": [min(positions[0::3]), min(positions[1::3]), min(positions[2::3])],
                           "max": [max(positions[0::3]), max(positions[1::3]), max(positions[2::3])]},
                          {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]}


def write_gltf(name, doc):
    path = os.path.join(OUT, "gltf", name + ".gltf")
    with open(path, "w") as f:
        json.dump(doc, f)
    return path


# Every file of the glTF corpus, now through a config and the run.
for f in sorted(os.listdir(GLTF_CORPUS)):
    if f.endswith((".gltf", ".glb")):
        gltf_config("gltf_corpus_" + os.path.splitext(f)[0], os.path.join(GLTF_CORPUS, f))

# 200,000 nodes of one instanced triangle, as a chain 200,000 deep and as
# 200,000 roots: receiver inference asked each planar instance about every
# vertex of the scene, O(n²), and `validate` did not finish in 10 minutes.
# Now about 2 s for validate and 4 s for run, idle 2-core VM.
def many_nodes(count, chain):
    doc = tri_gltf([0, 0, 0, 1, 0, 0, 0, 1, 0])
    if chain:
        doc["nodes"] = [{"mesh": 0, "children": [i + 1]} for i in range(count - 1)] + [{"mesh": 0}]
    else:
        doc["nodes"] = [{"mesh": 0} for _ in range(count)]
        doc["scenes"] = [{"nodes": list(range(count))}]
    return doc


gltf_config("gltf_200k_node_chain", write_gltf("node_chain", many_nodes(200000, True)),
            validate=(0,), seconds=20)
gltf_config("gltf_200k_instances", write_gltf("instances", many_nodes(200000, False)),
            validate=(0,), seconds=20)
gltf_config("gltf_zero_area", write_gltf("zero_area", tri_gltf([0, 0, 0, 1, 0, 0, 2, 0, 0])))
gltf_config("gltf_positions_3e38", write_gltf("far", tri_gltf([0, 0, 0, 3e38, 0, 0, 0, 3e38, 0])))
gltf_config("gltf_scale_1e30", write_gltf("scale", tri_gltf([0, 0, 0, 1, 0, 0, 0, 1, 0],
                                                             {"scale": [1e30, 1e30, 1e30]})))
doc = tri_gltf([0, 0, 0, 1, 0, 0, 0, 1, 0])
doc["accessors"][0]["count"] = 300000000
gltf_config("gltf_count_3e8", write_gltf("count_3e8", doc))
doc = tri_gltf([0, 0, 0, 1, 0, 0, 0, 1, 0])
doc["nodes"][0]["extras"] = "DEEP"
deep_path = write_gltf("deep_extras", doc)
with open(deep_path) as f:
    text = f.read().replace('"DEEP"', "[" * 100000 + "]" * 100000)
with open(deep_path, "w") as f:
    f.write(text)
gltf_config("gltf_deep_extras", deep_path)
doc = tri_gltf([0, 0, 0, 1, 0, 0, 0, 1, 0])
doc["images"] = [{"uri": "%FF%FE.png"}]
doc["textures"] = [{"source": 0}]
doc["materials"] = [{"alphaMode": "MASK",
                     "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
doc["meshes"][0]["primitives"][0]["material"] = 0
gltf_config("gltf_non_utf8_image_uri", write_gltf("non_utf8_uri", doc))


def png(width, height):
    """A grey PNG, compressed in rows so that it stays small on disk."""
    raw = zlib.compressobj(9)
    row = b"\0" + b"\x80" * width
    body = b"".join(raw.compress(row) for _ in range(height)) + raw.flush()

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0))
            + chunk(b"IDAT", body) + chunk(b"IEND", b""))


# Six 8192² textures: 6 × 64 Mi texels decoded, from a few hundred kilobytes.
image = png(8192, 8192)
doc = tri_gltf([0, 0, 0, 1, 0, 0, 0, 1, 0])
doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(image).decode()}
                 for _ in range(6)]
doc["textures"] = [{"source": i} for i in range(6)]
doc["materials"] = [{"alphaMode": "MASK", "pbrMetallicRoughness": {"baseColorTexture": {"index": i}}}
                    for i in range(6)]
uv = struct.pack("<6f", 0, 0, 1, 0, 0, 1)
binary = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<3H", 0, 1, 2) + b"\0\0" + uv
doc["buffers"] = [{"byteLength": len(binary), "uri": data_uri(binary)}]
doc["bufferViews"].append({"buffer": 0, "byteOffset": 44, "byteLength": 24})
doc["accessors"].append({"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"})
doc["meshes"] = [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 2}, "indices": 1,
                                  "material": i}]} for i in range(6)]
doc["nodes"] = [{"mesh": i} for i in range(6)]
doc["scenes"] = [{"nodes": list(range(6))}]
gltf_config("gltf_six_big_textures", write_gltf("textures", doc))
gltf_config("gltf_dev_zero", "/dev/zero")
gltf_config("gltf_missing", os.path.join(OUT, "gltf", "missing.gltf"))

# Paths go as hex of their bytes: some are not UTF-8 on purpose.
for c in cases:
    for key in ("config", "out"):
        if c[key] is not None:
            c[key] = os.fsencode(c[key]).hex()
with open(os.path.join(OUT, "manifest.json"), "w") as f:
    json.dump(cases, f, indent=1)
print(f"{len(cases)} hostile cases in {OUT}")
