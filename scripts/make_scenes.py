#!/usr/bin/env python3
"""make_scenes.py — writes the scenes fenestra ships (scenes/*.gltf) from code.

Run from the repository root: `python3 scripts/make_scenes.py`. Standard library only; the
outputs are committed, so neither the build nor the tests run this. Each scene models no more
than it needs (DESIGN.md §1): zero-thickness walls (surfaces are two-sided, and the renderer only
lets light reach the camera from the side it arrived on), one ground plane, one glass pane.

Frame: metres, +y up, +x east, +z south, -z north (DESIGN.md §1); azimuth from north towards east.
"""
import base64
import json
import math
import os
import struct


class Gltf:
    """A glTF 2.0 document with one embedded buffer."""

    def __init__(self, generator):
        self.doc = {
            "asset": {"version": "2.0", "generator": generator},
            "scene": 0,
            "scenes": [{"nodes": []}],
            "nodes": [], "meshes": [], "materials": [], "accessors": [],
            "bufferViews": [], "buffers": [],
        }
        self.bin = bytearray()
        self.material_index = {}

    def material(self, name, rgb, transmission=None, ior=None):
        if name in self.material_index:
            return self.material_index[name]
        m = {"name": name,
             "pbrMetallicRoughness": {"baseColorFactor": list(rgb) + [1.0],
                                      "metallicFactor": 0.0, "roughnessFactor": 1.0}}
        ext = {}
        if transmission is not None:
            ext["KHR_materials_transmission"] = {"transmissionFactor": transmission}
        if ior is not None:
            ext["KHR_materials_ior"] = {"ior": ior}
        if ext:
            m["extensions"] = ext
            for k in ext:
                self.doc.setdefault("extensionsUsed", [])
                if k not in self.doc["extensionsUsed"]:
                    self.doc["extensionsUsed"].append(k)
        self.doc["materials"].append(m)
        self.material_index[name] = len(self.doc["materials"]) - 1
        return self.material_index[name]

    def _view(self, data, target):
        while len(self.bin) % 4:
            self.bin.append(0)
        off = len(self.bin)
        self.bin += data
        self.doc["bufferViews"].append(
            {"buffer": 0, "byteOffset": off, "byteLength": len(data), "target": target})
        return len(self.doc["bufferViews"]) - 1

    def mesh_node(self, name, triangles, material, extras=None):
        """triangles: list of (p0, p1, p2) with p = (x, y, z) in world space."""
        pos = [c for tri in triangles for p in tri for c in p]
        data = struct.pack("<%df" % len(pos), *pos)
        view = self._view(data, 34962)
        lo = [min(pos[i::3]) for i in range(3)]
        hi = [max(pos[i::3]) for i in range(3)]
        self.doc["accessors"].append({"bufferView": view, "componentType": 5126,
                                      "count": len(pos) // 3, "type": "VEC3",
                                      "min": lo, "max": hi})
        acc = len(self.doc["accessors"]) - 1
        self.doc["meshes"].append({"name": name, "primitives": [
            {"attributes": {"POSITION": acc}, "material": material}]})
        node = {"name": name, "mesh": len(self.doc["meshes"]) - 1}
        if extras:
            node["extras"] = extras
        return self._add_node(node)

    def _add_node(self, node):
        self.doc["nodes"].append(node)
        idx = len(self.doc["nodes"]) - 1
        self.doc["scenes"][0]["nodes"].append(idx)
        return idx

    def sun(self, name, altitude_deg, azimuth_deg, illuminance_lux):
        """A directional light whose light travels away from the sun at (altitude, azimuth)."""
        self.doc.setdefault("extensionsUsed", []).append("KHR_lights_punctual")
        self.doc.setdefault("extensions", {})["KHR_lights_punctual"] = {
            "lights": [{"name": name, "type": "directional", "intensity": illuminance_lux,
                        "color": [1.0, 1.0, 1.0]}]}
        to_sun = sky_direction(90.0 - altitude_deg, azimuth_deg)
        # the node's +z must point at the sun (light travels along -z)
        return self._add_node({"name": name, "rotation": quat_z_to(to_sun),
                               "extensions": {"KHR_lights_punctual": {"light": 0}}})

    def camera(self, name, position, target, yfov_deg, aspect):
        self.doc.setdefault("cameras", []).append(
            {"name": name, "type": "perspective",
             "perspective": {"yfov": math.radians(yfov_deg), "aspectRatio": aspect,
                             "znear": 0.05}})
        fwd = normalize(sub(target, position))
        return self._add_node({"name": name, "camera": len(self.doc["cameras"]) - 1,
                               "translation": list(position),
                               "rotation": quat_look(fwd, (0.0, 1.0, 0.0))})

    def write(self, path, sky):
        self.doc["scenes"][0]["extras"] = {"sky": sky}
        self.doc["buffers"] = [{"byteLength": len(self.bin),
                                "uri": "data:application/octet-stream;base64," +
                                       base64.b64encode(bytes(self.bin)).decode()}]
        with open(path, "w") as f:
            json.dump(self.doc, f, indent=1)
            f.write("\n")


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(a):
    n = math.sqrt(sum(x * x for x in a))
    return tuple(x / n for x in a)


