#!/usr/bin/env python3
"""gltf_to_rad.py — converts a fenestra glTF scene into a Radiance scene description, so that
Radiance can compute an independent reference for fenestra's results (docs/results/radiance.md).
Radiance is a checking tool only: nothing in the build or the tests uses it or this script.

    python3 scripts/radiance/gltf_to_rad.py scenes/room.gltf --out out/radiance/room.rad \
        [--open-windows] [--write-gltf docs/results/radiance/room_open.gltf] \
        [--sky iso1|gensky] [--sky-lux 10000] [--grey rec709|radiance]

Reads a .gltf (JSON, buffers as base64 data URIs or .bin files beside it) or a .glb; walks the
default scene's node tree (matrix or TRS transforms, nested children) and writes

- every triangle of every mesh (primitive modes 4, 5, 6; indexed or not) as a Radiance `polygon`;
- each opaque material as `plastic r g b 0 0`: two-sided Lambertian of albedo
  baseColorFactor.rgb, as fenestra models it (DESIGN.md §1; textures are not converted);
- each material with KHR_materials_transmission as Radiance `glass` (reference only, see
  `glass_transmissivity`), or, with --open-windows, not at all: every node whose mesh uses such a
  material is dropped (window glass and fully transparent `opening`s such as the inner room's
  gap), so the comparison does not depend on two different glass models;
- the sky: upper hemisphere only (no ground glow: fenestra's sky is zero below the horizon) and
  no sun. `--sky iso1` (default) is the CIE standard general sky of type 1 of ISO 15469 /
  CIE S 011 — the sky of fenestra's `--sky cie:1` — written as a Radiance brightfunc
  (`cie_iso1.cal`, beside the output); `--sky gensky` is Radiance's own `gensky -c` (the
  Moon–Spencer overcast sky, (1 + 2 cos Z) / 3, blended towards gensky's ground brightness in
  the last degrees above the horizon). Either is scaled to the diffuse horizontal illuminance
  --sky-lux (default 10 000 lux, i.e. 10000 / 179 = 55.866 W/m^2 with Radiance's luminous
  efficacy of 179 lm/W).

Coordinates: glTF is y-up (fenestra: +x east, +y up, +z south); Radiance's sky functions take +z
as up. The geometry is rotated: (x, y, z)_glTF -> (x, -z, y)_Radiance (a proper rotation,
determinant +1): east stays +x, north (-z_glTF) becomes +y, up becomes +z, as Radiance's own
convention has them. `to_radiance()` is the mapping; sensor points and their normals are rotated
the same way by the runner (reference.py), never in the points file.

--write-gltf OUT writes the glTF that fenestra is to render: the input with exactly the nodes
dropped by --open-windows removed (scenes, extras, cameras, the sun and every other node kept;
meshes and materials left in place, unused). Buffers stay embedded, or their relative paths are
rewritten to stay valid from OUT's folder.

--grey rec709|radiance replaces every opaque material's colour by the grey of equal luminance by
that weighting (0.2126/0.7152/0.0722, fenestra's, or 0.265/0.670/0.065, Radiance's): the check
of how much the two luminance weightings differ on this scene (reference.py).

Standard library only.
"""
import argparse
import base64
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys

SKY_LUX_DEFAULT = 10000.0
RADIANCE_EFFICACY = 179.0  # lm/W: Radiance's luminous efficacy of its white "RGB" W/m^2
RADIANCE_WEIGHTS = (0.265, 0.670, 0.065)  # Radiance's luminance weights of R, G, B
REC709_WEIGHTS = (0.2126, 0.7152, 0.0722)  # fenestra's (DESIGN.md §1)

# ISO 15469 / CIE S 011 type 1: gradation phi(Z) = 1 + a exp(b / cos Z), no indicatrix.
ISO1_A, ISO1_B = 4.0, -0.70


# --------------------------------------------------------------------------------------------
# glTF reading


COMPONENT = {5120: ("b", 1), 5121: ("B", 1), 5122: ("h", 2), 5123: ("H", 2), 5125: ("I", 4),
             5126: ("f", 4)}
