#!/usr/bin/env python3
"""Writes scenes/street-gltf.glb: a street at night modelled as glTF 2.0, for
scenes/street-gltf.toml (issue 29).

A road (8 m x 80 m, along -Z, Y up, metres), raised pavements, facades on both sides and three
lamp posts on the right pavement. Each lamp post is one node ("LampPost.1".."LampPost.3") whose
children are the pole and arm (a rough metal: metallic 1, roughness 0.5), the lantern's head,
its emitting lens (emissive, KHR_materials_emissive_strength: 4000 cd/m^2) and a
KHR_lights_punctual spot of 2500 cd aimed down (outer half-angle 70 deg, inner 50 deg). The
lamp posts share their meshes (one mesh, three nodes). A camera node ("Eye") at a pedestrian's
eye looks up the street.

Made with pygltflib 1.16.5 in a virtualenv outside the repository:
    python3 -m venv /work/venv-gltf && /work/venv-gltf/bin/pip install pygltflib==1.16.5
    /work/venv-gltf/bin/python tools/make_street_gltf.py scenes/street-gltf.glb
"""

import math
import struct
import sys

import pygltflib as g

FLOAT, UINT = 5126, 5125


class Writer:
    def __init__(self):
        self.doc = g.GLTF2(asset=g.Asset(generator="brume tools/make_street_gltf.py"))
        self.blob = bytearray()
        self.doc.extensionsUsed = ["KHR_lights_punctual", "KHR_materials_emissive_strength"]
        self.doc.extensions = {"KHR_lights_punctual": {"lights": []}}

    def view(self, data):
        while len(self.blob) % 4:
            self.blob.append(0)
        self.doc.bufferViews.append(
            g.BufferView(buffer=0, byteOffset=len(self.blob), byteLength=len(data)))
        self.blob.extend(data)
        return len(self.doc.bufferViews) - 1

    def mesh(self, name, positions, triangles, material):
        flat = [c for p in positions for c in p]
        pos = self.view(struct.pack(f"<{len(flat)}f", *flat))
        lo = [min(p[k] for p in positions) for k in range(3)]
        hi = [max(p[k] for p in positions) for k in range(3)]
        self.doc.accessors.append(g.Accessor(bufferView=pos, componentType=FLOAT,
                                             count=len(positions), type="VEC3", min=lo, max=hi))
        idx = [i for t in triangles for i in t]
        iv = self.view(struct.pack(f"<{len(idx)}I", *idx))
        self.doc.accessors.append(g.Accessor(bufferView=iv, componentType=UINT,
                                             count=len(idx), type="SCALAR"))
        prim = g.Primitive(attributes=g.Attributes(POSITION=len(self.doc.accessors) - 2),
                           indices=len(self.doc.accessors) - 1, material=material)
        self.doc.meshes.append(g.Mesh(name=name, primitives=[prim]))
        return len(self.doc.meshes) - 1

    def material(self, name, rgb, metallic=0.0, roughness=1.0, emissive=None, strength=None):
        m = g.Material(name=name, pbrMetallicRoughness=g.PbrMetallicRoughness(
            baseColorFactor=[*rgb, 1.0], metallicFactor=metallic, roughnessFactor=roughness))
        if emissive:
            m.emissiveFactor = emissive
            m.extensions = {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}
        self.doc.materials.append(m)
        return len(self.doc.materials) - 1

    def node(self, **kw):
        self.doc.nodes.append(g.Node(**kw))
        return len(self.doc.nodes) - 1

    def spot(self, name, candela, inner_deg, outer_deg):
        lights = self.doc.extensions["KHR_lights_punctual"]["lights"]
        lights.append({"name": name, "type": "spot", "intensity": candela,
                       "color": [1.0, 0.93, 0.82],
                       "spot": {"innerConeAngle": math.radians(inner_deg),
                                "outerConeAngle": math.radians(outer_deg)}})
        return len(lights) - 1

    def save(self, path):
        self.doc.buffers = [g.Buffer(byteLength=len(self.blob))]
        self.doc.set_binary_blob(bytes(self.blob))
        self.doc.save_binary(path)


