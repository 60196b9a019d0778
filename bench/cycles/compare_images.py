"""The images of bench/cycles/compare.py (issue 23, the Cycles comparison), also read by
bench/smallpt_compare.py and bench/sampler_study.py through compare.py: an EXR's R, G, B read
through oiiotool, Rec. 709 luminance, the emissive materials' luminance from the glTF, the
mask of pixels away from the light, and the relative MSE against a reference."""
import json
import os
import re
import struct
import subprocess
import tempfile

import numpy as np

LUMA = np.array([0.2126, 0.7152, 0.0722])


def read_rgb(path):
    """R, G, B of an EXR as float64 (H, W, 3), row 0 on top, through oiiotool (openimageio-tools)."""
    with tempfile.TemporaryDirectory() as tmp:
        rgb = os.path.join(tmp, "rgb.exr")
        subprocess.run(["oiiotool", path, "--ch", "R,G,B", "-d", "float", "-o", rgb], check=True,
                       stdout=subprocess.DEVNULL)
        text = subprocess.run(["oiiotool", "--dumpdata", rgb], check=True, capture_output=True,
                              text=True).stdout
    header = re.search(r":\s+(\d+) x\s+(\d+), 3 channel", text)
    if not header:
        raise RuntimeError(f"{path}: unexpected oiiotool --dumpdata output")
    w, h = int(header.group(1)), int(header.group(2))
    img = np.zeros((h, w, 3))
    seen = 0
    for m in re.finditer(r"Pixel \((\d+), (\d+)\): (\S+) (\S+) (\S+)", text):
        x, y = int(m.group(1)), int(m.group(2))
        img[y, x] = (float(m.group(3)), float(m.group(4)), float(m.group(5)))
        seen += 1
    if seen != w * h:
        raise RuntimeError(f"{path}: read {seen} pixels of {w}x{h}")
    return img


def luminance(img):
    return img @ LUMA


def gltf_json(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] == b"glTF":  # .glb: 12-byte header, then the JSON chunk
        length, kind = struct.unpack_from("<II", data, 12)
        if kind != 0x4E4F534A:
            raise RuntimeError(f"{path}: first .glb chunk is not JSON")
        return json.loads(data[20:20 + length])
    return json.loads(data)


def emitted_luminances(scene):
    out = []
    for m in gltf_json(scene).get("materials", []):
        e = m.get("emissiveFactor", [0.0, 0.0, 0.0])
        s = m.get("extensions", {}).get("KHR_materials_emissive_strength", {}).get("emissiveStrength", 1.0)
        y = float(np.dot(LUMA, np.array(e, dtype=float) * s))
        if y > 0.0:
            out.append(y)
    return out


def away_mask(refs, threshold):
    """True where a pixel is away from the light: no reference at or above threshold there or next to it."""
    bright = np.zeros(refs[0].shape[:2], dtype=bool)
    for ref in refs:
        bright |= luminance(ref) >= threshold
    near = bright.copy()
    h, w = bright.shape
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            shifted = np.zeros_like(bright)
            shifted[max(dy, 0):h + min(dy, 0), max(dx, 0):w + min(dx, 0)] = \
                bright[max(-dy, 0):h + min(-dy, 0), max(-dx, 0):w + min(-dx, 0)]
            near |= shifted
    return ~near, int(bright.sum())


def rel_mse(img, ref, mask=None):
    if mask is not None:
        img, ref = img[mask], ref[mask]
    return float(np.mean((img - ref) ** 2) / np.mean(ref) ** 2)
