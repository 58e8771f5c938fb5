#!/usr/bin/env python3
"""through_stats.py — the mean luminance of the pixels that see through one node of a scene (the
inner room's `gap` under its door), in several renders of it, and the standard error of that mean
over the renders: how fenestra and a peer (scripts/mitsuba_peer.py) are compared in a region no
rectangle fits (docs/results/peer.md, "The gap under the inner room's door").

    python3 scripts/through_stats.py out/gap/zoom.gltf --node gap out/gap/fen_*.exr
    python3 scripts/through_stats.py out/gap/open.gltf --node gap --width 320 --crop-offset 30,140 out/gap/mi_*.exr

A pixel counts when its whole footprint (its corners, edge midpoints and centre) sees through the
node's triangles from the scene's first camera, as fenestra's camera maps pixels (row 0 at the top;
docs/DESIGN.md §1); pixels half on the node's edge are left out, so that a difference in how the
renderers filter an edge cannot count. Nothing in front of the node is checked for occlusion;
`--node all` takes every pixel (a whole image's mean, with the same statistics). The
luminance is Y = 0.2126 R + 0.7152 G + 0.0722 B (DESIGN.md §1) for every renderer alike; the script
also prints Y over the channels' mean and over G in the region, which say how far a comparison
that reduced one renderer's colour some other way would be off. Renders made with
mitsuba_peer.py --crop are placed with --crop-offset, and --width gives the full image's width
(the height follows the camera's aspect ratio). Reads EXR through Mitsuba (`pip install mitsuba`),
as the other peer scripts do; not part of the build or the tests.
"""
import argparse
import base64
import json
import math
import sys

import numpy as np

LUMA = np.array([0.2126, 0.7152, 0.0722])


def quat_rotate(q, v):
    x, y, z, w = q
    u = np.array([x, y, z])
    return 2 * np.dot(u, v) * u + (w * w - np.dot(u, u)) * v + 2 * w * np.cross(u, v)


def node_triangles(doc, name):
    """World-space triangles (n, 3, 3) of node `name`: flat, non-indexed meshes, as shipped."""
    nodes = [n for n in doc["nodes"] if n.get("name") == name and "mesh" in n]
    if not nodes:
        sys.exit(f"through_stats.py: no mesh node named {name!r}")
    if any(k in nodes[0] for k in ("translation", "rotation", "scale", "matrix")):
        sys.exit(f"through_stats.py: node {name}: only world-space meshes are read")
    blob = base64.b64decode(doc["buffers"][0]["uri"].split(",", 1)[1])
    tris = []
    for prim in doc["meshes"][nodes[0]["mesh"]]["primitives"]:
        if "indices" in prim:
            sys.exit(f"through_stats.py: node {name}: indexed meshes are not read")
        acc = doc["accessors"][prim["attributes"]["POSITION"]]
        view = doc["bufferViews"][acc["bufferView"]]
        off = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
        tris.append(np.frombuffer(blob, dtype="<f4", count=acc["count"] * 3, offset=off)
                    .astype(float).reshape(-1, 3, 3))
    return np.concatenate(tris)


def through_mask(doc, name, width, height):
    """Pixels (height, width) whose whole footprint sees through node `name`'s triangles."""
    node = [n for n in doc["nodes"] if "camera" in n][0]
    cam = doc["cameras"][node["camera"]]["perspective"]
    q = node.get("rotation", [0, 0, 0, 1])
    org = np.array(node.get("translation", [0, 0, 0]), dtype=float)
    fwd = quat_rotate(q, np.array([0.0, 0.0, -1.0]))
    up = quat_rotate(q, np.array([0.0, 1.0, 0.0]))
    right = np.cross(fwd, up)
    tan_y = math.tan(0.5 * cam["yfov"])
    tan_x = tan_y * width / height
    tris = node_triangles(doc, name)
    py, px = np.mgrid[0:height, 0:width].astype(float)
    mask = np.ones((height, width), bool)
    for a in (0.0, 0.5, 1.0):
        for b in (0.0, 0.5, 1.0):
            sx = (2 * (px + a) / width - 1) * tan_x
            sy = (1 - 2 * (py + b) / height) * tan_y
            d = fwd + sx[..., None] * right + sy[..., None] * up
            hit = np.zeros((height, width), bool)
            for p0, p1, p2 in tris:  # Moller-Trumbore against each triangle
                e1, e2 = p1 - p0, p2 - p0
                pv = np.cross(d, e2)
                det = pv @ e1
                with np.errstate(divide="ignore", invalid="ignore"):
                    inv = 1.0 / det
                    tv = org - p0
                    u = (pv @ tv) * inv
                    qv = np.cross(tv, e1)
                    v = (d @ qv) * inv
                    t = (qv @ e2) * inv
                hit |= (np.abs(det) > 1e-12) & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 0)
            mask &= hit
    return mask


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("exrs", nargs="+")
    ap.add_argument("--node", default="gap", help="mesh node the pixels see through, or all (default gap)")
    ap.add_argument("--width", type=int, help="the full image's width (default: each EXR's own)")
    ap.add_argument("--crop-offset", default="0,0", help="x0,y0 of a cropped EXR in the full image")
    a = ap.parse_args()
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    doc = json.load(open(a.scene))
    aspect = [doc["cameras"][n["camera"]]["perspective"] for n in doc["nodes"] if "camera" in n][0]["aspectRatio"]
    x0, y0 = (int(v) for v in a.crop_offset.split(","))
    means, rgb, mask = [], np.zeros(3), None
    for path in a.exrs:
        img = np.array(mi.Bitmap(path), dtype=float)[..., :3]
        if mask is None:
            w = a.width or img.shape[1]
            h = int(round(w / aspect))
            full = np.ones((h, w), bool) if a.node == "all" else through_mask(doc, a.node, w, h)
            mask = full[y0:y0 + img.shape[0], x0:x0 + img.shape[1]]
            print(f"{mask.sum()} pixels see wholly through {a.node} ({full.sum()} in the full image)")
        region = img[mask]
        means.append(float(region.mean(axis=0) @ LUMA))
        rgb += region.mean(axis=0)
    m = np.array(means)
    se = m.std(ddof=1) / math.sqrt(len(m)) if len(m) > 1 else float("nan")
    y = rgb @ LUMA
    print(f"renders {len(m)}: mean luminance {m.mean():.6g} cd/m2, standard error {se:.3g} "
          f"({100 * se / m.mean():.3f} %), one render's spread {100 * m.std(ddof=1) / m.mean() if len(m) > 1 else float('nan'):.2f} %")
    print(f"Y / mean(R, G, B) = {y / rgb.mean():.4f}, Y / G = {y / rgb[1]:.4f}")


if __name__ == "__main__":
    main()
