#!/usr/bin/env python3
"""Writes assets/textured_tile.glb: a gently curved, textured SSS tile (assets/README.md).

A 50 x 50 mm tile, 6 mm thick, curved along x (a slice of a cylindrical shell of outer
radius 100 mm, so its corners drop 3.2 mm below its crest). Its top carries a 4 x 4
soft checker of glazed squares separated by grout grooves: a base-colour texture and a
matching normal map (both 128 x 128 PNG, embedded), with UVs and tangents. The
material scatters underneath (materials[0].extras.sss, an artist colour and mean free
path). A perspective camera and a KHR_lights_punctual directional key light are in the
file, so it renders as it is.

Python 3 standard library only. The output is deterministic: the same script gives the
same bytes (PNG pixels are deflated with zlib at level 9).

    python3 assets/make_textured_tile.py [OUT.glb]     # default: next to this script
"""

import json
import math
import os
import struct
import sys
import zlib

# --- geometry (metres; glTF scenes are in metres, DESIGN.md §3) -------------------------

WIDTH = 0.050       # along x, as a chord
DEPTH = 0.050       # along z
THICKNESS = 0.006
RADIUS = 0.100      # outer (top) radius of the shell; its axis runs along z
SEGMENTS = 16       # around the curve
ROWS = 2            # along z
HALF_ANGLE = math.asin(0.5 * WIDTH / RADIUS)
ARC = 2.0 * HALF_ANGLE * RADIUS   # the top's length along u, for the normal map

TEXTURE_SIZE = 128
CELLS = 4                  # checker squares per side
GROOVE_HALF_WIDTH = 0.025  # in uv (of a 0.25 cell): about 1.25 mm on the tile
GROOVE_DEPTH = 0.0003      # 0.3 mm

SSS = {"color": [0.82, 0.66, 0.56], "mfp": [1.6, 1.0, 0.8], "gaussians": 6}


