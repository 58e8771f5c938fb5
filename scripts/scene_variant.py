#!/usr/bin/env python3
"""scene_variant.py — a copy of a glTF scene with some materials or its camera changed: what-if
studies (a darker ground, whiter walls, an open window) and controlled experiments
(docs/results/house.md: the house with a black ground, to measure how much of its noise the light
reflected off the ground makes; docs/results/peer.md: the inner room with an open window, seen
through the gap under its door by a camera zoomed on the gap).

    python3 scripts/scene_variant.py scenes/house.gltf --material ground=0,0,0 --out out/house_black_ground.gltf
    python3 scripts/scene_variant.py scenes/inner_room.gltf --opening glass --out out/inner_room_open.gltf

--material NAME=R,G,B sets that material's base colour (linear, 0..1; repeatable). --opening NAME
makes that material a fully transparent opening (transmission 1, IOR 1, base colour white: what
fenestra passes unchanged and scripts/mitsuba_peer.py leaves out; repeatable). --remove NODE takes
that node's mesh out of the scene (the node stays, empty; repeatable): an opening against no
surface at all. --look-at X,Y,Z
turns the first camera towards that point (up stays +y), --look-from X,Y,Z moves it, --yfov DEG
and --aspect A change its field of view; a point's coordinates are the scene's (metres, +y up).
The scene must keep its buffers inside the file (data URIs, as every shipped scene does) or beside
it: relative buffer paths are rewritten to stay valid from the new location.
"""
import argparse
import json
import math
import os
import sys


def point(text, option):
    try:
        x, y, z = (float(v) for v in text.split(","))
    except ValueError:
        sys.exit("scene_variant.py: %s %s: expected X,Y,Z" % (option, text))
    return [x, y, z]


def look_rotation(eye, target):
    """The glTF rotation (quaternion x, y, z, w) of a camera at eye looking at target, +y up: its
    -z axis towards the target, its +x level."""
    f = [t - e for t, e in zip(target, eye)]
    n = math.sqrt(sum(v * v for v in f))
    if n == 0.0 or math.hypot(f[0], f[2]) < 1e-9 * n:
        sys.exit("scene_variant.py: --look-at must differ from the camera's position, and not lie straight above or below it")
    f = [v / n for v in f]
    r = [-f[2], 0.0, f[0]]  # f x (0, 1, 0)
    rn = math.hypot(r[0], r[2])
    r = [v / rn for v in r]
    u = [r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]]
    # columns of the rotation: right, up, back
    m = [[r[0], u[0], -f[0]], [r[1], u[1], -f[1]], [r[2], u[2], -f[2]]]
    tr = m[0][0] + m[1][1] + m[2][2]
    if tr > 0:
        s = 2 * math.sqrt(tr + 1)
        return [(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, s / 4]
    i = max(range(3), key=lambda k: m[k][k])
    j, k = (i + 1) % 3, (i + 2) % 3
    s = 2 * math.sqrt(1 + m[i][i] - m[j][j] - m[k][k])
    q = [0.0, 0.0, 0.0, (m[k][j] - m[j][k]) / s]
    q[i], q[j], q[k] = s / 4, (m[j][i] + m[i][j]) / s, (m[k][i] + m[i][k]) / s
    return q


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("--material", action="append", default=[], metavar="NAME=R,G,B")
    ap.add_argument("--opening", action="append", default=[], metavar="NAME")
    ap.add_argument("--remove", action="append", default=[], metavar="NODE")
    ap.add_argument("--look-from", metavar="X,Y,Z")
    ap.add_argument("--look-at", metavar="X,Y,Z")
    ap.add_argument("--yfov", type=float, metavar="DEG")
    ap.add_argument("--aspect", type=float)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    try:
        with open(a.scene) as f:
            scene = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit("scene_variant.py: %s: %s" % (a.scene, e))
    materials = {m.get("name"): m for m in scene.get("materials", [])}
    for spec in a.material:
        name, _, rgb = spec.partition("=")
        try:
            r, g, b = (float(x) for x in rgb.split(","))
        except ValueError:
            sys.exit("scene_variant.py: --material %s: expected NAME=R,G,B" % spec)
        if not all(0.0 <= x <= 1.0 for x in (r, g, b)):
            sys.exit("scene_variant.py: --material %s: each colour component must be in 0..1" % spec)
        if name not in materials:
            sys.exit("scene_variant.py: %s has no material '%s' (it has: %s)"
                     % (a.scene, name, ", ".join(sorted(str(k) for k in materials))))
        pbr = materials[name].setdefault("pbrMetallicRoughness", {})
        alpha = pbr.get("baseColorFactor", [1, 1, 1, 1])[3]
        pbr["baseColorFactor"] = [r, g, b, alpha]
    for name in a.opening:
        if name not in materials:
            sys.exit("scene_variant.py: %s has no material '%s' (it has: %s)"
                     % (a.scene, name, ", ".join(sorted(str(k) for k in materials))))
        m = materials[name]
        m.setdefault("pbrMetallicRoughness", {})["baseColorFactor"] = [1.0, 1.0, 1.0, 1.0]
        m.setdefault("extensions", {})["KHR_materials_transmission"] = {"transmissionFactor": 1.0}
        m["extensions"]["KHR_materials_ior"] = {"ior": 1.0}
        used = scene.setdefault("extensionsUsed", [])
        for ext in ("KHR_materials_transmission", "KHR_materials_ior"):
            if ext not in used:
                used.append(ext)
    for name in a.remove:
        hits = [n for n in scene.get("nodes", []) if n.get("name") == name and "mesh" in n]
        if not hits:
            sys.exit("scene_variant.py: %s has no mesh node '%s'" % (a.scene, name))
        for n in hits:
            del n["mesh"]
    if a.look_from or a.look_at or a.yfov or a.aspect:
        cams = [n for n in scene.get("nodes", []) if "camera" in n]
        if not cams:
            sys.exit("scene_variant.py: %s has no camera node" % a.scene)
        node = cams[0]
        if "matrix" in node:
            sys.exit("scene_variant.py: %s: the camera node has a matrix; only translation and rotation are changed" % a.scene)
        persp = scene["cameras"][node["camera"]].get("perspective")
        if persp is None:
            sys.exit("scene_variant.py: %s: the first camera is not a perspective camera" % a.scene)
        if a.look_from:
            node["translation"] = point(a.look_from, "--look-from")
        if a.look_at:
            node["rotation"] = look_rotation(node.get("translation", [0.0, 0.0, 0.0]),
                                             point(a.look_at, "--look-at"))
        if a.yfov:
            if not 0.0 < a.yfov < 180.0:
                sys.exit("scene_variant.py: --yfov %g: must be in (0, 180) degrees" % a.yfov)
            persp["yfov"] = math.radians(a.yfov)
        if a.aspect:
            if not a.aspect > 0.0:
                sys.exit("scene_variant.py: --aspect %g: must be > 0" % a.aspect)
            persp["aspectRatio"] = a.aspect
    src, dst = os.path.dirname(os.path.abspath(a.scene)), os.path.dirname(os.path.abspath(a.out))
    for buf in scene.get("buffers", []) + scene.get("images", []):
        uri = buf.get("uri", "")
        if uri and not uri.startswith("data:") and not os.path.isabs(uri):
            buf["uri"] = os.path.relpath(os.path.join(src, uri), dst)
    os.makedirs(dst, exist_ok=True)
    with open(a.out, "w") as f:
        json.dump(scene, f)
    return 0


if __name__ == "__main__":
    sys.exit(main())