def sky_direction(zenith_deg, azimuth_deg):
    """Unit vector towards the sky point (DESIGN.md §1 convention)."""
    t, p = math.radians(zenith_deg), math.radians(azimuth_deg)
    return (math.sin(t) * math.sin(p), math.cos(t), -math.sin(t) * math.cos(p))


def quat_from_matrix(m):
    """Quaternion (x, y, z, w) of a rotation matrix given as columns m[0], m[1], m[2]."""
    r = [[m[c][r] for c in range(3)] for r in range(3)]
    tr = r[0][0] + r[1][1] + r[2][2]
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        return [(r[2][1] - r[1][2]) / s, (r[0][2] - r[2][0]) / s, (r[1][0] - r[0][1]) / s, 0.25 * s]
    if r[0][0] > r[1][1] and r[0][0] > r[2][2]:
        s = math.sqrt(1.0 + r[0][0] - r[1][1] - r[2][2]) * 2
        return [0.25 * s, (r[0][1] + r[1][0]) / s, (r[0][2] + r[2][0]) / s, (r[2][1] - r[1][2]) / s]
    if r[1][1] > r[2][2]:
        s = math.sqrt(1.0 + r[1][1] - r[0][0] - r[2][2]) * 2
        return [(r[0][1] + r[1][0]) / s, 0.25 * s, (r[1][2] + r[2][1]) / s, (r[0][2] - r[2][0]) / s]
    s = math.sqrt(1.0 + r[2][2] - r[0][0] - r[1][1]) * 2
    return [(r[0][2] + r[2][0]) / s, (r[1][2] + r[2][1]) / s, 0.25 * s, (r[1][0] - r[0][1]) / s]


def quat_look(forward, up):
    """Rotation whose -z is `forward` and whose +y is as close to `up` as possible."""
    z = tuple(-c for c in forward)
    x = normalize(cross(up, z))
    y = cross(z, x)
    return quat_from_matrix([x, y, z])


def quat_z_to(direction):
    """Rotation taking +z to `direction`."""
    z = normalize(direction)
    helper = (0.0, 1.0, 0.0) if abs(z[1]) < 0.9 else (1.0, 0.0, 0.0)
    x = normalize(cross(helper, z))
    y = cross(z, x)
    return quat_from_matrix([x, y, z])


def quad(a, b, c, d):
    """Two triangles of the planar quad a-b-c-d (in order around its edge)."""
    return [(a, b, c), (a, c, d)]


def rect_x(x0, x1, y0, y1, z):
    """Rectangle in the plane z = const."""
    return quad((x0, y0, z), (x1, y0, z), (x1, y1, z), (x0, y1, z))


def rect_z(z0, z1, y0, y1, x):
    """Rectangle in the plane x = const."""
    return quad((x, y0, z0), (x, y0, z1), (x, y1, z1), (x, y1, z0))


