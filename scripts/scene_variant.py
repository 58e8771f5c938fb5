#!/usr/bin/env python3
"""scene_variant.py — a copy of a glTF scene with some materials' colours changed: what-if studies
(a darker ground, whiter walls) and controlled experiments (docs/results/house.md: the house with
a black ground, to measure how much of its noise the light reflected off the ground makes).

    python3 scripts/scene_variant.py scenes/house.gltf --material ground=0,0,0 --out out/house_black_ground.gltf

--material NAME=R,G,B sets that material's base colour (linear, 0..1; repeatable). The scene must
keep its buffers inside the file (data URIs, as every shipped scene does) or beside it: relative
buffer paths are rewritten to stay valid from the new location.
"""
import argparse
import json
import os
import sys


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("--material", action="append", default=[], metavar="NAME=R,G,B")
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
