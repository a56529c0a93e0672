#!/usr/bin/env python3
"""Writes the text and GLB seeds of fuzz/corpus/ (the JPEG/PNG image seeds were written once with
stb_image_write and are kept as files). With the path of a manifest.json written by
`aasim fixtures --out DIR` it also writes the manifest seeds that pass the canonical-set check. Each seed is a valid input or one of the hostile inputs
of issue 10, so the fuzzer starts on both sides of every check. Run from anywhere; rewrites the
seeds in place."""
import base64, json, os, struct, sys, zlib

HERE = os.path.dirname(os.path.abspath(__file__))

def write(kind, name, data):
    path = os.path.join(HERE, "corpus", kind, name)
    with open(path, "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())

def deep(levels):
    return "[" * levels + "]" * levels

# --- glTF ---------------------------------------------------------------------------------------
positions = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
indices = struct.pack("<3H", 0, 1, 2) + b"\0\0"
buffer = positions + indices

def triangle(uri=None, extra=None):
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "translation": [0, 0, -2]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 0.2, 1]}}],
        "buffers": [{"byteLength": len(buffer)}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
             "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
    }
    if uri is not None:
        doc["buffers"][0]["uri"] = uri
    if extra:
        extra(doc)
    return doc

data_uri = "data:application/octet-stream;base64," + base64.b64encode(buffer).decode()
write("gltf", "triangle-data-uri.gltf", json.dumps(triangle(data_uri)))

def glb(doc, bin_chunk, bin_length_delta=0):
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    chunks = struct.pack("<II", len(text), 0x4E4F534A) + text
    chunks += struct.pack("<II", len(bin_chunk) + bin_length_delta, 0x004E4942) + bin_chunk
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks

write("gltf", "triangle.glb", glb(triangle(), buffer))
# The BIN chunk claims 8 bytes more than the file holds (read past the heap buffer before).
write("gltf", "bin-chunk-overrun.glb", glb(triangle(), buffer, 8))

write("gltf", "extras-20000-deep.gltf",
      json.dumps(triangle(data_uri)).replace('"asset"', '"extras": ' + deep(20000) + ', "asset"', 1))

def wrong(pointer_edit):
    doc = triangle(data_uri)
    pointer_edit(doc)
    return json.dumps(doc)
write("gltf", "bufferview-string.gltf", wrong(lambda d: d["accessors"][0].update(bufferView="0")))
write("gltf", "basecolor-string.gltf", wrong(
    lambda d: d["materials"][0]["pbrMetallicRoughness"].update(baseColorFactor=[1, "0.5", 0.2, 1])))
write("gltf", "byteoffset-negative.gltf", wrong(lambda d: d["bufferViews"][1].update(byteOffset=-12)))
write("gltf", "scene-string.gltf", wrong(lambda d: d.update(scene="hello")))
write("gltf", "coordinates-1e19.gltf", wrong(lambda d: d["nodes"][0].update(translation=[1e19, 0, 0])))
write("gltf", "yfov-pi.gltf", wrong(lambda d: d["cameras"][0]["perspective"].update(yfov=3.14159265)))
write("gltf", "uri-directory.gltf", json.dumps(triangle(".")))
write("gltf", "uri-device.gltf", json.dumps(triangle("/dev/zero")))

# --- images -------------------------------------------------------------------------------------
def png(width, height, rows):
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))
# 20000 x 20000 grey in the header, a few rows of data: the size check must come first.
write("image", "20000x20000-header.png", png(20000, 20000, b"\0" * 20001 * 4))
# A real 4 x 4 JPEG whose frame header (SOF0) claims 8192 x 8192: stb_image would decode the
# missing data as zeros; refused first by texels per byte (kMaxJpegTexelsPerByte).
with open(os.path.join(HERE, "corpus", "image", "rgb-4x4.jpg"), "rb") as f:
    jpeg = bytearray(f.read())
