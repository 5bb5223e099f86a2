#!/usr/bin/env python3
"""Writes the seed corpora fuzz/corpus/<target>/ (Python 3 standard library only).

Each seed is a small valid input that reaches deep into its parser, so that libFuzzer
starts from accepted files rather than from bytes the first check refuses. Rejected
inputs for the glTF loader come from tests/data/bad/ (scripts/fuzz.sh passes it as a
second seed folder). Run from anywhere: python3 fuzz/make_corpus.py
Formats: glTF 2.0 (Khronos spec §3, §4.4 GLB), PNG (RFC 2083 / ISO 15948), OpenEXR
(openexr.com "OpenEXR File Layout": magic, version, header attributes, offset table,
scanline blocks; ZIPS = zlib of the byte-interleaved, delta-predicted scanline).
"""
import base64
import json
import os
import shutil
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
CORPUS = os.path.join(HERE, "corpus")


def put(target, name, data):
    if isinstance(data, str):
        data = data.encode()
    with open(os.path.join(CORPUS, target, name), "wb") as f:
        f.write(data)


# ---------------------------------------------------------------- PNG
def png_chunk(kind, payload):
    c = struct.pack(">I", len(payload)) + kind + payload
    return c + struct.pack(">I", zlib.crc32(kind + payload) & 0xFFFFFFFF)


def png(width, height, bit_depth, colour_type, rows, interlace=0, extra=b""):
    """rows: the raw scanlines (filter byte 0 is prepended here)."""
    ihdr = struct.pack(">IIBBBBB", width, height, bit_depth, colour_type, 0, 0, interlace)
    raw = b"".join(b"\x00" + r for r in rows)
    return (b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", ihdr) + extra +
            png_chunk(b"IDAT", zlib.compress(raw, 9)) + png_chunk(b"IEND", b""))


def pngs():
    put("image", "rgba8_2x2.png", png(2, 2, 8, 6, [bytes([255, 0, 0, 255, 0, 255, 0, 128]),
                                                   bytes([0, 0, 255, 0, 255, 255, 255, 255])]))
    put("image", "rgb8_3x1.png", png(3, 1, 8, 2, [bytes([10, 20, 30, 40, 50, 60, 70, 80, 90])]))
    put("image", "gray8_2x2.png", png(2, 2, 8, 0, [bytes([0, 255]), bytes([128, 64])]))
    put("image", "gray_alpha8_1x2.png", png(1, 2, 8, 4, [bytes([200, 100]), bytes([50, 25])]))
    put("image", "rgb16_1x1.png", png(1, 1, 16, 2, [bytes([0x12, 0x34, 0x56, 0x78, 0x9A, 0xBC])]))
    plte = png_chunk(b"PLTE", bytes([255, 0, 0, 0, 255, 0, 0, 0, 255])) + png_chunk(b"tRNS", bytes([255, 128]))
    put("image", "palette4_4x1.png", png(4, 1, 4, 3, [bytes([0x01, 0x20])], extra=plte))
    # Adam7: 3x3, 8-bit gray; the passes' scanlines in order (RFC 2083 §8.2)
    passes = [[b"\x01"], [], [], [b"\x03"], [b"\x07\x09"], [b"\x02", b"\x08"], [b"\x04\x05\x06"]]
    ihdr = struct.pack(">IIBBBBB", 3, 3, 8, 0, 0, 0, 1)
    raw = b"".join(b"\x00" + r for p in passes for r in p)
    put("image", "gray8_3x3_adam7.png", b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", ihdr) +
        png_chunk(b"IDAT", zlib.compress(raw)) + png_chunk(b"IEND", b""))


# ---------------------------------------------------------------- EXR
def exr_attr(name, kind, value):
    return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value