def rect_y(x0, x1, z0, z1, y):
    """Rectangle in the plane y = const."""
    return quad((x0, y, z0), (x1, y, z0), (x1, y, z1), (x0, y, z1))


def wall_with_hole(x0, x1, y0, y1, z, hx0, hx1, hy0, hy1):
    """Wall in the plane z = const with a rectangular opening, as four rectangles."""
    return (rect_x(x0, x1, y0, hy0, z) + rect_x(x0, x1, hy1, y1, z) +
            rect_x(x0, hx0, hy0, hy1, z) + rect_x(hx1, x1, hy0, hy1, z))


def room_scene(path):
    """scenes/room.gltf — the default scene: a 5 x 4 x 2.8 m room with one south window.

    Sun at altitude 35 deg, azimuth 150 deg (south-south-east), 75 klux; CIE standard clear sky
    (type 12) for the same sun, zenith luminance 3500 cd/m^2. The window (2 x 1.5 m, sill at
    0.9 m) is glazed: thin glass, transmission 0.9, IOR 1.5. Outside, a 20 x 20 m ground plane of
    albedo 0.2. The camera stands in the north-west corner at eye height, looking at the window
    and the sun patch on the floor.
    """
    g = Gltf("fenestra scripts/make_scenes.py")
    W, D, H = 5.0, 4.0, 2.8          # room: x in [0, W], z in [0, D] (south wall at z = D)
    wx0, wx1, wy0, wy1 = 1.5, 3.5, 0.9, 2.4
    floor = g.material("floor", (0.35, 0.3, 0.25))
    wall = g.material("wall", (0.7, 0.7, 0.7))
    ceiling = g.material("ceiling", (0.8, 0.8, 0.8))
    ground = g.material("ground", (0.2, 0.2, 0.2))
    glass = g.material("glass", (1.0, 1.0, 1.0), transmission=0.9, ior=1.5)
    g.mesh_node("floor", rect_y(0, W, 0, D, 0.0), floor)
    g.mesh_node("ceiling", rect_y(0, W, 0, D, H), ceiling)
    g.mesh_node("north_wall", rect_x(0, W, 0, H, 0.0), wall)
    g.mesh_node("west_wall", rect_z(0, D, 0, H, 0.0), wall)
    g.mesh_node("east_wall", rect_z(0, D, 0, H, W), wall)
    g.mesh_node("south_wall", wall_with_hole(0, W, 0, H, D, wx0, wx1, wy0, wy1), wall)
    g.mesh_node("window", rect_x(wx0, wx1, wy0, wy1, D), glass, extras={"portal": True})
    g.mesh_node("ground", rect_y(-7.5, 12.5, -8.0, 12.0, -0.02), ground)
    g.sun("sun", 35.0, 150.0, 75000.0)
    g.camera("camera", (0.4, 1.6, 0.4), (3.2, 0.4, 3.2), 60.0, 4.0 / 3.0)
    g.write(path, {"type": "cie", "cie_type": 12, "zenith_luminance": 3500.0,
                   "sun_altitude_deg": 35.0, "sun_azimuth_deg": 150.0})


def frame_x(x0, x1, y0, y1, z, w):
    """The frame of an opening [x0,x1] x [y0,y1] in the plane z: strips of width w around it."""
    return (rect_x(x0 - w, x1 + w, y0 - w, y0, z) + rect_x(x0 - w, x1 + w, y1, y1 + w, z) +
            rect_x(x0 - w, x0, y0, y1, z) + rect_x(x1, x1 + w, y0, y1, z))


