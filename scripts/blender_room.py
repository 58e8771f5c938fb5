#!/usr/bin/env python3
"""blender_room.py — a small daylit room built and exported by real Blender, and its hand-written twin.

One description of the room (below, in fenestra's frame: metres, +x east, +y up, +z south) is
turned into two files that must render alike (tests/e2e/cli_test.cpp, CliBlender.*):

  scenes/blender_room.glb         built in Blender through its Python module (`pip install bpy`,
                                  headless) and written by Blender's own glTF exporter, as a user
                                  would: Principled BSDF materials (an image texture on the floor,
                                  Transmission 1 glass in the window), a custom property
                                  `portal` on the window, a Sun lamp, a camera; no sky (glTF has
                                  no place for Blender's World: give it with --sky).
  scenes/blender_room_twin.gltf   the same room written directly as glTF by this script (no
                                  Blender), with the same texture file.

and scenes/textures/floor_planks.png, the floor's texture (64 x 64, four plank tones), written by
this script with the standard library.

Run: python3 scripts/blender_room.py            (needs bpy: writes all three)
     python3 scripts/blender_room.py --twin-only (standard library only: the PNG and the twin)
Nothing in the build or the tests runs it; its outputs are committed.
"""
import base64
import json
import math
import os
import struct
import sys
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
SCENES = os.path.normpath(os.path.join(HERE, "..", "scenes"))
TEXTURE = os.path.join(SCENES, "textures", "floor_planks.png")

# ---- the room, in fenestra's frame ----------------------------------------------------------
W, D, H = 4.0, 3.0, 2.6                 # x in [0, W], z in [0, D] (south wall at z = D), height H
WIN = (1.0, 3.0, 0.9, 2.1)              # window x0, x1, y0, y1 in the south wall
MATERIALS = {                           # linear albedo
    "floor": (1.0, 1.0, 1.0),           # times the texture
    "wall": (0.7, 0.7, 0.7),
    "ceiling": (0.8, 0.8, 0.8),
    "ground": (0.2, 0.2, 0.2),
}
SUN_ALT, SUN_AZ, SUN_LUX = 40.0, 170.0, 75000.0
CAMERA_EYE, CAMERA_TARGET, CAMERA_YFOV_DEG, RES = (0.5, 1.5, 0.5), (2.5, 0.8, 3.0), 60.0, (640, 480)


def quad(a, b, c, d):
    return [a, b, c, d]


def surfaces():
    """(name, material, [quads]) in fenestra's frame; each quad's corners in order."""
    x0, x1, y0, y1 = WIN
    south = [quad((0, 0, D), (W, 0, D), (W, y0, D), (0, y0, D)),
             quad((0, y1, D), (W, y1, D), (W, H, D), (0, H, D)),
             quad((0, y0, D), (x0, y0, D), (x0, y1, D), (0, y1, D)),
             quad((x1, y0, D), (W, y0, D), (W, y1, D), (x1, y1, D))]
    return [
        ("floor", "floor", [quad((0, 0, 0), (W, 0, 0), (W, 0, D), (0, 0, D))]),
        ("ceiling", "ceiling", [quad((0, H, 0), (W, H, 0), (W, H, D), (0, H, D))]),
        ("north_wall", "wall", [quad((0, 0, 0), (W, 0, 0), (W, H, 0), (0, H, 0))]),
        ("west_wall", "wall", [quad((0, 0, 0), (0, 0, D), (0, H, D), (0, H, 0))]),
        ("east_wall", "wall", [quad((W, 0, 0), (W, 0, D), (W, H, D), (W, H, 0))]),
        ("south_wall", "wall", south),
        ("window", "glass", [quad((x0, y0, D), (x1, y0, D), (x1, y1, D), (x0, y1, D))]),
        ("ground", "ground", [quad((-8, 0, D), (12, 0, D), (12, 0, D + 12), (-8, 0, D + 12))]),
    ]


def floor_uv(p):
    """The floor's texture coordinates in glTF's convention: one repeat per metre."""
    return (p[0], p[2])


def direction(alt_deg, az_deg):
    h, a = math.radians(alt_deg), math.radians(az_deg)
    return (math.cos(h) * math.sin(a), math.sin(h), -math.cos(h) * math.cos(a))


# ---- the texture ------------------------------------------------------------------------------
def write_png(path, width, height, rows):
    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + bytes(r) for r in rows)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(png)