def box(size, centre=(0.0, 0.0, 0.0)):
    """Corners and outward counter-clockwise triangles of an axis-aligned box."""
    (sx, sy, sz), (cx, cy, cz) = [s / 2 for s in size], centre
    p = [(cx + x * sx, cy + y * sy, cz + z * sz)
         for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
    # Corner index = 4*(x>0) + 2*(y>0) + (z>0).
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    return p, [t for a, b, c, d in faces for t in ((a, b, c), (a, c, d))]


def quad_y(size_x, size_z, y, up):
    """A horizontal rectangle at height y facing +Y (up) or -Y."""
    hx, hz = size_x / 2, size_z / 2
    p = [(-hx, y, -hz), (hx, y, -hz), (hx, y, hz), (-hx, y, hz)]
    tris = [(0, 2, 1), (0, 3, 2)] if up else [(0, 1, 2), (0, 2, 3)]
    return p, tris


def look_rotation(eye, target):
    """Quaternion (x, y, z, w) turning -Z towards target - eye with +Y up."""
    f = [t - e for t, e in zip(target, eye)]
    n = math.sqrt(sum(c * c for c in f))
    f = [c / n for c in f]
    r = [-f[2], 0.0, f[0]]  # f x (0, 1, 0)
    n = math.sqrt(sum(c * c for c in r))
    r = [c / n for c in r]
    u = [r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]]
    b = [-c for c in f]
    m = [[r[0], u[0], b[0]], [r[1], u[1], b[1]], [r[2], u[2], b[2]]]
    w = math.sqrt(max(0.0, 1.0 + m[0][0] + m[1][1] + m[2][2])) / 2
    return [(m[2][1] - m[1][2]) / (4 * w), (m[0][2] - m[2][0]) / (4 * w),
            (m[1][0] - m[0][1]) / (4 * w), w]


def main(out):
    w = Writer()
    asphalt = w.material("Asphalt", [0.08, 0.08, 0.08])
    pavement = w.material("Pavement", [0.25, 0.25, 0.24])
    facade = w.material("Facade", [0.40, 0.33, 0.27])
    metal = w.material("PoleMetal", [0.56, 0.57, 0.58], metallic=1.0, roughness=0.5)
    housing = w.material("Housing", [0.05, 0.05, 0.05])
    lens = w.material("Lens", [0.9, 0.9, 0.9], emissive=[1.0, 0.93, 0.82], strength=4000.0)

    road = w.mesh("Road", *quad_y(8.0, 80.0, 0.0, True), asphalt)
    kerb = w.mesh("Pavement", *box((3.0, 0.12, 80.0)), pavement)
    wall = w.mesh("Facade", *box((2.0, 14.0, 80.0)), facade)
    pole = w.mesh("Pole", *box((0.14, 8.36, 0.14), (0.0, 4.18, 0.0)), metal)
    # The arm runs above the head, which holds the lens below it and the light below that (a
    # light inside a closed box would be in its vacuum, unseen).
    arm = w.mesh("Arm", *box((1.6, 0.08, 0.1), (-0.7, 8.32, 0.0)), metal)
    head = w.mesh("Head", *box((0.7, 0.16, 0.35), (-1.3, 8.2, 0.0)), housing)
    glass = w.mesh("LensGlass", *quad_y(0.6, 0.28, 8.115, False), lens)
    spot = w.spot("Lantern", 2500.0, 50.0, 70.0)

    street = [w.node(name="Road", mesh=road, translation=[0.0, 0.0, -30.0])]
    for x in (-5.5, 5.5):
        street.append(w.node(name="Pavement", mesh=kerb, translation=[x, 0.06, -30.0]))
    for x in (-8.0, 8.0):
        street.append(w.node(name="Facade", mesh=wall, translation=[x, 7.0, -30.0]))
    down = [-math.sqrt(0.5), 0.0, 0.0, math.sqrt(0.5)]  # -Z turned to -Y
    for i, z in enumerate((-8.0, -28.0, -48.0), start=1):
        parts = [w.node(name=f"Pole.{i}", mesh=pole), w.node(name=f"Arm.{i}", mesh=arm),
                 w.node(name=f"Head.{i}", mesh=head),
                 w.node(name=f"Lens.{i}", mesh=glass, translation=[-1.3, 0.0, 0.0]),
                 w.node(name=f"Lantern.{i}", translation=[-1.3, 8.08, 0.0], rotation=down,
                        extensions={"KHR_lights_punctual": {"light": spot}})]
        street.append(w.node(name=f"LampPost.{i}", children=parts,
                             translation=[4.6, 0.12, z]))
    w.doc.cameras.append(g.Camera(type="perspective", perspective=g.Perspective(
        yfov=math.radians(55.0), znear=0.05, aspectRatio=16 / 9)))
    eye = [1.5, 1.6, 4.0]
    street.append(w.node(name="Eye", camera=0, translation=eye,
                         rotation=look_rotation(eye, [0.0, 2.5, -30.0])))
    w.doc.scenes = [g.Scene(name="Street", nodes=street)]
    w.doc.scene = 0
    w.save(out)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "scenes/street-gltf.glb")
