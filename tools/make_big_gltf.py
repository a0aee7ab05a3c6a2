#!/usr/bin/env python3
"""Writes a 1-million-triangle glTF (a rippled 100 m x 100 m terrain as one indexed mesh, a
point light of 20000 cd and a camera) and the scene that reads it, for the glTF load benchmark
of docs/performance.md. Standard library only; the .glb is 18 MB, so they are written to a
folder of your choice, never committed:

    python3 tools/make_big_gltf.py /tmp/big
    /usr/bin/time -f "%e s wall, %U s user, %M KB" target/release/brume info /tmp/big/big.toml
    target/release/brume render /tmp/big/big.toml --passes 2 -o /tmp/big/big.png
"""

import json
import math
import os
import struct
import sys

N = 708  # vertices per side: 2 * 707^2 = 999 698 triangles


def main(out):
    os.makedirs(out, exist_ok=True)
    pos = bytearray()
    for j in range(N):
        for i in range(N):
            x, z = i * 100.0 / (N - 1) - 50.0, j * 100.0 / (N - 1) - 50.0
            y = 0.3 * math.sin(0.7 * x) * math.cos(0.5 * z)
            pos += struct.pack("<3f", x, y, z)
    idx = bytearray()
    for j in range(N - 1):
        for i in range(N - 1):
            a = j * N + i
            b, c, d = a + 1, a + N, a + N + 1
            idx += struct.pack("<6I", a, c, b, b, c, d)
    tris = len(idx) // 12
    blob = bytes(pos + idx)
    doc = {
        "asset": {"version": "2.0", "generator": "brume tools/make_big_gltf.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "point", "intensity": 20000.0}]}},
        "buffers": [{"byteLength": len(blob)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
            {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": N * N, "type": "VEC3",
             "min": [-50.0, -0.3, -50.0], "max": [50.0, 0.3, 50.0]},
            {"bufferView": 1, "componentType": 5125, "count": tris * 3, "type": "SCALAR"},
        ],
        "materials": [{"name": "Ground", "pbrMetallicRoughness": {
            "baseColorFactor": [0.3, 0.3, 0.3, 1.0], "metallicFactor": 0.0}}],
        "meshes": [{"name": "Terrain", "primitives": [
            {"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.1}}],
        "nodes": [
            {"name": "Terrain", "mesh": 0},
            {"name": "Lamp", "translation": [0.0, 10.0, 0.0],
             "extensions": {"KHR_lights_punctual": {"light": 0}}},
            # 30 m up and 40 m back, looking down 30 degrees.
            {"name": "Eye", "camera": 0, "translation": [0.0, 30.0, 40.0],
             "rotation": [-math.sin(math.radians(15)), 0.0, 0.0, math.cos(math.radians(15))]},
        ],
        "scenes": [{"nodes": [0, 1, 2]}],
        "scene": 0,
    }
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    total = 12 + 8 + len(text) + 8 + len(blob)
    with open(os.path.join(out, "big.glb"), "wb") as f:
        f.write(b"glTF" + struct.pack("<II", 2, total))
        f.write(struct.pack("<I", len(text)) + b"JSON" + text)
        f.write(struct.pack("<I", len(blob)) + b"BIN\0" + blob)
    with open(os.path.join(out, "big.toml"), "w") as f:
        f.write('[film]\nexposure = "auto"\n\n[camera]\nwidth = 160\nheight = 90\n\n[integrator]\nradius = 0.2\n'
                'forward_rays = 20000\n\n[import]\nlights = true\n\n'
                '[[shapes]]\ntype = "gltf"\nfile = "big.glb"\n')
    print(f"{out}/big.glb: {tris} triangles, {total} bytes")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "/tmp/big")
