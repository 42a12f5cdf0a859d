#!/usr/bin/env python3
"""Writes the example material maps of scenes/marble_textured.json: a veined marble's surface albedo
(scenes/maps/marble_albedo.png, sRGB colour) and its mean-free-path factor (scenes/maps/marble_mfp.png, linear
data: 255 = the material's mfp_mm, lower = denser veins). Standard library only; deterministic.

Usage: python3 scripts/make_marble_maps.py [OUTPUT_DIR]   (default: scenes/maps beside this script's repo)
"""
import math
import os
import struct
import sys
import zlib

WIDTH, HEIGHT = 512, 256  # the sphere's u runs around it (twice as long as v, pole to pole)


def write_png(path, width, height, rows):
    """rows: a list of bytes objects, RGB 8-bit, top row first."""
    raw = b"".join(b"\x00" + row for row in rows)

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(png)
    os.replace(tmp, path)


def hash01(ix, iy, seed):
    h = (ix * 374761393 + iy * 668265263 + seed * 2147483647) & 0xFFFFFFFF
    h = ((h ^ (h >> 13)) * 1274126177) & 0xFFFFFFFF
    return ((h ^ (h >> 16)) & 0xFFFFFF) / float(0x1000000)


def value_noise(x, y, period_x, seed):
    """Smooth value noise, periodic in x with period_x lattice cells (so the texture wraps around the sphere)."""
    ix, iy = math.floor(x), math.floor(y)
    fx, fy = x - ix, y - iy
    sx, sy = fx * fx * (3 - 2 * fx), fy * fy * (3 - 2 * fy)

    def v(i, j):
        return hash01(i % period_x, j, seed)

    a = v(ix, iy) + (v(ix + 1, iy) - v(ix, iy)) * sx
    b = v(ix, iy + 1) + (v(ix + 1, iy + 1) - v(ix, iy + 1)) * sx
    return a + (b - a) * sy


def turbulence(u, v):
    total, amplitude, frequency = 0.0, 1.0, 4
    for octave in range(5):
        total += amplitude * value_noise(u * frequency, v * frequency / 2, frequency, 7 + octave)
        amplitude *= 0.5
        frequency *= 2
    return total


def srgb(linear):
    c = min(max(linear, 0.0), 1.0)
    c = 12.92 * c if c <= 0.0031308 else 1.055 * c ** (1 / 2.4) - 0.055
    return int(round(255 * c))


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "scenes", "maps")
    os.makedirs(out, exist_ok=True)
    base, vein = (0.86, 0.83, 0.78), (0.30, 0.40, 0.36)  # linear surface albedos
    albedo_rows, mfp_rows = [], []
    for y in range(HEIGHT):
        v = (HEIGHT - 1 - y + 0.5) / HEIGHT  # v = 0 at the bottom row, as lucent reads maps
        albedo_row, mfp_row = bytearray(), bytearray()
        for x in range(WIDTH):
            u = (x + 0.5) / WIDTH
            # Veins: thin dark bands where a turbulent sine crosses zero.
            phase = 6.0 * math.pi * (u + 0.35 * v) + 5.0 * turbulence(u, v)
            w = math.exp(-(math.sin(phase) ** 2) / 0.015)
            albedo_row += bytes(srgb(b + (c - b) * w) for b, c in zip(base, vein))
            mfp_row += bytes([int(round(255 * (1.0 - 0.75 * w)))] * 3)  # veins: a quarter of the mean free path
        albedo_rows.append(bytes(albedo_row))
        mfp_rows.append(bytes(mfp_row))
    write_png(os.path.join(out, "marble_albedo.png"), WIDTH, HEIGHT, albedo_rows)
    write_png(os.path.join(out, "marble_mfp.png"), WIDTH, HEIGHT, mfp_rows)
    print(f"wrote {out}/marble_albedo.png and marble_mfp.png ({WIDTH}x{HEIGHT})")


if __name__ == "__main__":
    main()