sof = jpeg.index(b"\xff\xc0")
jpeg[sof + 5:sof + 9] = struct.pack(">HH", 8192, 8192)
write("image", "8192x8192-header.jpg", bytes(jpeg))

# --- sample patterns ----------------------------------------------------------------------------
write("sample_pattern", "uniform-4.json",
      '{"name": "rg4", "samples": 4, "offsets": [[-2,-6],[6,-2],[-6,2],[2,6]]}')
write("sample_pattern", "per-pixel-2-pixels.json", json.dumps(
    {"name": "pp", "samples": 2, "units": "pixels",
     "pixels": [[[0.25, 0.25], [0.75, 0.75]]] * 4}))
write("sample_pattern", "tiny-off-grid.json",
      '{"name":"x","samples":2,"units":"pixels","offsets":[[0.5,0.5],[5e-324,0.5]]}')
write("sample_pattern", "nested-70000.json", '{"name": "x", "samples": ' + deep(70000) + "}")

# --- CRAA LUT fixtures (docs/craa.md "File format") -----------------------------------------------
def craa_lut(samples, tables, entries, fallback=()):
    return json.dumps({"schema": "aasim.craa.lut", "version": 1, "pattern": "fuzz", "samples": samples,
                       "tables": [{"offsets": offsets, "fallback": list(fallback), "entries": entries}
                                  for offsets in tables]})

write("craa_lut", "uniform-2.json",
      craa_lut(2, [[[-4, -4], [4, 4]]], [[0, 0, 0, 0], [1, 0, 0, 0], [0, 0, 0, 1], [0, 1, 1, 0]], [2]))
# One table per quad pixel; craa_lut() gives every table the same entries.
write("craa_lut", "per-pixel-1.json",
      craa_lut(1, [[[0, 0]], [[1, 1]], [[-1, -1]], [[7, -8]]], [[0, 0, 0, 0], [0, 0, 1, 0]]))
write("craa_lut", "sum-above-unknown.json",
      craa_lut(2, [[[-4, -4], [4, 4]]], [[0, 0, 0, 0], [1, 1, 0, 0], [0, 0, 0, 1], [0, 1, 1, 0]]))
write("craa_lut", "nested-70000.json", '{"schema": "aasim.craa.lut", "tables": ' + deep(70000) + "}")

# --- GPU files ----------------------------------------------------------------------------------
gpu_dir = os.path.join(HERE, "..", "sim", "gpus")
for name in sorted(os.listdir(gpu_dir)):
    with open(os.path.join(gpu_dir, name), "rb") as f:
        write("gpu_config", name, f.read())
with open(os.path.join(gpu_dir, "ps4-class.jsonc")) as f:
    ps4 = f.read()
write("gpu_config", "threads-int-max.jsonc",
      ps4.replace('"maxThreadsPerGroup": 1024', '"maxThreadsPerGroup": 2147483647'))
write("gpu_config", "vgprs-4.jsonc", ps4.replace('"maxVgprsPerWave": 256', '"maxVgprsPerWave": 4'))
write("gpu_config", "clock-1e400.jsonc", ps4.replace('"clockMhz": 800', '"clockMhz": 1e400'))
write("gpu_config", "nested-70000.jsonc", '{"name": ' + deep(70000) + "}")

# --- fixture manifests --------------------------------------------------------------------------
write("fixture_manifest", "nested-70000.json",
      '{"schema": "aasim.fmask.fixtures", "version": ' + deep(70000) + "}")
write("fixture_manifest", "empty-list.json",
      '{"schema": "aasim.fmask.fixtures", "version": 1, "fixtures": []}')
if len(sys.argv) > 1:
    with open(sys.argv[1]) as f:
        manifest = json.load(f)
    names = dict(manifest, fixtures=[{"name": entry["name"]} for entry in manifest["fixtures"]])
    write("fixture_manifest", "canonical-names.json", json.dumps(names))
    write("fixture_manifest", "two-fixtures.json", json.dumps(dict(manifest, fixtures=manifest["fixtures"][:2])))