NCOMP = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}


def load_gltf(path):
    """(document, [buffer bytes]) of a .gltf or .glb file."""
    with open(path, "rb") as f:
        raw = f.read()
    glb_bin = None
    if raw[:4] == b"glTF":
        length = struct.unpack_from("<I", raw, 8)[0]
        pos, doc = 12, None
        while pos < length:
            clen, ctype = struct.unpack_from("<II", raw, pos)
            chunk = raw[pos + 8:pos + 8 + clen]
            if ctype == 0x4E4F534A:
                doc = json.loads(chunk.decode("utf-8"))
            elif ctype == 0x004E4942:
                glb_bin = chunk
            pos += 8 + clen
    else:
        doc = json.loads(raw.decode("utf-8"))
    buffers = []
    base = os.path.dirname(os.path.abspath(path))
    for b in doc.get("buffers", []):
        uri = b.get("uri")
        if uri is None:
            buffers.append(glb_bin)
        elif uri.startswith("data:"):
            buffers.append(base64.b64decode(uri.split(",", 1)[1]))
        else:
            from urllib.parse import unquote
            with open(os.path.join(base, unquote(uri)), "rb") as f:
                buffers.append(f.read())
    return doc, buffers


def read_accessor(doc, buffers, index):
    """The accessor's elements as a list of tuples (normalized integer types are not used by the
    attributes read here: POSITION is float, indices are unsigned integers)."""
    acc = doc["accessors"][index]
    fmt, size = COMPONENT[acc["componentType"]]
    n = NCOMP[acc["type"]]
    count = acc["count"]
    if "bufferView" not in acc:
        return [tuple([0] * n)] * count
    view = doc["bufferViews"][acc["bufferView"]]
    data = buffers[view["buffer"]]
    start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
    stride = view.get("byteStride") or n * size
    out = []
    for i in range(count):
        out.append(struct.unpack_from("<" + fmt * n, data, start + i * stride))
    if "sparse" in acc:
        sys.exit("gltf_to_rad.py: sparse accessors are not supported")
    return out


def mat_mul(a, b):
    """4x4 row-major product."""
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def node_matrix(node):
    """The node's local transform as a row-major 4x4 (glTF stores `matrix` column-major)."""
    if "matrix" in node:
        m = node["matrix"]
        return [[m[c * 4 + r] for c in range(4)] for r in range(4)]
    tx, ty, tz = node.get("translation", [0, 0, 0])
    qx, qy, qz, qw = node.get("rotation", [0, 0, 0, 1])
    sx, sy, sz = node.get("scale", [1, 1, 1])
    r = [[1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)],
         [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)],
         [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)]]
    s = (sx, sy, sz)
    return [[r[i][0] * s[0], r[i][1] * s[1], r[i][2] * s[2], (tx, ty, tz)[i]] for i in range(3)] + \
        [[0, 0, 0, 1]]


def apply(m, p):
    return tuple(m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3] for i in range(3))


def primitive_triangles(doc, buffers, prim):
    """The primitive's triangles as lists of three local-space vertices."""
    mode = prim.get("mode", 4)
    pos = read_accessor(doc, buffers, prim["attributes"]["POSITION"])
    if "indices" in prim:
        idx = [i[0] for i in read_accessor(doc, buffers, prim["indices"])]
    else:
        idx = list(range(len(pos)))
    if mode == 4:
        tris = [idx[i:i + 3] for i in range(0, len(idx) - 2, 3)]
    elif mode == 5:
        tris = [(idx[i], idx[i + 1], idx[i + 2]) if i % 2 == 0 else (idx[i + 1], idx[i], idx[i + 2])
                for i in range(len(idx) - 2)]
    elif mode == 6:
        tris = [(idx[0], idx[i], idx[i + 1]) for i in range(1, len(idx) - 1)]
    else:
        return []  # points and lines have no area
    return [[pos[i] for i in t] for t in tris]


