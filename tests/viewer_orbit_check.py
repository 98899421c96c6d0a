#!/usr/bin/env python3
"""After --orbit N the rested view equals the view without an orbit, pixel for pixel.

Usage: viewer_orbit_check.py TRILAB OUT_DIR [VIEWER ARGS...]

Runs the viewer twice under xvfb-run with the same arguments and --screenshot, once with
--orbit and once without, and compares the view rectangle (from --print-layout) of the two
screenshots; the status bar outside it shows frame times, which differ from run to run. The
orbit run must have drawn the proxy (TRILAB_PROXY_MIN_FACES, set by the test, gives the small
test mesh one), so the comparison covers the proxy-to-exact switch.
"""
import os
import re
import struct
import subprocess
import sys
import zlib


def read_png(path):
    """(width, height, bytes per pixel, rows) of an 8-bit RGB or RGBA PNG."""
    data = open(path, "rb").read()
    i, idat = 8, b""
    width = height = kind = 0
    while i < len(data):
        n = struct.unpack(">I", data[i:i + 4])[0]
        tag, body = data[i + 4:i + 8], data[i + 8:i + 8 + n]
        if tag == b"IHDR":
            width, height, depth, kind = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and kind in (2, 6), f"{path}: not 8-bit RGB(A)"
        elif tag == b"IDAT":
            idat += body
        i += 12 + n
    raw = zlib.decompress(idat)
    bpp = 4 if kind == 6 else 3
    stride = width * bpp
    rows, prev, p = [], bytearray(stride), 0
    for _ in range(height):
        f, line = raw[p], bytearray(raw[p + 1:p + 1 + stride])
        p += 1 + stride
        for x in range(stride):
            a = line[x - bpp] if x >= bpp else 0
            b = prev[x]
            c = prev[x - bpp] if x >= bpp else 0
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return width, height, bpp, rows


def run(trilab, out, args, orbit):
    png = os.path.join(out, "orbit.png" if orbit else "still.png")
    cmd = ["xvfb-run", "-a", "-s", "-screen 0 1280x800x24", trilab, *args, "--no-recovery",
           "--print-layout", "--screenshot", png]
    if orbit:
        cmd += ["--orbit", "24"]
    result = subprocess.run(cmd, capture_output=True, text=True, timeout=240)
    text = result.stdout + result.stderr
    if result.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed ({result.returncode}):\n{text}")
    view = re.search(r"^view (\d+) (\d+) (\d+) (\d+)$", text, re.M)
    if not view:
        sys.exit(f"no view line in:\n{text}")
    return png, [int(v) for v in view.groups()], text


def main():
    trilab, out, args = sys.argv[1], sys.argv[2], sys.argv[3:]
    os.makedirs(out, exist_ok=True)
    still, view, _ = run(trilab, out, args, False)
    orbit, view_orbit, text = run(trilab, out, args, True)
    print(text)
    if view != view_orbit:
        sys.exit(f"the views differ: {view} and {view_orbit}")
    frames = re.search(r"orbit: proxy_frames=(\d+) exact_frames=(\d+)", text)
    if not frames or int(frames.group(1)) == 0:
        sys.exit("the orbit drew no proxy frame: the test would not cover the switch")
    w1, h1, bpp1, a = read_png(still)
    w2, h2, bpp2, b = read_png(orbit)
    if (w1, h1) != (w2, h2):
        sys.exit(f"screenshot sizes differ: {w1}x{h1} and {w2}x{h2}")
    x0, y0, w, h = view
    differing = 0
    for y in range(y0, min(y0 + h, h1)):
        ra, rb = a[y], b[y]
        for x in range(x0, min(x0 + w, w1)):
            if ra[x * bpp1:x * bpp1 + 3] != rb[x * bpp2:x * bpp2 + 3]:
                differing += 1
    if differing:
        sys.exit(f"{differing} pixels of the view differ after the orbit ({still}, {orbit})")
    print(f"the rested view equals the unturned view: {w}x{h} pixels")


if __name__ == "__main__":
    main()
