#!/usr/bin/env python3
# test_cli: a roma-render PNG shows --background where coverage.pfm is 0, and elsewhere the
# PFM value times --exposure 0.5 through --tonemap reinhard, sRGB-encoded (within 1 of 255).
# Usage: check_png_tone.py AO.png AO.pfm COVERAGE.pfm (background 0,0,1)
import struct, sys, zlib
def png(path):  # 8-bit RGB, no interlace (stb_image_write)
    data = open(path, "rb").read()
    pos, idat, w, h = 8, b"", 0, 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h = struct.unpack(">II", body[:8])
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, rows, prev = zlib.decompress(idat), [], bytearray(3 * w)
    for y in range(h):
        start = y * (3 * w + 1)
        f, line = raw[start], bytearray(raw[start + 1:start + 1 + 3 * w])
        for i in range(3 * w):
            a = line[i - 3] if i >= 3 else 0
            b = prev[i]
            c = prev[i - 3] if i >= 3 else 0
            p = a + b - c
            paeth = a if abs(p - a) <= abs(p - b) and abs(p - a) <= abs(p - c) else (b if abs(p - b) <= abs(p - c) else c)
            line[i] = (line[i] + [0, a, b, (a + b) // 2, paeth][f]) & 255
        rows.append(line)
        prev = line
    return w, h, rows
def pfm(path):
    data = open(path, "rb").read()
    parts = data.split(b"\n", 3)
    w, h = map(int, parts[1].split())
    ch = 3 if parts[0] == b"PF" else 1
    return w, h, ch, struct.unpack("<%df" % (w * h * ch), parts[3][:4 * w * h * ch])  # rows bottom first
w, h, rows = png(sys.argv[1])
_, _, _, ao = pfm(sys.argv[2])
_, _, _, cov = pfm(sys.argv[3])
srgb = lambda v: round(255 * (12.92 * v if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055))
seen = background = 0
for y in range(h):
    for x in range(w):
        k = (h - 1 - y) * w + x
        px = tuple(rows[y][3 * x:3 * x + 3])
        if cov[k] > 0:
            v = 0.5 * ao[k]
            want = srgb(v / (1 + v))
            assert abs(px[0] - want) <= 1, (x, y, px, want)
            seen += 1
        else:
            assert px == (0, 0, 255), (x, y, px)
            background += 1
assert seen > 20 and background > 20, (seen, background)