def material_info(doc, index):
    """(name, rgb, transmission or None, ior) of material `index` (None: glTF's default)."""
    if index is None:
        return ("default", (1.0, 1.0, 1.0), None, 1.5)
    m = doc["materials"][index]
    rgb = tuple(m.get("pbrMetallicRoughness", {}).get("baseColorFactor", [1, 1, 1, 1])[:3])
    ext = m.get("extensions", {})
    t = ext.get("KHR_materials_transmission", {}).get("transmissionFactor") \
        if "KHR_materials_transmission" in ext else None
    ior = ext.get("KHR_materials_ior", {}).get("ior", 1.5)
    return (m.get("name", "material%d" % index), rgb, t, ior)


def walk(doc):
    """Yields (node index, node, world matrix) for every node of the default scene."""
    scene = doc["scenes"][doc.get("scene", 0)]
    ident = [[1 if i == j else 0 for j in range(4)] for i in range(4)]
    stack = [(n, ident) for n in reversed(scene.get("nodes", []))]
    while stack:
        n, parent = stack.pop()
        node = doc["nodes"][n]
        world = mat_mul(parent, node_matrix(node))
        yield n, node, world
        for c in reversed(node.get("children", [])):
            stack.append((c, world))


def node_is_transmissive(doc, node):
    if "mesh" not in node:
        return False
    return any(material_info(doc, p.get("material"))[2] is not None
               for p in doc["meshes"][node["mesh"]]["primitives"])


def scene_triangles(doc, buffers, open_windows=False):
    """[(node name, material index, [v0, v1, v2] in glTF world coordinates)], and the names of
    the nodes dropped (open_windows: those whose mesh has a transmissive material)."""
    out, dropped = [], []
    for n, node, world in walk(doc):
        if "mesh" not in node:
            continue
        name = node.get("name", "node%d" % n)
        if open_windows and node_is_transmissive(doc, node):
            dropped.append(name)
            continue
        for prim in doc["meshes"][node["mesh"]]["primitives"]:
            for tri in primitive_triangles(doc, buffers, prim):
                out.append((name, prim.get("material"), [apply(world, v) for v in tri]))
    return out, dropped


def node_triangles(doc, buffers, node_name):
    """The world-space triangles of the node(s) called node_name."""
    tris = []
    for n, node, world in walk(doc):
        if node.get("name") == node_name and "mesh" in node:
            for prim in doc["meshes"][node["mesh"]]["primitives"]:
                tris += [[apply(world, v) for v in t]
                         for t in primitive_triangles(doc, buffers, prim)]
    return tris


# --------------------------------------------------------------------------------------------
# Radiance output


def to_radiance(p):
    """glTF (x, y up, z south) -> Radiance (x east, y north, z up)."""
    return (p[0], -p[2], p[1])


def ident(s):
    return re.sub(r"[^A-Za-z0-9_.-]", "_", s) or "_"


def glass_transmissivity(transmission, ior):
    """Radiance `glass` takes the transmissivity tn through the medium; its transmittance at
    normal incidence, two interfaces of reflectance R0 with interreflection, is
    Tn = tn (1 - R0)^2 / (1 - R0^2 tn^2). fenestra's thin glass has Tn = T (1 - R0(ior)) (one
    Fresnel interface, DESIGN.md §1). tn solves Radiance's equation for that Tn; R0 from the
    material's IOR (Radiance's glass itself assumes n = 1.52 unless given). Reference only: the
    angular behaviour of the two models differs, which is why comparisons use --open-windows."""
    r0 = ((ior - 1) / (ior + 1)) ** 2
    tn_target = transmission * (1 - r0)
    if tn_target <= 0:
        return 0.0
    # R0^2 Tn tn^2 + (1 - R0)^2 tn - Tn = 0
    a, b, c = r0 * r0 * tn_target, (1 - r0) ** 2, -tn_target
    if a < 1e-12:
        return min(1.0, -c / b)
    return min(1.0, (-b + math.sqrt(b * b - 4 * a * c)) / (2 * a))


