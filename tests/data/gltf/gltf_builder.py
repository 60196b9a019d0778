# The glTF builder behind make_fixtures.py: a document with one binary buffer, written as
# .gltf (the buffer embedded or in a .bin beside it) or as .glb, into this folder.
import base64
import json
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
FLOAT, U8, U16, U32 = 5126, 5121, 5123, 5125
TRIANGLE = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
QUAD = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]


class Gltf:
    """A glTF document under construction with one binary buffer."""

    def __init__(self):
        self.doc = {"asset": {"version": "2.0", "generator": "make_fixtures.py"},
                    "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [],
                    "accessors": [], "bufferViews": [], "buffers": []}
        self.bin = bytearray()

    def add(self, array, item):
        self.doc.setdefault(array, []).append(item)
        return len(self.doc[array]) - 1

    def view(self, data, stride=None):
        while len(self.bin) % 4:
            self.bin.append(0)
        view = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if stride:
            view["byteStride"] = stride
        self.bin += data
        return self.add("bufferViews", view)

    def positions(self, points):
        data = b"".join(struct.pack("<3f", *p) for p in points)
        return self.add("accessors", {"bufferView": self.view(data), "componentType": FLOAT,
                                      "count": len(points), "type": "VEC3"})

    def indices(self, values, ctype=U16):
        fmt = {U8: "B", U16: "H", U32: "I"}[ctype]
        data = struct.pack("<%d%s" % (len(values), fmt), *values)
        return self.add("accessors", {"bufferView": self.view(data), "componentType": ctype,
                                      "count": len(values), "type": "SCALAR"})

    def mesh(self, points, indices=None, material=None, ctype=U16):
        prim = {"attributes": {"POSITION": self.positions(points)}}
        if indices is not None:
            prim["indices"] = self.indices(indices, ctype)
        if material is not None:
            prim["material"] = material
        return self.add("meshes", {"primitives": [prim]})

    def node(self, root=True, **fields):
        index = self.add("nodes", fields)
        if root:
            self.doc["scenes"][0]["nodes"].append(index)
        return index

    def finish_buffer(self, uri):
        buffer = {"byteLength": len(self.bin)}
        if uri is not None:
            buffer["uri"] = uri
        self.doc["buffers"] = [buffer] if self.bin else []
        if not self.bin:
            for key in ("bufferViews", "buffers", "accessors"):
                self.doc.pop(key, None)

    def write_gltf(self, name, bin_name=None):
        if bin_name:
            with open(os.path.join(HERE, bin_name), "wb") as f:
                f.write(self.bin)
            self.finish_buffer(bin_name)
        else:
            self.finish_buffer("data:application/octet-stream;base64," +
                               base64.b64encode(bytes(self.bin)).decode())
        write_text(name, json.dumps(self.doc, indent=1) + "\n")

    def write_glb(self, name, bin_chunk_extra=0):
        self.finish_buffer(None)
        text = json.dumps(self.doc, separators=(",", ":")).encode()
        text += b" " * (-len(text) % 4)
        data = bytes(self.bin) + b"\0" * (-len(self.bin) % 4)
        body = struct.pack("<II", len(text), 0x4E4F534A) + text
        body += struct.pack("<II", len(data) + bin_chunk_extra, 0x004E4942) + data
        with open(os.path.join(HERE, name), "wb") as f:
            f.write(struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body)


def write_text(name, text):
    with open(os.path.join(HERE, name), "w") as f:
        f.write(text)


def one_triangle(points=TRIANGLE):
    g = Gltf()
    g.node(mesh=g.mesh(points))
    return g
