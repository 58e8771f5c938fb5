#!/usr/bin/env python3
"""mitsuba_peer.py — renders a shipped scene with Mitsuba 3's light tracer (`ptracer`), an
independent implementation of the same algorithm, to check fenestra's images and efficiency.

Not part of the build or the tests: Mitsuba is not a dependency (`pip install mitsuba` first).
The measurements it made are in docs/results/peer.md.

The scene is converted from the glTF as fenestra reads it (docs/DESIGN.md §1): world-space
triangles; two-sided Lambertian surfaces (`twosided` + `diffuse`: each side shows only the light
that reached it); thin glass as `thindielectric` (the one difference: Mitsuba's sheet has two
interfaces with inter-reflection, R ~ 2R1/(1+R1), where fenestra's reflects one interface's R1, so
the window passes ~4 % less light at normal incidence); a transparent opening (transmission 1,
IOR 1) is left out; the CIE sky is baked into a latitude-longitude `envmap` with the formula of
host/sky/cie_sky.cpp (zero below the horizon); the sun is a `directional` emitter of the glTF's
illuminance; the camera is a pinhole of the glTF's vertical field of view. Radiance values are
cd/m² in every channel, as in fenestra's images.

    python3 scripts/mitsuba_peer.py scenes/inner_room.gltf --width 320 --spp 64 --runs 8 \
        --out out/peer/mi_box --filter box

writes OUT_<k>.exr for k = 1..runs and OUT.json with each run's render seconds.

`--integrator path` renders the same conversion with Mitsuba's path tracer instead (`--spp` then
counts camera samples per pixel): a second estimator of the same scene, and far faster than the
light tracer for a small region that light reaches by many bounces (docs/results/peer.md, the gap
under the inner room's door); it also shows the sky seen directly (the light tracer hides it: that
light is fenestra's camera pass). `--crop x0,y0,x1,y1` renders only that rectangle of the image (x1, y1
exclusive; the EXR is the rectangle's size), for a region that needs many samples.
"""
import argparse
import base64
import json
import math
import os
import struct
import sys
import time

import numpy as np

# Table 1 of ISO 15469:2004 (a, b, c, d, e), the same numbers as host/sky/cie_sky.cpp.
CIE = {1: (4.0, -0.70, 0, -1.0, 0.00), 2: (4.0, -0.70, 2, -1.5, 0.15),
       3: (1.1, -0.80, 0, -1.0, 0.00), 4: (1.1, -0.80, 2, -1.5, 0.15),
       5: (0.0, -1.00, 0, -1.0, 0.00), 6: (0.0, -1.00, 2, -1.5, 0.15),
       7: (0.0, -1.00, 5, -2.5, 0.30), 8: (0.0, -1.00, 10, -3.0, 0.45),
       9: (-1.0, -0.55, 2, -1.5, 0.15), 10: (-1.0, -0.55, 5, -2.5, 0.30),
       11: (-1.0, -0.55, 10, -3.0, 0.45), 12: (-1.0, -0.32, 10, -3.0, 0.45),
       13: (-1.0, -0.32, 16, -3.0, 0.30), 14: (-1.0, -0.15, 16, -3.0, 0.30),
       15: (-1.0, -0.15, 24, -2.8, 0.15)}


def sky_direction(zenith, azimuth):
    """Unit vector towards a sky point, radians (DESIGN.md §1: azimuth from north, -z, to east, +x)."""
    return np.stack([np.sin(zenith) * np.sin(azimuth), np.cos(zenith),
                     -np.sin(zenith) * np.cos(azimuth)], axis=-1)


def cie_luminance(sky, dirs):
    """Luminance (cd/m²) of the CIE sky `sky` (the glTF's scene extras) towards unit `dirs`."""
    a, b, c, d, e = CIE[int(sky["cie_type"])]
    zs = math.radians(90.0 - sky["sun_altitude_deg"])
    sun = sky_direction(np.float64(zs), np.float64(math.radians(sky["sun_azimuth_deg"])))
    cos_z = dirs[..., 1]
    cos_chi = np.clip(dirs @ sun, -1.0, 1.0)
    chi = np.arccos(cos_chi)

    def gradation(cz):
        with np.errstate(divide="ignore", over="ignore"):
            return np.where(cz > 0, 1.0 + a * np.exp(b / np.maximum(cz, 1e-12)), 1.0)

    def indicatrix(x):
        return 1.0 + c * (np.exp(d * x) - math.exp(d * math.pi / 2)) + e * np.cos(x) ** 2

    rel = indicatrix(chi) * gradation(cos_z) / (indicatrix(zs) * gradation(1.0))
    return np.where(cos_z > 0, sky["zenith_luminance"] * rel, 0.0)


def read_gltf(path):
    doc = json.load(open(path))
    uri = doc["buffers"][0]["uri"]
    blob = base64.b64decode(uri.split(",", 1)[1])
    return doc, blob