def inner_room_scene(path):
    """scenes/inner_room.gltf — after the paper's Fig. 2: an inner room lit only through the gap
    under its closed door, from an outer room with a large window and an open door.

    Outer room x in [0, 6], z in [0, 5] (south), 3 m high: a 3.5 x 1.8 m glazed window in its
    south wall (node `window`, extras.portal = true) and an open 1 x 2.1 m doorway in its east
    wall, marked by its frame (node `door_frame`, extras.portal = "hull": fenestra emits through
    the frame's convex hull, the doorway). Inner room x in [0, 6], z in [-4, 0], no window; the
    partition wall at z = 0 has a closed door (x in [3.5, 4.4]) with a 5 cm gap under it. The
    gap's opening is node `gap`: a surface of a fully transparent material (transmission 1,
    IOR 1: nothing reflects, everything passes), unmarked, so `--portals gap` reproduces the
    paper's wrong choice. No ground outside: all light enters through the window and the door.
    Sun at altitude 30 deg, azimuth 200 deg (south-south-west), 60 klux, CIE clear sky (type 12)
    for it, zenith luminance 3000 cd/m^2. The camera stands in the inner room and looks to the
    right of the door (west of it: the camera faces south).
    """
    g = Gltf("fenestra scripts/make_scenes.py")
    X, Y, Zo, Zi = 6.0, 3.0, 5.0, -4.0
    floor = g.material("floor", (0.3, 0.3, 0.3))
    wall = g.material("wall", (0.7, 0.7, 0.7))
    ceiling = g.material("ceiling", (0.8, 0.8, 0.8))
    door = g.material("door", (0.5, 0.4, 0.3))
    glass = g.material("glass", (1.0, 1.0, 1.0), transmission=0.9, ior=1.5)
    opening = g.material("opening", (1.0, 1.0, 1.0), transmission=1.0, ior=1.0)
    # window (south wall z = Zo) and outer doorway (east wall x = X)
    wx0, wx1, wy0, wy1 = 1.0, 4.5, 0.8, 2.6
    dz0, dz1, dy1 = 3.2, 4.2, 2.1
    # inner door in the partition z = 0, its gap under it
    ix0, ix1, iy1, gap = 3.5, 4.4, 2.1, 0.05
    g.mesh_node("floor", rect_y(0, X, Zi, Zo, 0.0), floor)
    g.mesh_node("ceiling", rect_y(0, X, Zi, Zo, Y), ceiling)
    walls = (rect_x(0, X, 0, Y, Zi) +                                   # inner room, north
             rect_z(Zi, Zo, 0, Y, 0.0) +                                # west (both rooms)
             rect_z(Zi, 0, 0, Y, X) +                                   # inner room, east
             rect_z(0, dz0, 0, Y, X) + rect_z(dz1, Zo, 0, Y, X) +       # outer room, east,
             rect_z(dz0, dz1, dy1, Y, X) +                              #   around the doorway
             wall_with_hole(0, X, 0, Y, Zo, wx0, wx1, wy0, wy1) +       # outer room, south
             rect_x(0, ix0, 0, Y, 0.0) + rect_x(ix1, X, 0, Y, 0.0) +    # partition around the
             rect_x(ix0, ix1, iy1, Y, 0.0))                             #   inner door
    g.mesh_node("walls", walls, wall)
    g.mesh_node("window", rect_x(wx0, wx1, wy0, wy1, Zo), glass, extras={"portal": True})
    # the open doorway's frame: jambs and head, 5 cm, in the wall plane x = X
    frame = (rect_z(dz0 - 0.05, dz0, 0, dy1, X) + rect_z(dz1, dz1 + 0.05, 0, dy1, X) +
             rect_z(dz0 - 0.05, dz1 + 0.05, dy1, dy1 + 0.05, X))
    g.mesh_node("door_frame", frame, wall, extras={"portal": "hull"})
    g.mesh_node("inner_door", rect_x(ix0, ix1, gap, iy1, 0.0), door)
    g.mesh_node("gap", rect_x(ix0, ix1, 0.0, gap, 0.0), opening)
    g.sun("sun", 30.0, 200.0, 60000.0)
    g.camera("camera", (5.4, 1.4, -3.0), (2.4, 0.3, -0.4), 55.0, 4.0 / 3.0)
    g.write(path, {"type": "cie", "cie_type": 12, "zenith_luminance": 3000.0,
                   "sun_altitude_deg": 30.0, "sun_azimuth_deg": 200.0})