def iso1_horizontal_factor(n=200000):
    """E_h / L_z for the ISO 15469 type 1 sky: 2 pi * integral_0^1 phi(mu)/phi(1) mu dmu."""
    phi = lambda mu: 1 + ISO1_A * math.exp(ISO1_B / mu) if mu > 0 else 1.0
    s = 0.0
    for i in range(n):  # midpoint rule; the integrand is smooth on [0, 1]
        mu = (i + 0.5) / n
        s += phi(mu) * mu
    return 2 * math.pi * s / n / phi(1.0)


ISO1_CAL = """{ cie_iso1.cal — written by fenestra's scripts/radiance/gltf_to_rad.py.
  Relative luminance of the CIE standard general sky of type 1 (ISO 15469 / CIE S 011:
  gradation a = %g, b = %g, no indicatrix): L / Lz = (1 + a exp(b / cos Z)) / (1 + a exp(b)),
  Dz = cos Z (Radiance's +z is up). Zero below the horizon (the source covers the upper
  hemisphere only). }
iso1a = %r;
iso1b = %r;
skybr = if(Dz - 1e-6, (1 + iso1a*exp(iso1b/Dz)) / (1 + iso1a*exp(iso1b)), 0);
"""


def sky_text(kind, sky_lux, out_dir):
    """The sky's Radiance description (and, for iso1, its .cal file written into out_dir)."""
    e_h = sky_lux / RADIANCE_EFFICACY  # W/m^2 of Radiance "white"
    lines = []
    if kind == "iso1":
        with open(os.path.join(out_dir, "cie_iso1.cal"), "w") as f:
            f.write(ISO1_CAL % (ISO1_A, ISO1_B, ISO1_A, ISO1_B))
        lz = e_h / iso1_horizontal_factor()
        lines += ["# CIE standard general sky type 1 (ISO 15469), diffuse horizontal %g lux:" % sky_lux,
                  "#   zenith radiance %.6g W/sr/m^2 (x 179 = %.6g cd/m^2)" % (lz, lz * RADIANCE_EFFICACY),
                  "void brightfunc skyfunc", "2 skybr cie_iso1.cal", "0", "0", "",
                  "skyfunc glow skyglow", "0", "0", "4 %.6g %.6g %.6g 0" % (lz, lz, lz)]
    elif kind == "gensky":
        cmd = ["gensky", "3", "21", "12", "-c", "-B", "%.6g" % e_h]
        txt = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
        lines += ["# %s (CIE overcast, Moon-Spencer; the date is irrelevant for -c)" % " ".join(cmd)]
        lines += [l for l in txt.splitlines() if not l.startswith("#")]
        lines += ["skyfunc glow skyglow", "0", "0", "4 1 1 1 0"]
    else:
        raise ValueError(kind)
    lines += ["", "# upper hemisphere only: no ground glow, no sun",
              "skyglow source sky", "0", "0", "4 0 0 1 180", ""]
    return "\n".join(lines)


def grey_of(rgb, weights):
    y = sum(w * c for w, c in zip(weights, rgb))
    return (y, y, y)