def planks():
    tones = [150, 118, 172, 96]  # sRGB codes of four planks, 16 rows each
    rows = []
    for y in range(64):
        t = tones[y // 16]
        rows.append([v for _ in range(64) for v in (t, int(t * 0.78), int(t * 0.55))])
    write_png(TEXTURE, 64, 64, rows)


# ---- the hand-written twin --------------------------------------------------------------------
def look_at_quaternion(eye, target):
    """glTF rotation (x, y, z, w) of a node looking along -z at target, +y up."""
    f = [t - e for t, e in zip(target, eye)]
    n = math.sqrt(sum(c * c for c in f))
    f = [c / n for c in f]
    back = [-c for c in f]
    right = [f[1] * 0 - f[2] * 1, f[2] * 0 - f[0] * 0, f[0] * 1 - f[1] * 0]  # f x up(0,1,0)
    n = math.sqrt(sum(c * c for c in right))
    right = [c / n for c in right]
    up = [back[1] * right[2] - back[2] * right[1], back[2] * right[0] - back[0] * right[2],
          back[0] * right[1] - back[1] * right[0]]
    return matrix_to_quaternion(right, up, back)


def matrix_to_quaternion(x, y, z):
    """Quaternion of the rotation whose columns are x, y, z."""
    m00, m11, m22 = x[0], y[1], z[2]
    tr = m00 + m11 + m22
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        return [(y[2] - z[1]) / s, (z[0] - x[2]) / s, (x[1] - y[0]) / s, 0.25 * s]
    if m00 > m11 and m00 > m22:
        s = math.sqrt(1.0 + m00 - m11 - m22) * 2
        return [0.25 * s, (y[0] + x[1]) / s, (z[0] + x[2]) / s, (y[2] - z[1]) / s]
    if m11 > m22:
        s = math.sqrt(1.0 + m11 - m00 - m22) * 2
        return [(y[0] + x[1]) / s, 0.25 * s, (z[1] + y[2]) / s, (z[0] - x[2]) / s]
    s = math.sqrt(1.0 + m22 - m00 - m11) * 2
    return [(z[0] + x[2]) / s, (z[1] + y[2]) / s, 0.25 * s, (x[1] - y[0]) / s]


def twin():
    buf = bytearray()
    doc = {"asset": {"version": "2.0", "generator": "fenestra scripts/blender_room.py (hand-written twin)"},
           "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [], "accessors": [], "bufferViews": [],
           "materials": [], "extensionsUsed": ["KHR_materials_transmission", "KHR_lights_punctual"]}
    names = list(MATERIALS) + ["glass"]
    for name in names:
        m = {"name": name, "pbrMetallicRoughness": {"metallicFactor": 0.0, "roughnessFactor": 1.0}}
        if name == "glass":
            m["extensions"] = {"KHR_materials_transmission": {"transmissionFactor": 1.0}}
        else:
            m["pbrMetallicRoughness"]["baseColorFactor"] = list(MATERIALS[name]) + [1.0]
        if name == "floor":
            m["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
        doc["materials"].append(m)
    doc["textures"] = [{"source": 0, "sampler": 0}]
    doc["images"] = [{"uri": "textures/floor_planks.png"}]
    doc["samplers"] = [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}]

    def accessor(values, ctype, fmt, kind):
        off = len(buf)
        for v in values:
            buf.extend(struct.pack(fmt, *v))
        while len(buf) % 4:
            buf.append(0)
        doc["bufferViews"].append({"buffer": 0, "byteOffset": off, "byteLength": len(buf) - off})
        a = {"bufferView": len(doc["bufferViews"]) - 1, "componentType": ctype, "count": len(values), "type": kind}
        if kind == "VEC3":
            a["min"] = [min(v[i] for v in values) for i in range(3)]
            a["max"] = [max(v[i] for v in values) for i in range(3)]
        doc["accessors"].append(a)
        return len(doc["accessors"]) - 1

    for name, mat, quads in surfaces():
        pos, idx, uv = [], [], []
        for q in quads:
            base = len(pos)
            pos.extend(q)
            uv.extend(floor_uv(p) for p in q)
            idx.extend([(base,), (base + 1,), (base + 2,), (base,), (base + 2,), (base + 3,)])
        attrs = {"POSITION": accessor(pos, 5126, "<3f", "VEC3")}
        if mat == "floor":
            attrs["TEXCOORD_0"] = accessor(uv, 5126, "<2f", "VEC2")
        prim = {"attributes": attrs, "indices": accessor(idx, 5125, "<I", "SCALAR"), "material": names.index(mat)}
        doc["meshes"].append({"name": name, "primitives": [prim]})
        node = {"name": name, "mesh": len(doc["meshes"]) - 1}
        if name == "window":
            node["extras"] = {"portal": True}
        doc["nodes"].append(node)
    travel = [-c for c in direction(SUN_ALT, SUN_AZ)]
    sun_target = [travel[0], travel[1], travel[2]]
    doc["nodes"].append({"name": "sun", "rotation": look_at_quaternion((0, 0, 0), sun_target),
                         "extensions": {"KHR_lights_punctual": {"light": 0}}})
    doc["extensions"] = {"KHR_lights_punctual": {"lights": [{"name": "sun", "type": "directional",
                                                             "intensity": SUN_LUX, "color": [1, 1, 1]}]}}
    doc["nodes"].append({"name": "camera", "camera": 0, "translation": list(CAMERA_EYE),
                         "rotation": look_at_quaternion(CAMERA_EYE, CAMERA_TARGET)})
    doc["cameras"] = [{"name": "camera", "type": "perspective",
                       "perspective": {"yfov": math.radians(CAMERA_YFOV_DEG), "aspectRatio": RES[0] / RES[1],
                                       "znear": 0.05}}]
    doc["scenes"][0]["nodes"] = list(range(len(doc["nodes"])))
    doc["buffers"] = [{"byteLength": len(buf),
                       "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(buf)).decode()}]
    with open(os.path.join(SCENES, "blender_room_twin.gltf"), "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


# ---- the Blender scene --------------------------------------------------------------------------
def blender():
    import bpy
    from mathutils import Vector

    def to_blender(p):  # fenestra / glTF (x, y, z) -> Blender (x, -z, y)
        return (p[0], -p[2], p[1])

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = RES

    def principled(name, color, transmission=0.0):
        m = bpy.data.materials.new(name)
        m.use_nodes = True
        bsdf = m.node_tree.nodes["Principled BSDF"]
        bsdf.inputs["Base Color"].default_value = (*color, 1.0)
        bsdf.inputs["Roughness"].default_value = 1.0 if transmission == 0.0 else 0.0
        bsdf.inputs["Metallic"].default_value = 0.0
        if transmission:
            bsdf.inputs["Transmission Weight"].default_value = transmission
            bsdf.inputs["IOR"].default_value = 1.5
        return m, bsdf

    mats = {}
    for name, color in MATERIALS.items():
        mats[name], bsdf = principled(name, color)
        if name == "floor":
            tex = mats[name].node_tree.nodes.new("ShaderNodeTexImage")
            tex.image = bpy.data.images.load(TEXTURE)
            tex.image.colorspace_settings.name = "sRGB"
            tex.interpolation = "Linear"
            tex.extension = "REPEAT"
            mats[name].node_tree.links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
    mats["glass"], _ = principled("glass", (1.0, 1.0, 1.0), transmission=1.0)

    for name, mat, quads in surfaces():
        verts, faces = [], []
        for q in quads:
            faces.append(tuple(range(len(verts), len(verts) + 4)))
            verts.extend(to_blender(p) for p in q)
        mesh = bpy.data.meshes.new(name)
        mesh.from_pydata(verts, [], faces)
        if mat == "floor":
            uv = mesh.uv_layers.new(name="UVMap")
            for loop in mesh.loops:
                co = verts[loop.vertex_index]
                u, v = floor_uv((co[0], co[2], -co[1]))
                uv.data[loop.index].uv = (u, 1.0 - v)  # Blender's v runs up, glTF's down
        mesh.materials.append(mats[mat])
        obj = bpy.data.objects.new(name, mesh)
        scene.collection.objects.link(obj)
        if name == "window":
            obj["portal"] = True  # a custom property: exported as extras

    sun_data = bpy.data.lights.new("sun", type="SUN")
    sun_data.energy = SUN_LUX / 683.0  # W/m^2, as Blender's exporter converts (683 lm/W)
    sun = bpy.data.objects.new("sun", sun_data)
    scene.collection.objects.link(sun)
    travel = Vector(to_blender([-c for c in direction(SUN_ALT, SUN_AZ)]))
    sun.rotation_mode = "QUATERNION"
    sun.rotation_quaternion = travel.to_track_quat("-Z", "Y")

    cam_data = bpy.data.cameras.new("camera")
    cam_data.sensor_fit = "VERTICAL"
    cam_data.angle = math.radians(CAMERA_YFOV_DEG)
    cam = bpy.data.objects.new("camera", cam_data)
    scene.collection.objects.link(cam)
    cam.location = to_blender(CAMERA_EYE)
    look = Vector(to_blender(CAMERA_TARGET)) - Vector(to_blender(CAMERA_EYE))
    cam.rotation_mode = "QUATERNION"
    cam.rotation_quaternion = look.to_track_quat("-Z", "Y")
    scene.camera = cam

    bpy.ops.export_scene.gltf(filepath=os.path.join(SCENES, "blender_room.glb"), export_format="GLB",
                              export_extras=True, export_cameras=True, export_lights=True, export_yup=True)
    print("blender", bpy.app.version_string, "wrote", os.path.join(SCENES, "blender_room.glb"))


if __name__ == "__main__":
    planks()
    twin()
    if "--twin-only" not in sys.argv:
        blender()