def exr(width, height, channels, pixel_type, compression, values):
    """channels: names (written sorted, as the format requires); values(x, y, c) -> float."""
    channels = sorted(channels)
    chlist = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", pixel_type, 0, 1, 1)
                      for c in channels) + b"\0"
    box = struct.pack("<iiii", 0, 0, width - 1, height - 1)
    header = (exr_attr("channels", "chlist", chlist) +
              exr_attr("compression", "compression", bytes([compression])) +
              exr_attr("dataWindow", "box2i", box) + exr_attr("displayWindow", "box2i", box) +
              exr_attr("lineOrder", "lineOrder", b"\0") +
              exr_attr("pixelAspectRatio", "float", struct.pack("<f", 1.0)) +
              exr_attr("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0)) +
              exr_attr("screenWindowWidth", "float", struct.pack("<f", 1.0)) + b"\0")
    start = 8 + len(header) + 8 * height  # one scanline per block (NONE and ZIPS)
    blocks = []
    for y in range(height):
        raw = b""
        for ci, _ in enumerate(channels):
            for x in range(width):
                v = values(x, y, ci)
                raw += struct.pack("<e", v) if pixel_type == 1 else struct.pack("<f", v)
        if compression == 2:  # ZIPS: interleave the bytes, then predict, then zlib
            t = raw[0::2] + raw[1::2]
            p = bytes([t[0]] + [(t[i] - t[i - 1] + 128) & 255 for i in range(1, len(t))])
            z = zlib.compress(p, 9)
            if len(z) < len(raw):  # a block that does not shrink is stored raw
                raw = z
        blocks.append(struct.pack("<ii", y, len(raw)) + raw)
    offsets, pos = b"", start
    for b in blocks:
        offsets += struct.pack("<Q", pos)
        pos += len(b)
    return b"\x76\x2f\x31\x01" + struct.pack("<I", 2) + header + offsets + b"".join(blocks)


def exrs():
    grad = lambda x, y, c: 0.25 * x + 0.5 * y + 0.125 * c
    put("image", "rgb_half_none_2x2.exr", exr(2, 2, "RGB", 1, 0, grad))
    put("image", "rgba_float_none_2x1.exr", exr(2, 1, "RGBA", 2, 0, grad))
    put("image", "rgb_half_zips_8x2.exr", exr(8, 2, "RGB", 1, 2, lambda x, y, c: 1.0))
    put("image", "y_float_none_1x1.exr", exr(1, 1, "Y", 2, 0, grad))


# ---------------------------------------------------------------- glTF
def triangle_gltf(glb=False, mode=4, indexed=True, sss=None, textured=False, quantized=False):
    if quantized:  # KHR_mesh_quantization (+ KHR_texture_transform on the textures), 36/36/24 bytes
        pos = struct.pack("<12h", 0, 0, 0, 0, 1000, 0, 0, 0, 0, 1000, 0, 0) + b"\0" * 12
        nrm = struct.pack("<12b", 0, 0, 127, 0, 0, 0, 127, 0, 0, 0, 127, 0) + b"\0" * 24
        uv = struct.pack("<6H", 0, 0, 65535, 0, 0, 65535) + b"\0" * 12
    else:
        pos = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
        nrm = struct.pack("<9f", 0, 0, 1, 0, 0, 1, 0, 0, 1)
        uv = struct.pack("<6f", 0, 0, 1, 0, 0, 1)
    idx = struct.pack("<3H", 0, 1, 2) + b"\0\0"
    binary = pos + nrm + uv + (idx if indexed else b"")
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
             {"buffer": 0, "byteOffset": 36, "byteLength": 36},
             {"buffer": 0, "byteOffset": 72, "byteLength": 24}]
    acc = [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
            "min": [0, 0, 0], "max": [1, 1, 0]},
           {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
           {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"}]
    if quantized:
        views[0]["byteStride"] = 8
        views[1]["byteStride"] = 4
        acc[0] = {"bufferView": 0, "componentType": 5122, "count": 3, "type": "VEC3",
                  "min": [0, 0, 0], "max": [1000, 1000, 0]}
        acc[1] = {"bufferView": 1, "componentType": 5120, "normalized": True, "count": 3, "type": "VEC3"}
        acc[2] = {"bufferView": 2, "componentType": 5123, "normalized": True, "count": 3, "type": "VEC2"}
    prim = {"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "material": 0, "mode": mode}
    if indexed:
        views.append({"buffer": 0, "byteOffset": 96, "byteLength": 6, "target": 34963})
        acc.append({"bufferView": 3, "componentType": 5123, "count": 3, "type": "SCALAR"})
        prim["indices"] = 3
    material = {"name": "m", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.6, 0.5, 1],
                                                      "metallicFactor": 0, "roughnessFactor": 0.5},
                "extras": {"sss": sss if sss is not None else {"preset": "skin1"}}}
    doc = {"asset": {"version": "2.0", "generator": "fuzz/make_corpus.py"},
           "extensionsUsed": ["KHR_lights_punctual"],
           "extensions": {"KHR_lights_punctual": {"lights": [
               {"type": "directional", "color": [1, 1, 1], "intensity": 2},
               {"type": "spot", "intensity": 5, "spot": {"innerConeAngle": 0.1, "outerConeAngle": 0.5}}]}},
           "scene": 0, "scenes": [{"nodes": [0, 3]}],
           "nodes": [{"name": "root", "children": [1, 2], "translation": [0, 0, -1],
                      "rotation": [0, 0.7071068, 0, 0.7071068], "scale": [2, 2, 2]},
                     {"mesh": 0},
                     {"camera": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 3, 1]},
                     {"extensions": {"KHR_lights_punctual": {"light": 0}}, "rotation": [0.38, 0, 0, 0.92]}],
           "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.01, "zfar": 100}}],
           "meshes": [{"name": "tri", "primitives": [prim]}],
           "materials": [material],
           "accessors": acc, "bufferViews": views}
    if textured:
        tex_png = png(2, 2, 8, 6, [bytes([255, 0, 0, 255, 0, 255, 0, 255]),
                                   bytes([0, 0, 255, 255, 255, 255, 255, 255])])
        doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(tex_png).decode()}]
        doc["samplers"] = [{"magFilter": 9728, "minFilter": 9729, "wrapS": 33071, "wrapT": 33648}]
        doc["textures"] = [{"source": 0, "sampler": 0}]
        material["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
        material["normalTexture"] = {"index": 0, "scale": 1}
    if quantized:
        doc["extensionsUsed"] += ["KHR_mesh_quantization", "KHR_texture_transform"]
        doc["extensionsRequired"] = ["KHR_mesh_quantization"]
        doc["nodes"][1]["scale"] = [0.001, 0.001, 0.001]
        tf = {"KHR_texture_transform": {"offset": [0.25, 0], "rotation": 0.3, "scale": [2, 2]}}
        if textured:
            material["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = tf
            material["normalTexture"]["extensions"] = tf
    if glb:
        doc["buffers"] = [{"byteLength": len(binary)}]
        text = json.dumps(doc, separators=(",", ":")).encode()
        text += b" " * (-len(text) % 4)
        binary += b"\0" * (-len(binary) % 4)
        body = (struct.pack("<I4s", len(text), b"JSON") + text +
                struct.pack("<I4s", len(binary), b"BIN\0") + binary)
        return b"glTF" + struct.pack("<II", 2, 12 + len(body)) + body
    doc["buffers"] = [{"byteLength": len(binary),
                       "uri": "data:application/octet-stream;base64," + base64.b64encode(binary).decode()}]
    return json.dumps(doc, indent=1)


SSS_BLOCKS = {
    "preset.json": {"preset": "skin1"},
    "coefficients.json": {"sigma_a": [0.032, 0.17, 0.48], "sigma_s": [0.74, 0.88, 1.01],
                          "g": 0.2, "eta": [1.3, 1.3, 1.3], "model": "multipole", "thickness": 2},
    "artist.json": {"color": [0.8, 0.5, 0.3], "mfp": [1.0, 0.5, 0.25], "g": 0, "eta": 1.4,
                    "model": "burley", "gaussians": 4, "scale": 0.5, "albedo_mode": "pre-post"},
    "scalars.json": {"sigma_a": 0.01, "sigma_s": 1, "model": "pbd", "enabled": False},
    "mc.json": {"preset": "marble", "model": "mc", "gaussians": 1, "albedo_mode": "post-scatter"},
    "dipole.json": {"color": 0.5, "mfp": 2, "model": "dipole", "gaussians": 8, "eta": 1.0},
    "openpbr.json": {"openpbr": {"subsurface_color": [0.671, 0.505, 0.371], "subsurface_radius": 1,
                                 "subsurface_radius_scale": [0.482, 0.169, 0.109],
                                 "subsurface_scatter_anisotropy": 0.2, "specular_ior": 1.4,
                                 "subsurface_weight": 1},
                     "albedo_inversion": "model", "model": "better-dipole"},
    "standard_surface.json": {"standard_surface": {"subsurface_color": 0.6, "subsurface_radius": [1, 0.5, 0.25],
                                                   "subsurface_scale": 2, "subsurface_anisotropy": 0,
                                                   "specular_IOR": 1.5, "subsurface": 1}},
}

ARGS = {
    "preset.txt": "--preset skin1",
    "coefficients.txt": "--sigma-a 0.032,0.17,0.48 --sigma-s 0.74,0.88,1.01 --g 0.1 --eta 1.4",
    "artist.txt": "--color 0.8,0.5,0.3 --mfp 1,0.5,0.25 --model burley",
    "slab.txt": "--model multipole --thickness 2 --preset marble",
    "overrides.txt": "--gaussians 3 --albedo pre-post --preset skin2 --eta 1.33",
    "nul_separated.txt": "--sigma-a\x000.1\x00--sigma-s\x001e-3\x00--model\x00mc",
    "equals.txt": "--color=0.9 --mfp=0.5 --model=dipole --gaussians=8",
    "openpbr.txt": "--subsurface-color 0.671,0.505,0.371 --subsurface-radius 1 "
                   "--subsurface-radius-scale 0.482,0.169,0.109 --eta 1.4 --albedo-inversion model",
    "standard_surface.txt": "--subsurface-color 0.6 --subsurface-radius 1,0.5,0.25 --subsurface-scale 2",
}


def main():
    for t in ("gltf", "sss_extras", "medium_args", "image"):
        os.makedirs(os.path.join(CORPUS, t), exist_ok=True)
    put("gltf", "triangle.gltf", triangle_gltf())
    put("gltf", "triangle.glb", triangle_gltf(glb=True))
    put("gltf", "strip_unindexed.gltf", triangle_gltf(mode=5, indexed=False,
                                                      sss=SSS_BLOCKS["coefficients.json"]))
    put("gltf", "fan_artist.gltf", triangle_gltf(mode=6, sss=SSS_BLOCKS["artist.json"]))
    put("gltf", "textured.gltf", triangle_gltf(textured=True))
    put("gltf", "textured.glb", triangle_gltf(glb=True, textured=True))
    put("gltf", "quantized_textured.glb", triangle_gltf(glb=True, textured=True, quantized=True))
    shutil.copyfile(os.path.join(HERE, "..", "assets", "textured_tile.glb"),
                    os.path.join(CORPUS, "gltf", "textured_tile.glb"))
    for name, block in SSS_BLOCKS.items():
        put("sss_extras", name, json.dumps(block))
    for name, text in ARGS.items():
        put("medium_args", name, text)
    pngs()
    exrs()


if __name__ == "__main__":
    main()
