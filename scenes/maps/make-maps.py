#!/usr/bin/env python3
"""Writes the small groom maps the scenes/groom-*.json files use (64x64
greyscale or RGB PNGs, row 0 at the top = v = 1, as pelt reads maps).
Run from this folder: ./make-maps.py"""
import struct
import zlib


def png(path, w, h, channels, pixel):
    rows = b''.join(b'\0' + bytes(c for x in range(w) for c in pixel(x, y)) for y in range(h))
    def chunk(kind, data):
        return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data))
    colour_type = {1: 0, 3: 2}[channels]
    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n')
        f.write(chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, colour_type, 0, 0, 0)))
        f.write(chunk(b'IDAT', zlib.compress(rows, 9)))
        f.write(chunk(b'IEND', b''))


# Eight stripes across u: white (long) and black (short).
png('stripes-u.png', 64, 64, 1, lambda x, y: (255 if (x // 8) % 2 == 0 else 0,))
# One band across u (u in [0.375, 0.5)) with no hair, the rest full.
png('band-u.png', 64, 64, 1, lambda x, y: (0 if 24 <= x < 32 else 255,))
# A flow map leaning every strand along +u: r = 1, g = 0.5.
png('flow-u.png', 64, 64, 3, lambda x, y: (255, 128, 128))