def write_rad(doc, buffers, out, open_windows, sky, sky_lux, grey=None):
    """Writes the Radiance scene; returns a summary dict."""
    tris, dropped = scene_triangles(doc, buffers, open_windows)
    out_dir = os.path.dirname(os.path.abspath(out))
    os.makedirs(out_dir, exist_ok=True)
    used = sorted({m for _, m, _ in tris}, key=lambda m: -1 if m is None else m)
    lines = ["# Radiance scene written by fenestra's scripts/radiance/gltf_to_rad.py",
             "# frame: (x, y, z)_glTF -> (x, -z, y)_Radiance; metres",
             "# open windows: %s; dropped nodes: %s" % (open_windows, ", ".join(dropped) or "none"),
             "", sky_text(sky, sky_lux, out_dir), "# materials"]
    names = {}
    for m in used:
        name, rgb, t, ior = material_info(doc, m)
        rid = "m%s_%s" % ("d" if m is None else m, ident(name))
        names[m] = rid
        if t is None:
            if grey:
                rgb = grey_of(rgb, REC709_WEIGHTS if grey == "rec709" else RADIANCE_WEIGHTS)
            lines += ["void plastic %s" % rid, "0", "0", "5 %.6g %.6g %.6g 0 0" % tuple(rgb), ""]
        else:
            tn = glass_transmissivity(t, ior)
            tint = [tn * c for c in rgb]
            lines += ["# KHR_materials_transmission %g, IOR %g -> glass transmissivity %.6g"
                      % (t, ior, tn),
                      "void glass %s" % rid, "0", "0", "4 %.6g %.6g %.6g %.6g" % (tuple(tint) + (ior,)), ""]
    lines.append("# geometry: one polygon per triangle")
    count = {}
    for node, m, tri in tris:
        k = count.get(node, 0)
        count[node] = k + 1
        v = [to_radiance(p) for p in tri]
        lines.append("%s polygon %s.%d" % (names[m], ident(node), k))
        lines.append("0\n0\n9 " + "  ".join("%.9g %.9g %.9g" % p for p in v))
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")
    return {"triangles": len(tris), "dropped_nodes": dropped}


def write_open_gltf(path_in, doc, out):
    """The input document minus every node whose mesh has a transmissive material."""
    doc = json.loads(json.dumps(doc))
    doc_nodes = list(doc.get("nodes", []))
    drop = {i for i, n in enumerate(doc.get("nodes", [])) if node_is_transmissive(doc, n)}
    remap, nodes = {}, []
    for i, n in enumerate(doc.get("nodes", [])):
        if i not in drop:
            remap[i] = len(nodes)
            nodes.append(n)
    for n in nodes:
        if "children" in n:
            n["children"] = [remap[c] for c in n["children"] if c in remap]
            if not n["children"]:
                del n["children"]
    doc["nodes"] = nodes
    for s in doc.get("scenes", []):
        s["nodes"] = [remap[c] for c in s.get("nodes", []) if c in remap]
    src, dst = os.path.dirname(os.path.abspath(path_in)), os.path.dirname(os.path.abspath(out))
    for buf in doc.get("buffers", []) + doc.get("images", []):
        uri = buf.get("uri", "")
        if uri and not uri.startswith("data:") and not os.path.isabs(uri):
            buf["uri"] = os.path.relpath(os.path.join(src, uri), dst)
    if path_in.endswith(".glb"):
        sys.exit("gltf_to_rad.py: --write-gltf needs a .gltf input (its buffers stay as they are)")
    os.makedirs(dst, exist_ok=True)
    with open(out, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    return [doc_in_node.get("name", "node%d" % i) for i, doc_in_node in enumerate(doc_nodes)
            if i in drop]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("--out", help="Radiance scene to write (.rad)")
    ap.add_argument("--open-windows", action="store_true",
                    help="drop every node with a transmissive material")
    ap.add_argument("--write-gltf", metavar="OUT", help="write the open-window glTF variant")
    ap.add_argument("--sky", choices=("iso1", "gensky"), default="iso1")
    ap.add_argument("--sky-lux", type=float, default=SKY_LUX_DEFAULT)
    ap.add_argument("--grey", choices=("rec709", "radiance"))
    a = ap.parse_args()
    doc, buffers = load_gltf(a.scene)
    if a.out:
        info = write_rad(doc, buffers, a.out, a.open_windows, a.sky, a.sky_lux, a.grey)
        print("%s: %d triangles; dropped: %s" % (a.out, info["triangles"],
                                                 ", ".join(info["dropped_nodes"]) or "none"))
    if a.write_gltf:
        write_open_gltf(a.scene, doc, a.write_gltf)
        print("%s: open-window glTF" % a.write_gltf)
    if not a.out and not a.write_gltf:
        ap.error("nothing to do: give --out and/or --write-gltf")
    return 0


if __name__ == "__main__":
    sys.exit(main())
