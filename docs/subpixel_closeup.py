#!/usr/bin/env python3
"""A close-up of a native panel image that shows its subpixels: each pixel of
a crop becomes three stripes, red, green and blue, each lit by its own
channel, as the panel lights them. Reads and writes binary PPM (P6).
Usage: subpixel_closeup.py IN.ppm OUT.ppm X Y W H SCALE [bgr]"""
import sys


def read_ppm(path):
    data = open(path, "rb").read()
    fields, pos = [], 0
    while len(fields) < 4:  # magic, width, height, maxval; skip comments
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            pos = data.index(b"\n", pos)
            continue
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    assert fields[0] == b"P6" and fields[3] == b"255", "expected an 8-bit P6 PPM"
    return int(fields[1]), int(fields[2]), data[pos + 1:]


def main():
    src, dst = sys.argv[1], sys.argv[2]
    x0, y0, w, h, scale = (int(a) for a in sys.argv[3:8])
    order = [2, 1, 0] if len(sys.argv) > 8 and sys.argv[8] == "bgr" else [0, 1, 2]
    width, _, px = read_ppm(src)
    rows = []
    for y in range(y0, y0 + h):
        row = bytearray()
        for x in range(x0, x0 + w):
            p = px[(y * width + x) * 3:(y * width + x) * 3 + 3]
            for ch in order:  # stripes left to right in the panel's order
                stripe = bytearray(3)
                stripe[ch] = p[ch]
                row += stripe * scale
        for _ in range(3 * scale):  # square pixels: three stripes wide, three scales tall
            rows.append(bytes(row))
    with open(dst, "wb") as f:
        f.write(b"P6\n%d %d\n255\n" % (w * 3 * scale, h * 3 * scale))
        f.writelines(rows)


if __name__ == "__main__":
    main()