def bay_window_scene(path):
    """scenes/bay_window.gltf — many portal planes: a 6 x 6 m room whose south side is a
    half-cylindrical bay window of 200 vertical glass facets (400 triangles, 200 planes,
    extras.portal = true), radius 3 m, 3 m high. It exists to measure how portal emission scales
    with the number of portal planes (table precompute, paths per second); same sun and sky as
    the inner room.
    """
    g = Gltf("fenestra scripts/make_scenes.py")
    wall = g.material("wall", (0.7, 0.7, 0.7))
    glass = g.material("glass", (1.0, 1.0, 1.0), transmission=0.9, ior=1.5)
    g.mesh_node("floor", rect_y(0, 6, 0, 6, 0.0), wall)
    g.mesh_node("ceiling", rect_y(0, 6, 0, 6, 3.0), wall)
    g.mesh_node("walls", rect_x(0, 6, 0, 3, 0.0) + rect_z(0, 6, 0, 3, 0.0) +
                rect_z(0, 6, 0, 3, 6.0), wall)
    facets, r, h = 200, 3.0, 3.0
    bay, bay_floor, bay_ceiling = [], [], []
    for k in range(facets):
        a0, a1 = math.pi * k / facets, math.pi * (k + 1) / facets
        x0, z0 = 3 - r * math.cos(a0), 6 + r * math.sin(a0)
        x1, z1 = 3 - r * math.cos(a1), 6 + r * math.sin(a1)
        bay += quad((x0, 0.0, z0), (x1, 0.0, z1), (x1, h, z1), (x0, h, z0))
        bay_floor.append(((3.0, 0.0, 6.0), (x0, 0.0, z0), (x1, 0.0, z1)))
        bay_ceiling.append(((3.0, h, 6.0), (x0, h, z0), (x1, h, z1)))
    # the bay has a floor and a ceiling: light enters only through the glass
    g.mesh_node("bay_floor", bay_floor, wall)
    g.mesh_node("bay_ceiling", bay_ceiling, wall)
    g.mesh_node("bay", bay, glass, extras={"portal": True})
    g.sun("sun", 30.0, 200.0, 60000.0)
    g.camera("camera", (1.0, 1.5, 1.0), (3.0, 0.5, 5.0), 60.0, 4.0 / 3.0)
    g.write(path, {"type": "cie", "cie_type": 12, "zenith_luminance": 3000.0,
                   "sun_altitude_deg": 30.0, "sun_azimuth_deg": 200.0})


def wall_with_holes(rect, u0, u1, v0, v1, holes):
    """A wall [u0, u1] x [v0, v1] (u along the wall, v = y) with rectangular openings
    holes = [(a0, a1, b0, b1), ...] (inside the wall, not overlapping), as rectangles made by
    rect(a0, a1, b0, b1): horizontal bands between the openings' edges, each cut around the
    openings that span it. rect is e.g. `lambda a0, a1, b0, b1: rect_x(a0, a1, b0, b1, z)`.
    """
    vs = sorted({v0, v1} | {b for h in holes for b in h[2:]})
    tris = []
    for b0, b1 in zip(vs, vs[1:]):
        a = u0
        for h0, h1, _, _ in sorted(h for h in holes if h[2] <= b0 and h[3] >= b1):
            if h0 > a:
                tris += rect(a, h0, b0, b1)
            a = h1
        if u1 > a:
            tris += rect(a, u1, b0, b1)
    return tris