def positions(doc, blob, accessor):
    acc = doc["accessors"][accessor]
    view = doc["bufferViews"][acc["bufferView"]]
    off = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
    return np.frombuffer(blob, dtype="<f4", count=acc["count"] * 3, offset=off).reshape(-1, 3)


def quat_rotate(q, v):
    x, y, z, w = q
    u = np.array([x, y, z])
    return 2 * np.dot(u, v) * u + (w * w - np.dot(u, u)) * v + 2 * w * np.cross(u, v)


def write_ply(path, tris):
    n = len(tris)
    with open(path, "wb") as f:
        f.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\n"
                 "property float x\nproperty float y\nproperty float z\n"
                 "element face %d\nproperty list uchar int vertex_indices\nend_header\n"
                 % (n, n // 3)).encode())
        f.write(tris.astype("<f4").tobytes())
        for i in range(0, n, 3):
            f.write(struct.pack("<Biii", 3, i, i + 1, i + 2))


def scene_dict(mi, gltf_path, width, spp, rfilter, workdir, sky_res=(2048, 1024), crop=None):
    doc, blob = read_gltf(gltf_path)
    os.makedirs(workdir, exist_ok=True)
    scene = {"type": "scene"}
    mats = doc["materials"]
    if any("children" in n for n in doc["nodes"]):
        sys.exit(f"{gltf_path}: node hierarchies are not converted (only flat scenes, as shipped)")
    for i, node in enumerate(doc["nodes"]):
        if "mesh" in node:
            if any(k in node for k in ("translation", "rotation", "scale", "matrix")):
                sys.exit(f"{gltf_path}: node {node['name']}: only world-space meshes are converted")
            for j, prim in enumerate(doc["meshes"][node["mesh"]]["primitives"]):
                if "indices" in prim:
                    sys.exit(f"{gltf_path}: node {node['name']}: indexed meshes are not converted")
                m = mats[prim["material"]]
                rgb = m["pbrMetallicRoughness"]["baseColorFactor"][:3]
                ext = m.get("extensions", {})
                t = ext.get("KHR_materials_transmission", {}).get("transmissionFactor", 0.0)
                if t > 0.0:  # fenestra: glass only where something passes
                    ior = ext.get("KHR_materials_ior", {}).get("ior", 1.5)
                    if ior == 1.0 and t == 1.0:
                        continue  # an opening: nothing to draw
                    bsdf = {"type": "thindielectric", "int_ior": ior, "ext_ior": 1.0,
                            "specular_transmittance": {"type": "rgb",
                                                       "value": [t * c for c in rgb]}}
                else:
                    bsdf = {"type": "twosided", "material": {
                        "type": "diffuse", "reflectance": {"type": "rgb", "value": rgb}}}
                ply = os.path.join(workdir, f"mesh_{i}_{j}.ply")
                write_ply(ply, positions(doc, blob, prim["attributes"]["POSITION"]))
                scene[f"mesh_{i}_{j}"] = {"type": "ply", "filename": ply, "bsdf": bsdf}
        elif "KHR_lights_punctual" in node.get("extensions", {}):
            light = doc["extensions"]["KHR_lights_punctual"]["lights"][
                node["extensions"]["KHR_lights_punctual"]["light"]]
            travel = quat_rotate(node.get("rotation", [0, 0, 0, 1]), np.array([0.0, 0.0, -1.0]))
            if light.get("extras", {}).get("angular_radius_deg", 0.0) > 0.0:
                sys.exit(f"{gltf_path}: a sun of finite angular radius is not converted")
            e = light["intensity"]
            scene["sun"] = {"type": "directional", "direction": travel.tolist(),
                            "irradiance": {"type": "rgb",
                                           "value": [e * c for c in light.get("color", [1, 1, 1])]}}
        elif "camera" in node:
            cam = doc["cameras"][node["camera"]]["perspective"]
            q = node.get("rotation", [0, 0, 0, 1])
            org = np.array(node.get("translation", [0, 0, 0]), dtype=float)
            fwd = quat_rotate(q, np.array([0.0, 0.0, -1.0]))
            up = quat_rotate(q, np.array([0.0, 1.0, 0.0]))
            height = int(round(width / cam["aspectRatio"]))
            scene["camera"] = {
                "type": "perspective", "fov": math.degrees(cam["yfov"]), "fov_axis": "y",
                "near_clip": cam.get("znear", 0.01),
                "to_world": mi.ScalarTransform4f().look_at(origin=org.tolist(),
                                                           target=(org + fwd).tolist(),
                                                           up=up.tolist()),
                "film": {"type": "hdrfilm", "width": width, "height": height,
                         "pixel_format": "rgb", "rfilter": {"type": rfilter}},
                "sampler": {"type": "independent", "sample_count": spp}}
            if crop:
                x0, y0, x1, y1 = crop
                if not (0 <= x0 < x1 <= width and 0 <= y0 < y1 <= height):
                    sys.exit(f"--crop {x0},{y0},{x1},{y1}: must lie inside the {width} x {height} image")
                scene["camera"]["film"].update({"crop_offset_x": x0, "crop_offset_y": y0,
                                                "crop_width": x1 - x0, "crop_height": y1 - y0})
    sky = doc["scenes"][0].get("extras", {}).get("sky")
    if sky:
        if sky.get("type") != "cie":
            sys.exit(f"{gltf_path}: scene extras.sky.type {sky.get('type')!r}: only 'cie' is converted")
        w, h = sky_res
        # Mitsuba's envmap: u = atan2(x, -z) / 2pi, v = acos(y) / pi in its frame (+y up), texel
        # centres; checked against the emitter's own eval by --check-sky.
        u = (np.arange(w) + 0.5) / w
        v = (np.arange(h) + 0.5) / h
        phi = 2 * math.pi * u[None, :]
        theta = math.pi * v[:, None]
        dirs = np.stack(np.broadcast_arrays(np.sin(theta) * np.sin(phi), np.cos(theta),
                                            -np.sin(theta) * np.cos(phi)), axis=-1)
        lum = cie_luminance(sky, dirs)
        img = np.repeat(lum[..., None], 3, axis=2).astype(np.float32)
        scene["sky"] = {"type": "envmap", "bitmap": mi.Bitmap(img)}
    return scene


def check_sky(mi, scene, sky):
    """The envmap's own eval against the formula in a few directions: orientation and scale."""
    emitter = [e for e in scene.emitters() if e.is_environment()][0]
    rng = np.random.default_rng(1)
    worst = 0.0
    for _ in range(200):
        d = rng.normal(size=3)
        d /= np.linalg.norm(d)
        if d[1] < 0.05:
            d[1] = abs(d[1]) + 0.05
            d /= np.linalg.norm(d)
        si = mi.SurfaceInteraction3f()
        si.wi = mi.Vector3f(*(-d))
        got = emitter.eval(si)[0]
        want = float(cie_luminance(sky, d[None, :])[0])
        worst = max(worst, abs(got - want) / want)
    return worst


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--spp", type=int, default=64, help="light paths per pixel per run")
    ap.add_argument("--runs", type=int, default=8)
    ap.add_argument("--seed0", type=int, default=1)
    ap.add_argument("--filter", default="box", help="Mitsuba rfilter: box (fenestra's) or gaussian (Mitsuba's default)")
    ap.add_argument("--rr-depth", type=int, default=5, help="ptracer rr_depth (Mitsuba's default 5)")
    ap.add_argument("--integrator", default="ptracer", choices=("ptracer", "path"),
                    help="Mitsuba's light tracer (default: fenestra's algorithm) or its path tracer")
    ap.add_argument("--crop", help="x0,y0,x1,y1: render only this rectangle (x1, y1 exclusive)")
    ap.add_argument("--out", required=True, help="output prefix")
    ap.add_argument("--check-sky", action="store_true")
    args = ap.parse_args()

    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    work = args.out + "_meshes"
    crop = None
    if args.crop:
        try:
            crop = tuple(int(v) for v in args.crop.split(","))
        except ValueError:
            crop = ()
        if len(crop) != 4:
            sys.exit(f"--crop {args.crop}: expected x0,y0,x1,y1")
    d = scene_dict(mi, args.scene, args.width, args.spp, args.filter, work, crop=crop)
    d["integrator"] = {"type": args.integrator, "max_depth": -1, "rr_depth": args.rr_depth,
                       "hide_emitters": args.integrator == "ptracer"}
    scene = mi.load_dict(d)
    if args.check_sky:
        doc, _ = read_gltf(args.scene)
        print("sky: worst relative difference of envmap eval against the formula: %.4f"
              % check_sky(mi, scene, doc["scenes"][0]["extras"]["sky"]))
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    runs = []
    for k in range(args.runs):
        seed = args.seed0 + k
        t0 = time.perf_counter()
        img = mi.render(scene, seed=seed)
        secs = time.perf_counter() - t0
        path = f"{args.out}_{k + 1}.exr"
        mi.Bitmap(img).write(path)
        runs.append({"exr": path, "seed": seed, "render_seconds": secs})
        print(f"run {k + 1}: {secs:.2f} s -> {path}", flush=True)
    json.dump({"scene": args.scene, "width": args.width, "spp": args.spp, "filter": args.filter,
               "integrator": args.integrator, "crop": list(crop) if crop else None,
               "rr_depth": args.rr_depth, "mitsuba": mi.__version__, "runs": runs},
              open(args.out + ".json", "w"), indent=1)


if __name__ == "__main__":
    main()