def normalize(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


class MeshBuilder:
    """Flat arrays of vertex attributes and uint16 triangle indices."""

    def __init__(self):
        self.pos, self.nrm, self.uv, self.tan, self.idx = [], [], [], [], []

    def grid(self, point, normal, uv, nu, nv):
        """An (nu+1) x (nv+1) vertex grid over (s, t) in [0,1]^2, two triangles a cell.

        point(s, t) -> position, normal(s, t) -> unit outward normal, uv(s, t) -> [u, v].
        finish() orients the triangles and computes the tangents.
        """
        base = len(self.pos)
        for j in range(nv + 1):
            for i in range(nu + 1):
                s, t = i / nu, j / nv
                self.pos.append(point(s, t))
                self.nrm.append(normal(s, t))
                self.uv.append(uv(s, t))
        for j in range(nv):
            for i in range(nu):
                a = base + j * (nu + 1) + i
                b, c, d = a + 1, a + nu + 2, a + nu + 1
                self.idx += [a, b, c, a, c, d]

    def finish(self):
        """Makes every triangle CCW seen from outside (its face normal agrees with its
        vertex normals), and gives every vertex the glTF tangent: xyz the direction of
        increasing u (dP/du, summed over the vertex's triangles, made orthogonal to the
        normal), w = +1 where the bitangent cross(normal, tangent) points toward
        decreasing v (up in the image, as the normal map's +Y), else -1."""
        def sub(p, q):
            return [p[i] - q[i] for i in range(3)]

        def dot(p, q):
            return sum(p[i] * q[i] for i in range(3))

        du_sum = [[0.0] * 3 for _ in self.pos]
        dv_sum = [[0.0] * 3 for _ in self.pos]
        for k in range(0, len(self.idx), 3):
            a, b, c = self.idx[k:k + 3]
            e1, e2 = sub(self.pos[b], self.pos[a]), sub(self.pos[c], self.pos[a])
            n = [self.nrm[a][i] + self.nrm[b][i] + self.nrm[c][i] for i in range(3)]
            if dot(cross(e1, e2), n) < 0.0:
                self.idx[k + 1], self.idx[k + 2] = c, b
            du1, dv1 = self.uv[b][0] - self.uv[a][0], self.uv[b][1] - self.uv[a][1]
            du2, dv2 = self.uv[c][0] - self.uv[a][0], self.uv[c][1] - self.uv[a][1]
            det = du1 * dv2 - du2 * dv1
            dpdu = [(dv2 * e1[i] - dv1 * e2[i]) / det for i in range(3)]
            dpdv = [(du1 * e2[i] - du2 * e1[i]) / det for i in range(3)]
            for v in (a, b, c):
                du_sum[v] = [du_sum[v][i] + dpdu[i] for i in range(3)]
                dv_sum[v] = [dv_sum[v][i] + dpdv[i] for i in range(3)]
        self.tan = []
        for v, n in enumerate(self.nrm):
            t = normalize([du_sum[v][i] - n[i] * dot(n, du_sum[v]) for i in range(3)])
            w = 1.0 if dot(cross(n, t), dv_sum[v]) < 0.0 else -1.0
            self.tan.append(t + [w])


def shell_point(radius, angle, z):
    # The cylinder's axis is the line x = 0, y = -RADIUS; the crest of the top is y = 0.
    return [radius * math.sin(angle), radius * math.cos(angle) - RADIUS, z]


def build_tile():
    """The tile as one closed mesh, every face its own grid (sharp edges between faces).

    The top is mapped once by the texture: u along the curve (x), v along z. The sides
    carry the texture at the same scale, as if the pattern folded over the edges: each
    side mirrors the top's uv across the edge it shares with the top.
    """
    m = MeshBuilder()
    depth_in_v = THICKNESS / DEPTH   # the thickness in v (or u) units of the top's mapping
    depth_in_u = THICKNESS / ARC

    def angle(s):
        return -HALF_ANGLE + 2.0 * HALF_ANGLE * s

    def z_of(t):
        return -0.5 * DEPTH + DEPTH * t

    def radial(s):
        return [math.sin(angle(s)), math.cos(angle(s)), 0.0]

    def along(s):  # the direction of increasing angle
        return [math.cos(angle(s)), -math.sin(angle(s)), 0.0]

    # Top and bottom: (s, t) = (u, v); the bottom on the inner radius, facing down.
    m.grid(lambda s, t: shell_point(RADIUS, angle(s), z_of(t)),
           lambda s, t: radial(s), lambda s, t: [s, t], SEGMENTS, ROWS)
    m.grid(lambda s, t: shell_point(RADIUS - THICKNESS, angle(s), z_of(t)),
           lambda s, t: [-c for c in radial(s)], lambda s, t: [s, t], SEGMENTS, ROWS)
    # Front (z = +DEPTH/2, v = 1 on the top) and back (z = -DEPTH/2, v = 0): annular
    # sectors, s along the curve, t down through the thickness.
    for sign, v_edge in ((1.0, 1.0), (-1.0, 0.0)):
        z = 0.5 * DEPTH * sign
        m.grid(lambda s, t, z=z: shell_point(RADIUS - THICKNESS * t, angle(s), z),
               lambda s, t, sign=sign: [0.0, 0.0, sign],
               lambda s, t, sign=sign, v_edge=v_edge: [s, v_edge - sign * depth_in_v * t],
               SEGMENTS, 1)
    # The straight ends (s = 1, u = 1, outward +along; s = 0, u = 0, outward -along):
    # s along z, t down through the thickness.
    for s_edge, sign in ((1.0, 1.0), (0.0, -1.0)):
        a = angle(s_edge)
        m.grid(lambda s, t, a=a: shell_point(RADIUS - THICKNESS * t, a, z_of(s)),
               lambda s, t, s_edge=s_edge, sign=sign: [sign * c for c in along(s_edge)],
               lambda s, t, s_edge=s_edge, sign=sign: [s_edge - sign * depth_in_u * t, s],
               ROWS, 1)
    m.finish()
    return m


# --- textures ---------------------------------------------------------------------------

def smoothstep(e0, e1, x):
    t = min(max((x - e0) / (e1 - e0), 0.0), 1.0)
    return t * t * (3.0 - 2.0 * t)


def groove_distance(x):
    """Distance (in uv) from x to the nearest grid line of the checker."""
    f = x * CELLS
    return abs(f - round(f)) / CELLS


def height(u, v):
    """Relief of the top, metres: 0 on the squares, -GROOVE_DEPTH along the grout."""
    d = min(groove_distance(u), groove_distance(v))
    return -GROOVE_DEPTH * (1.0 - smoothstep(0.0, GROOVE_HALF_WIDTH, d))


def srgb_byte(linear):
    c = min(max(linear, 0.0), 1.0)
    s = 12.92 * c if c <= 0.0031308 else 1.055 * c ** (1.0 / 2.4) - 0.055
    return int(round(255.0 * s))


def base_color_pixel(u, v):
    # Linear colours: warm ivory and dusty rose squares, pale grey grout.
    ivory, rose, grout = (0.80, 0.70, 0.55), (0.62, 0.32, 0.30), (0.55, 0.53, 0.50)
    cell = (int(math.floor(u * CELLS)) + int(math.floor(v * CELLS))) % 2
    square = ivory if cell == 0 else rose
    # A soft shading inside each square: lighter toward its centre, so the checker is soft.
    fu, fv = (u * CELLS) % 1.0 - 0.5, (v * CELLS) % 1.0 - 0.5
    shade = 1.0 - 0.25 * (fu * fu + fv * fv)
    d = min(groove_distance(u), groove_distance(v))
    g = 1.0 - smoothstep(0.4 * GROOVE_HALF_WIDTH, 1.2 * GROOVE_HALF_WIDTH, d)
    rgb = [(1.0 - g) * square[i] * shade + g * grout[i] for i in range(3)]
    return [srgb_byte(c) for c in rgb]


def normal_pixel(u, v):
    # Tangent space: x along +u (the tangent), y along the bitangent, which points toward
    # decreasing v (glTF), z out of the surface. Gradients by central differences, in
    # metres of surface: u spans the top's arc length, v its depth.
    e = 0.25 / TEXTURE_SIZE
    dh_du = (height(u + e, v) - height(u - e, v)) / (2.0 * e * ARC)
    dh_dv = (height(u, v + e) - height(u, v - e)) / (2.0 * e * DEPTH)
    n = normalize([-dh_du, dh_dv, 1.0])
    return [int(round(255.0 * (0.5 * c + 0.5))) for c in n]


def png_rgb(size, pixel):
    rows = bytearray()
    for j in range(size):
        rows.append(0)  # filter: none
        for i in range(size):
            rows += bytes(pixel((i + 0.5) / size, (j + 0.5) / size))

    def chunk(kind, data):
        body = kind + data
        crc = zlib.crc32(body) & 0xFFFFFFFF
        return struct.pack(">I", len(data)) + body + struct.pack(">I", crc)

    ihdr = struct.pack(">IIBBBBB", size, size, 8, 2, 0, 0, 0)  # 8-bit RGB
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) +
            chunk(b"IDAT", zlib.compress(bytes(rows), 9)) + chunk(b"IEND", b""))