def house_scene(path, ground_albedo):
    """scenes/house.gltf (ground_albedo 0.2) and scenes/house_snow.gltf (0.9) — after the paper's
    "House" (its Fig. 4-5, Table 2): a two-storey house with many windows, the camera in an
    upstairs room lit mostly indirectly.

    Footprint x in [0, 10], z in [0, 8] (south facade at z = 8), storeys 2.8 m, flat roof at
    5.6 m. Each floor has a south room (z in [4, 8], the whole width) and two north rooms
    (x in [0, 5] and [5, 10], z in [0, 4]); the partition z = 4 has two open 0.9 x 2.1 m doorways
    (x in [3.8, 4.7] into the north-west room, [6.2, 7.1] into the north-east one); the partition
    x = 5 has a doorway downstairs and none upstairs. Between the storeys: the ground floor's
    ceiling at 2.75 m and the upper floor at 2.8 m (two sheets, each with its own albedo); no stair.
    16 glazed windows (thin glass 0.9 / IOR 1.5, one node each, extras.portal = true), 1.4 m high
    with sills at 0.9 m above each floor: 3 per storey south (1.6 m wide), 2 per storey north
    (one per north room, 1.2 m), 2 per storey east (north-east and south room, 1.2 m), 1 per storey
    west (south room, 1.2 m). Names window_<facade>_<n>, ground floor first, then west to east
    (north and south facades) or north to south (east and west). No exterior door.
    A 40 x 40 m ground plane around the house. Sun at altitude 35 deg, azimuth 200 deg
    (south-south-west), 70 klux; CIE clear sky (type 12) for it, zenith luminance 3500 cd/m^2.
    The camera stands upstairs in the north-east corner of the north-west room, looking at its
    south-west corner: the west wall, the partition and the floor, lit through the doorway from
    the sunny south room and by its own north window (behind the camera, out of view); no sun
    reaches this room.
    """
    g = Gltf("fenestra scripts/make_scenes.py")
    X, Z, H = 10.0, 8.0, 2.8             # footprint x in [0, X], z in [0, Z]; storey height
    Zp, Xp = 4.0, 5.0                    # partitions z = Zp (south room | north rooms), x = Xp
    slab = 0.05                          # the ground floor's ceiling is this far below the floor
    sill, top = 0.9, 2.3                 # window sill and head above each floor
    door_h = 2.1
    floor = g.material("floor", (0.35, 0.3, 0.25))
    wall = g.material("wall", (0.7, 0.7, 0.7))
    ceiling = g.material("ceiling", (0.8, 0.8, 0.8))
    ground = g.material("ground", (ground_albedo,) * 3)
    glass = g.material("glass", (1.0, 1.0, 1.0), transmission=0.9, ior=1.5)
    storeys = (0.0, H)
    # windows per facade: (u0, u1) along the facade, on both storeys
    south = [(1.0, 2.6), (4.2, 5.8), (7.4, 9.0)]        # x
    north = [(1.9, 3.1), (6.9, 8.1)]                    # x: north-west, north-east room
    east = [(1.4, 2.6), (5.4, 6.6)]                     # z: north-east room, south room
    west = [(5.4, 6.6)]                                 # z: south room

    def holes(spans):
        return [(u0, u1, y + sill, y + top) for y in storeys for u0, u1 in spans]

    g.mesh_node("floors", rect_y(0, X, 0, Z, 0.0) + rect_y(0, X, 0, Z, H), floor)
    g.mesh_node("ceilings", rect_y(0, X, 0, Z, H - slab) + rect_y(0, X, 0, Z, 2 * H), ceiling)
    g.mesh_node("facades",
                wall_with_holes(lambda a0, a1, b0, b1: rect_x(a0, a1, b0, b1, Z),
                                0, X, 0, 2 * H, holes(south)) +
                wall_with_holes(lambda a0, a1, b0, b1: rect_x(a0, a1, b0, b1, 0.0),
                                0, X, 0, 2 * H, holes(north)) +
                wall_with_holes(lambda a0, a1, b0, b1: rect_z(a0, a1, b0, b1, X),
                                0, Z, 0, 2 * H, holes(east)) +
                wall_with_holes(lambda a0, a1, b0, b1: rect_z(a0, a1, b0, b1, 0.0),
                                0, Z, 0, 2 * H, holes(west)), wall)
    partitions = []
    for y0, y1 in ((0.0, H - slab), (H, 2 * H)):
        partitions += wall_with_holes(lambda a0, a1, b0, b1: rect_x(a0, a1, b0, b1, Zp),
                                      0, X, y0, y1,
                                      [(3.8, 4.7, y0, y0 + door_h), (6.2, 7.1, y0, y0 + door_h)])
    partitions += wall_with_holes(lambda a0, a1, b0, b1: rect_z(a0, a1, b0, b1, Xp),
                                  0, Zp, 0, H - slab, [(1.5, 2.4, 0.0, door_h)])
    partitions += rect_z(0, Zp, H, 2 * H, Xp)
    g.mesh_node("partitions", partitions, wall)
    for side, spans, pane in (
            ("south", south, lambda u0, u1, b0, b1: rect_x(u0, u1, b0, b1, Z)),
            ("north", north, lambda u0, u1, b0, b1: rect_x(u0, u1, b0, b1, 0.0)),
            ("east", east, lambda u0, u1, b0, b1: rect_z(u0, u1, b0, b1, X)),
            ("west", west, lambda u0, u1, b0, b1: rect_z(u0, u1, b0, b1, 0.0))):
        for n, (u0, u1, b0, b1) in enumerate(holes(spans), 1):
            g.mesh_node("window_%s_%d" % (side, n), pane(u0, u1, b0, b1), glass,
                        extras={"portal": True})
    g.mesh_node("ground", rect_y(-15.0, 25.0, -16.0, 24.0, -0.02), ground)
    g.sun("sun", 35.0, 200.0, 70000.0)
    g.camera("camera", (4.6, H + 1.6, 0.4), (0.0, H + 0.7, 3.6), 60.0, 4.0 / 3.0)
    g.write(path, {"type": "cie", "cie_type": 12, "zenith_luminance": 3500.0,
                   "sun_altitude_deg": 35.0, "sun_azimuth_deg": 200.0})


