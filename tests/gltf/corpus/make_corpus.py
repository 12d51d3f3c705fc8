#!/usr/bin/env python3
"""Writes the broken glTF files of this folder (test_gltf_corpus.cpp reads them).

Each file is a one-triangle asset with one thing broken. Run from anywhere:
    python3 tests/gltf/corpus/make_corpus.py
"""
import base64
import copy
import json
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))

# One triangle: 3 float positions (36 bytes) then 3 uint16 indices (6 + 2 padding).
BIN = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<3H", 0, 1, 2) + b"\0\0"


def data_uri(payload):
    return "data:application/octet-stream;base64," + base64.b64encode(payload).decode()


def base():
    return {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "tri", "mesh": 0}],
        "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": len(BIN), "uri": data_uri(BIN)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 36},
            {"buffer": 0, "byteOffset": 36, "byteLength": 6},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
             "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"},
        ],
    }


def glb(doc, binary):
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    binary += b"\0" * (-len(binary) % 4)
    total = 12 + 8 + len(text) + 8 + len(binary)
    return (b"glTF" + struct.pack("<II", 2, total) + struct.pack("<I", len(text)) + b"JSON" +
            text + struct.pack("<I", len(binary)) + b"BIN\0" + binary)


def write(name, content):
    mode = "wb" if isinstance(content, bytes) else "w"
    with open(os.path.join(HERE, name), mode) as f:
        f.write(content)


def gltf(name, edit):
    doc = base()
    edit(doc)
    write(name, json.dumps(doc, indent=1) + "\n")


def glb_doc():
    doc = base()
    doc["buffers"] = [{"byteLength": len(BIN)}]
    return doc


def main():
    whole = glb(glb_doc(), BIN)
    write("truncated.glb", whole[: len(whole) // 2])
    bad_version = bytearray(whole)
    bad_version[4] = 1
    write("glb_version1.glb", bytes(bad_version))
    overrun = bytearray(whole)
    bin_header = len(whole) - 8 - len(BIN)
    overrun[bin_header:bin_header + 4] = struct.pack("<I", len(BIN) + 4)
    write("glb_bin_overrun.glb", bytes(overrun))
    write("json_syntax.gltf", json.dumps(base(), indent=1).replace('"meshes"', '"meshes" [', 1))

    gltf("accessor_past_view.gltf", lambda d: d["accessors"][0].update(count=4))
    gltf("accessor_offset_past_view.gltf", lambda d: d["accessors"][0].update(byteOffset=40))
    gltf("view_past_buffer.gltf", lambda d: d["bufferViews"][1].update(byteLength=64))
    gltf("bad_component_type.gltf", lambda d: d["accessors"][0].update(componentType=1234))
    gltf("huge_count.gltf", lambda d: d["accessors"][0].update(count=4000000000))
    gltf("wrong_type.gltf", lambda d: d["accessors"][0].update(type="VEC2"))

    def index_oob(d):  # indices 0, 1, 7: one past the three vertices... and more
        b = BIN[:36] + struct.pack("<3H", 0, 1, 7) + b"\0\0"
        d["buffers"][0]["uri"] = data_uri(b)
    gltf("index_out_of_range.gltf", index_oob)

    def sparse_oob(d):
        b = BIN + struct.pack("<I", 9) + struct.pack("<3f", 5, 5, 5)
        d["buffers"][0] = {"byteLength": len(b), "uri": data_uri(b)}
        d["bufferViews"] += [{"buffer": 0, "byteOffset": 44, "byteLength": 4},
                             {"buffer": 0, "byteOffset": 48, "byteLength": 12}]
        d["accessors"][0]["sparse"] = {"count": 1,
                                       "indices": {"bufferView": 2, "componentType": 5125},
                                       "values": {"bufferView": 3}}
    gltf("sparse_index_out_of_range.gltf", sparse_oob)

    gltf("absolute_uri.gltf", lambda d: d["buffers"][0].update(uri="/etc/passwd"))
    gltf("dotdot_uri.gltf", lambda d: d["buffers"][0].update(uri="../gltf/corpus/x.bin"))
    gltf("dotdot_escaped_uri.gltf", lambda d: d["buffers"][0].update(uri="a/%2e%2e/%2E%2E/x.bin"))
    gltf("file_uri.gltf", lambda d: d["buffers"][0].update(uri="file:///etc/passwd"))
    gltf("missing_buffer.gltf", lambda d: d["buffers"][0].update(uri="missing.bin"))

    def http_image(d):
        d["images"] = [{"uri": "http://example.com/texture.png"}]
        d["textures"] = [{"source": 0}]
    gltf("http_image_uri.gltf", http_image)

    def not_an_image(d):
        d["images"] = [{"name": "junk", "uri": "data:image/png;base64," +
                        base64.b64encode(b"this is not a png").decode()}]
        d["textures"] = [{"source": 0}]
        d["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
        d["meshes"][0]["primitives"][0]["material"] = 0
        d["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 0
    gltf("image_not_png.gltf", not_an_image)

    def points(d):
        d["meshes"][0]["name"] = "dots"
        d["meshes"][0]["primitives"][0]["mode"] = 0
    gltf("mode_points.gltf", points)
    gltf("no_position.gltf",
         lambda d: d["meshes"][0]["primitives"][0]["attributes"].update(POSITION=None) or
         d["meshes"][0]["primitives"][0]["attributes"].pop("POSITION"))

    def cycle(d):
        d["scenes"][0]["nodes"] = [2]
        d["nodes"] = [{"name": "wheel", "children": [1]}, {"name": "axle", "children": [0]},
                      {"name": "car", "mesh": 0}]
    gltf("node_cycle.gltf", cycle)
    gltf("node_self_parent.gltf", lambda d: d["nodes"][0].update(children=[0]))

    def two_parents(d):
        d["scenes"][0]["nodes"] = [0, 1]
        d["nodes"] = [{"name": "a", "children": [2]}, {"name": "b", "children": [2]},
                      {"name": "shared", "mesh": 0}]
    gltf("node_two_parents.gltf", two_parents)
    gltf("node_bad_mesh.gltf", lambda d: d["nodes"][0].update(mesh=5))

    def yfov0(d):
        d["cameras"] = [{"name": "cam", "type": "perspective",
                         "perspective": {"yfov": 0, "znear": 0.1}}]
        d["nodes"].append({"name": "eye", "camera": 0, "translation": [0, 0, 5]})
        d["scenes"][0]["nodes"].append(1)
    gltf("camera_yfov_zero.gltf", yfov0)
    gltf("required_draco.gltf",
         lambda d: d.update(extensionsRequired=["KHR_draco_mesh_compression"]))
    gltf("version1.gltf", lambda d: d["asset"].update(version="1.0"))


if __name__ == "__main__":
    main()