# --- camera and light -------------------------------------------------------------------

def look_rotation(forward, up=(0.0, 1.0, 0.0)):
    """The unit quaternion [x, y, z, w] turning local -Z to `forward` with +Y near `up`."""
    back = normalize([-c for c in forward])
    right = normalize(cross(list(up), back))
    true_up = cross(back, right)
    m = [[right[0], true_up[0], back[0]],
         [right[1], true_up[1], back[1]],
         [right[2], true_up[2], back[2]]]
    tr = m[0][0] + m[1][1] + m[2][2]
    if tr > 0.0:
        s = 2.0 * math.sqrt(tr + 1.0)
        q = [(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, 0.25 * s]
    elif m[0][0] > m[1][1] and m[0][0] > m[2][2]:
        s = 2.0 * math.sqrt(1.0 + m[0][0] - m[1][1] - m[2][2])
        q = [0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s, (m[2][1] - m[1][2]) / s]
    elif m[1][1] > m[2][2]:
        s = 2.0 * math.sqrt(1.0 + m[1][1] - m[0][0] - m[2][2])
        q = [(m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s, (m[0][2] - m[2][0]) / s]
    else:
        s = 2.0 * math.sqrt(1.0 + m[2][2] - m[0][0] - m[1][1])
        q = [(m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s, (m[1][0] - m[0][1]) / s]
    return normalize(q)


TARGET = [0.0, -0.006, 0.003]              # the tile's middle, below the crest, toward the front
CAMERA_DIRECTION = [-0.35, -0.75, -0.9]     # from the front right, above
CAMERA_DISTANCE = 0.115
YFOV = 0.6
KEY_DIRECTION = [0.75, -0.5, -0.35]         # the key light travels: from the left, above
KEY_IRRADIANCE = 3.0


# --- the GLB ----------------------------------------------------------------------------

def build_glb():
    m = build_tile()
    blob = bytearray()
    views, accessors = [], []

    def add_view(data, target=None):
        while len(blob) % 4:
            blob.append(0)
        view = {"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)}
        if target:
            view["target"] = target
        blob.extend(data)
        views.append(view)
        return len(views) - 1

    def add_float_accessor(rows, kind, with_bounds=False):
        flat = [float(c) for row in rows for c in row]
        view = add_view(struct.pack("<%df" % len(flat), *flat), 34962)
        acc = {"bufferView": view, "componentType": 5126, "count": len(rows), "type": kind}
        if with_bounds:
            # The bounds of the float32 values as stored, not of the doubles.
            fmt = "<%df" % len(rows[0])
            packed = [struct.unpack(fmt, struct.pack(fmt, *r)) for r in rows]
            acc["min"] = [min(r[i] for r in packed) for i in range(len(rows[0]))]
            acc["max"] = [max(r[i] for r in packed) for i in range(len(rows[0]))]
        accessors.append(acc)
        return len(accessors) - 1

    attributes = {
        "POSITION": add_float_accessor(m.pos, "VEC3", with_bounds=True),
        "NORMAL": add_float_accessor(m.nrm, "VEC3"),
        "TEXCOORD_0": add_float_accessor(m.uv, "VEC2"),
        "TANGENT": add_float_accessor(m.tan, "VEC4"),
    }
    assert len(m.pos) < 65536
    index_view = add_view(struct.pack("<%dH" % len(m.idx), *m.idx), 34963)
    accessors.append({"bufferView": index_view, "componentType": 5123, "count": len(m.idx),
                      "type": "SCALAR"})
    indices = len(accessors) - 1
    base_png = png_rgb(TEXTURE_SIZE, base_color_pixel)
    normal_png = png_rgb(TEXTURE_SIZE, normal_pixel)
    base_view = add_view(base_png)
    normal_view = add_view(normal_png)
    while len(blob) % 4:
        blob.append(0)

    target = TARGET
    forward = normalize(CAMERA_DIRECTION)
    eye = [target[i] - CAMERA_DISTANCE * forward[i] for i in range(3)]
    doc = {
        "asset": {
            "version": "2.0",
            "generator": "assets/make_textured_tile.py",
            "copyright": "CC0 1.0: the sss project's own work, dedicated to the public domain",
        },
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "key", "type": "directional", "color": [1.0, 1.0, 1.0],
             "intensity": KEY_IRRADIANCE}]}},
        "scene": 0,
        "scenes": [{"name": "textured tile", "nodes": [0, 1, 2]}],
        "nodes": [
            {"name": "tile", "mesh": 0},
            {"name": "camera", "camera": 0, "translation": eye, "rotation": look_rotation(forward)},
            {"name": "key light", "rotation": look_rotation(normalize(KEY_DIRECTION)),
             "extensions": {"KHR_lights_punctual": {"light": 0}}},
        ],
        "cameras": [{"name": "camera", "type": "perspective",
                     "perspective": {"yfov": YFOV, "znear": 0.01, "zfar": 1.0}}],
        "meshes": [{"name": "tile", "primitives": [
            {"attributes": attributes, "indices": indices, "material": 0, "mode": 4}]}],
        "materials": [{
            "name": "glazed tile",
            "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0],
                                     "baseColorTexture": {"index": 0},
                                     "metallicFactor": 0.0, "roughnessFactor": 0.45},
            "normalTexture": {"index": 1, "scale": 1.0},
            "extras": {"sss": SSS},
        }],
        "textures": [{"name": "base colour", "sampler": 0, "source": 0},
                     {"name": "normal", "sampler": 0, "source": 1}],
        "samplers": [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}],
        "images": [{"name": "tile_base_color", "bufferView": base_view, "mimeType": "image/png"},
                   {"name": "tile_normal", "bufferView": normal_view, "mimeType": "image/png"}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob)}],
    }
    text = json.dumps(doc, separators=(",", ":"), sort_keys=True).encode("utf-8")
    text += b" " * (-len(text) % 4)
    total = 12 + 8 + len(text) + 8 + len(blob)
    return (struct.pack("<III", 0x46546C67, 2, total) +
            struct.pack("<II", len(text), 0x4E4F534A) + text +
            struct.pack("<II", len(blob), 0x004E4942) + bytes(blob))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "textured_tile.glb")
    data = build_glb()
    with open(out, "wb") as f:
        f.write(data)
    print("%s: %d bytes" % (out, len(data)))


if __name__ == "__main__":
    main()