def courtyard_scene(path):
    """scenes/courtyard.gltf — light reflected from outside: a 5 x 4 x 2.8 m room whose only
    window (2 x 1.5 m, sill 0.9 m, thin glass 0.9 / IOR 1.5, extras.portal = true) faces north
    across a courtyard onto the sunlit south wall of a neighbouring building.

    Room x in [0, 5], z in [0, 4], window in the north wall z = 0. The neighbour is its south wall
    alone (node `neighbour`): z = -6, x in [-5, 10], 9 m tall, albedo 0.6, in full sun; it hides
    the sky below 51 deg altitude from the window. The courtyard floor and the ground around are one
    plane of albedo 0.3, x in [-10, 15], z in [-6, 10]. Sun due south at altitude 40 deg, 70 klux
    (it never enters the window); CIE clear sky (type 12) for it, zenith luminance 3500 cd/m^2.
    The camera stands in the north-west corner beside the window, looking at the south-east
    corner: the floor and the south and east walls, lit mostly by the neighbour's wall.
    """
    g = Gltf("fenestra scripts/make_scenes.py")
    W, D, H = 5.0, 4.0, 2.8
    wx0, wx1, wy0, wy1 = 1.5, 3.5, 0.9, 2.4
    floor = g.material("floor", (0.35, 0.3, 0.25))
    wall = g.material("wall", (0.7, 0.7, 0.7))
    ceiling = g.material("ceiling", (0.8, 0.8, 0.8))
    ground = g.material("ground", (0.3, 0.3, 0.3))
    facade = g.material("neighbour", (0.6, 0.6, 0.6))
    glass = g.material("glass", (1.0, 1.0, 1.0), transmission=0.9, ior=1.5)
    g.mesh_node("floor", rect_y(0, W, 0, D, 0.0), floor)
    g.mesh_node("ceiling", rect_y(0, W, 0, D, H), ceiling)
    g.mesh_node("north_wall", wall_with_hole(0, W, 0, H, 0.0, wx0, wx1, wy0, wy1), wall)
    g.mesh_node("walls", rect_x(0, W, 0, H, D) + rect_z(0, D, 0, H, 0.0) +
                rect_z(0, D, 0, H, W), wall)
    g.mesh_node("window", rect_x(wx0, wx1, wy0, wy1, 0.0), glass, extras={"portal": True})
    g.mesh_node("neighbour", rect_x(-5.0, 10.0, -0.02, 9.0, -6.0), facade)
    g.mesh_node("ground", rect_y(-10.0, 15.0, -6.0, 10.0, -0.02), ground)
    g.sun("sun", 40.0, 180.0, 70000.0)
    g.camera("camera", (0.4, 1.6, 0.4), (3.6, 0.5, 3.4), 60.0, 4.0 / 3.0)
    g.write(path, {"type": "cie", "cie_type": 12, "zenith_luminance": 3500.0,
                   "sun_altitude_deg": 40.0, "sun_azimuth_deg": 180.0})


