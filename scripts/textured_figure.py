#!/usr/bin/env python3
"""Writes a textured stand-in for a scanned character: a bumpy body of revolution of about
50,000 triangles with UVs, and 2048x2048 diffuse and specular maps (a fine pattern that aliases
without mip maps). Used to time the G-buffer on a textured model (README, Speed):
    scripts/textured_figure.py /tmp/figure && ssdo bench --scene room --model /tmp/figure/figure.obj ...
"""
import math
import os
import struct
import sys
import zlib


def png(path, width, height, pixel):
    rows = b"".join(b"\x00" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))
    chunk = lambda tag, data: struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data))
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows, 6)) + chunk(b"IEND", b""))


def main(out):
    os.makedirs(out, exist_ok=True)
    segments, rings = 112, 224
    lines = ["mtllib figure.mtl", "usemtl skin"]
    for j in range(rings + 1):
        t = j / rings
        for i in range(segments + 1):
            phi = 2 * math.pi * i / segments
            r = 0.12 * math.sqrt(max(math.sin(math.pi * t), 0.0)) * (1 + 0.06 * math.cos(7 * phi) * math.sin(9 * math.pi * t))
            lines.append(f"v {r * math.cos(phi):.6f} {t:.6f} {r * math.sin(phi):.6f}")
            lines.append(f"vt {4 * i / segments:.6f} {8 * t:.6f}")
    at = lambda i, j: j * (segments + 1) + i + 1
    for j in range(rings):
        for i in range(segments):
            a, b, c, d = at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)
            lines.append(f"f {a}/{a} {c}/{c} {b}/{b}")
            lines.append(f"f {a}/{a} {d}/{d} {c}/{c}")
    with open(os.path.join(out, "figure.obj"), "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(os.path.join(out, "figure.mtl"), "w") as f:
        f.write("newmtl skin\nKd 1 1 1\nKs 0.5 0.5 0.5\nNs 32\nmap_Kd diffuse.png\nmap_Ks specular.png\n")
    side = 2048
    png(os.path.join(out, "diffuse.png"), side, side,
        lambda x, y: (200, 120 + 80 * ((x // 3 + y // 3) % 2), 90) if (x * 7 + y * 13) % 11 else (60, 60, 60))
    png(os.path.join(out, "specular.png"), side, side, lambda x, y: (255 * ((x ^ y) & 1),) * 3)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "figure")
