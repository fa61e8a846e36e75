#!/usr/bin/env python3
"""Writes scenes/features/textures/gradient.bmp, the image of scenes/features/image_texture.sdl.

A 64x64 uncompressed 24-bit BMP (the format the SDL manual names, §3.2.8): red grows from left
to right, green from bottom to top, with a dark line every 16 texels and a white square in the
top-left corner, so that the image's orientation on each shape can be read off a render.
Standard library only: python3 scripts/make_texture_image.py
"""
import pathlib
import struct

SIZE = 64


def texel(x, y):  # y counts rows from the top
    if x < 12 and y < 12:
        return (255, 255, 255)
    if x % 16 == 0 or y % 16 == 0:
        return (20, 20, 40)
    return (round(255 * x / (SIZE - 1)), round(255 * (SIZE - 1 - y) / (SIZE - 1)), 110)


def bmp(width, height):
    row_bytes = (3 * width + 3) // 4 * 4
    pixels = bytearray()
    for y in reversed(range(height)):  # BMP rows run bottom to top
        row = bytearray()
        for x in range(width):
            r, g, b = texel(x, y)
            row += bytes((b, g, r))
        pixels += row + bytes(row_bytes - len(row))
    header = struct.pack("<2sIHHI", b"BM", 54 + len(pixels), 0, 0, 54)
    info = struct.pack("<IiiHHIIiiII", 40, width, height, 1, 24, 0, len(pixels), 2835, 2835, 0, 0)
    return header + info + pixels


if __name__ == "__main__":
    out = pathlib.Path(__file__).resolve().parent.parent / "scenes/features/textures/gradient.bmp"
    out.write_bytes(bmp(SIZE, SIZE))
    print(f"wrote {out}")
