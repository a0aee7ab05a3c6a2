#!/usr/bin/env python3
"""Writes brume's own test texture (scenes/textures/brume-pattern.png) with the standard library.

A 256x256 sRGB pattern: a light field with a dark grid, the letter B made of blocks, and a row of
colour bars, so that blur, noise and colour shifts through fog are easy to see.
"""
import struct
import sys
import zlib

W = H = 256

B = [
    "11110",
    "10001",
    "10001",
    "11110",
    "10001",
    "10001",
    "11110",
]

BARS = [(230, 60, 50), (240, 200, 40), (60, 180, 75), (40, 120, 220), (150, 70, 200), (245, 245, 245)]


def pixel(x, y):
    if y >= 208:
        return BARS[min(x * len(BARS) // W, len(BARS) - 1)]
    if x % 32 in (0, 1) or y % 32 in (0, 1):
        return (40, 40, 48)
    # The letter B, 20-pixel blocks, centred in the upper part.
    bx, by = (x - 78) // 20, (y - 36) // 22
    if 0 <= by < len(B) and 0 <= bx < 5 and B[by][bx] == "1":
        return (25, 35, 90)
    return (215, 210, 195)


def png(path):
    raw = b"".join(b"\x00" + bytes(c for x in range(W) for c in pixel(x, y)) for y in range(H))

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    data = b"\x89PNG\r\n\x1a\n"
    data += chunk(b"IHDR", struct.pack(">IIBBBBB", W, H, 8, 2, 0, 0, 0))
    data += chunk(b"sRGB", b"\x00")
    data += chunk(b"IDAT", zlib.compress(raw, 9))
    data += chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(data)


if __name__ == "__main__":
    png(sys.argv[1] if len(sys.argv) > 1 else "scenes/textures/brume-pattern.png")