def slit_scene(path):
    """scenes/slit.gltf — a rare light path: a closed 4 x 4 x 2.8 m room lit only through an open
    slit, 2 cm wide and 1 m tall, in its south wall (node `slit`, no glass, extras.portal = true).

    Room x in [0, 4], z in [0, 4], slit x in [1.99, 2.01], y in [0.8, 1.8] in the wall z = 4. No
    ground and nothing else outside: every path that lights the room passes the slit, which takes
    about 1/1000 of the silhouette of the scene's box that uniform emission draws its lines through. The sun due south at altitude 30 deg, 70 klux, draws
    a narrow stripe on the floor (z from about 0.9 to 2.6); a CIE clear sky (type 12) for it,
    zenith luminance 3500 cd/m^2. Floor (0.35, 0.3, 0.25), walls 0.7, ceiling 0.8. The camera in
    the north-west corner looks at the stripe.
    """
    g = Gltf("fenestra scripts/make_scenes.py")
    W, D, H = 4.0, 4.0, 2.8
    sx0, sx1, sy0, sy1 = 1.99, 2.01, 0.8, 1.8
    floor = g.material("floor", (0.35, 0.3, 0.25))
    wall = g.material("wall", (0.7, 0.7, 0.7))
    ceiling = g.material("ceiling", (0.8, 0.8, 0.8))
    g.mesh_node("floor", rect_y(0, W, 0, D, 0.0), floor)
    g.mesh_node("ceiling", rect_y(0, W, 0, D, H), ceiling)
    g.mesh_node("walls", rect_x(0, W, 0, H, 0.0) + rect_z(0, D, 0, H, 0.0) + rect_z(0, D, 0, H, W), wall)
    g.mesh_node("south_wall", wall_with_hole(0, W, 0, H, D, sx0, sx1, sy0, sy1), wall)
    # The opening itself, as a portal: an invisible node would need a material; an open slit is
    # marked by its frame's hull instead (4 thin strips around it, in the wall's plane).
    g.mesh_node("slit", frame_x(sx0, sx1, sy0, sy1, D, 0.005), wall, extras={"portal": "hull"})
    g.sun("sun", 30.0, 180.0, 70000.0)
    g.camera("camera", (0.4, 1.6, 0.4), (2.2, 0.0, 2.2), 60.0, 4.0 / 3.0)
    g.write(path, {"type": "cie", "cie_type": 12, "zenith_luminance": 3500.0,
                   "sun_altitude_deg": 30.0, "sun_azimuth_deg": 180.0})


def main():
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes")
    os.makedirs(root, exist_ok=True)
    room_scene(os.path.join(root, "room.gltf"))
    inner_room_scene(os.path.join(root, "inner_room.gltf"))
    bay_window_scene(os.path.join(root, "bay_window.gltf"))
    house_scene(os.path.join(root, "house.gltf"), 0.2)
    house_scene(os.path.join(root, "house_snow.gltf"), 0.9)
    courtyard_scene(os.path.join(root, "courtyard.gltf"))
    slit_scene(os.path.join(root, "slit.gltf"))


if __name__ == "__main__":
    main()
