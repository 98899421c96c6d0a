#!/usr/bin/env python3
"""Plots transfer curves written by `trilab-cli spectrum ... --filter ... --gains FILE` as one SVG.

usage: plot_gains.py [--predicted-only] OUT.svg "TITLE" GAINS [TITLE GAINS ...]

Each GAINS file gets a panel: |predicted gain| over the eigenvalue (log scale), red where the
gain is below -1 (growing and oscillating: unstable), orange where it is negative (oscillating),
blue otherwise, with the measured gains as dots where the file has them. Standard library only.
"""
import math
import sys


def read_gains(path):
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            _, ev, pred, meas = line.split()
            rows.append((max(0.0, float(ev)), float(pred), float(meas)))
    return sorted(rows)


def panel(x0, title, rows, measured, width=380, height=260):
    lo_exp, hi_exp = -3, 2  # |gain| from 1e-3 to 1e2
    top = max(r[0] for r in rows) or 1.0
    px = lambda ev: x0 + 50 + (width - 60) * ev / top
    py = lambda g: 30 + (height - 70) * (hi_exp - math.log10(min(max(abs(g), 10 ** lo_exp), 10 ** hi_exp))) / (hi_exp - lo_exp)
    out = [f'<text x="{x0 + width / 2}" y="18" text-anchor="middle" font-size="13">{title}</text>']
    out.append(f'<rect x="{x0 + 50}" y="30" width="{width - 60}" height="{height - 70}" fill="none" stroke="#888"/>')
    for e in range(lo_exp, hi_exp + 1):
        y = py(10 ** e)
        out.append(f'<line x1="{x0 + 50}" y1="{y}" x2="{x0 + width - 10}" y2="{y}" stroke="#ddd"/>')
        out.append(f'<text x="{x0 + 45}" y="{y + 4}" text-anchor="end" font-size="10">1e{e}</text>')
    for i in range(5):
        ev = top * i / 4
        out.append(f'<text x="{px(ev)}" y="{height - 25}" text-anchor="middle" font-size="10">{ev:.2f}</text>')
    out.append(f'<text x="{x0 + 50 + (width - 60) / 2}" y="{height - 8}" text-anchor="middle" font-size="11">eigenvalue λ of the umbrella (every frequency of the mesh)</text>')
    colour_of = lambda g: "#c0392b" if g < -1 else "#e67e22" if g < 0 else "#2c6fbb"
    step = max(1, len(rows) // 300)
    points = rows[::step] + ([rows[-1]] if (len(rows) - 1) % step else [])
    run, colour = [], None
    for ev, pred, _ in points:  # one polyline per run of one colour
        c = colour_of(pred)
        if c != colour and run:
            out.append(f'<polyline fill="none" stroke="{colour}" stroke-width="2" points="{" ".join(run)}"/>')
            run = run[-1:]
        colour = c
        run.append(f"{px(ev):.1f},{py(pred):.1f}")
    if run:
        out.append(f'<polyline fill="none" stroke="{colour}" stroke-width="2" points="{" ".join(run)}"/>')
    for ev, _, meas in rows[:: max(1, len(rows) // 150)] if measured else []:
        if not math.isnan(meas):
            out.append(f'<circle cx="{px(ev):.1f}" cy="{py(meas):.1f}" r="1.6" fill="#222"/>')
    y1 = py(1.0)
    out.append(f'<text x="{x0 + width - 12}" y="{y1 - 4}" text-anchor="end" font-size="10">|gain| = 1</text>')
    return out


def main():
    args = sys.argv[1:]
    measured = not (args and args[0] == "--predicted-only")
    args = args if measured else args[1:]
    if len(args) < 3 or len(args) % 2 == 0:
        sys.exit(__doc__)
    pairs = list(zip(args[1::2], args[2::2]))
    width = 380 * len(pairs)
    body = []
    for i, (title, path) in enumerate(pairs):
        body += panel(380 * i, title, read_gains(path), measured)
    legend = ('<text x="10" y="290" font-size="10">blue: damped; orange: negative gain (oscillates); '
              'red: below -1 (grows: unstable); dots: measured gain</text>')
    svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="300" font-family="sans-serif">',
           '<rect width="100%" height="100%" fill="white"/>'] + body + [legend, "</svg>"]
    if not measured:
        legend = legend.replace("; dots: measured gain", "")
    with open(args[0], "w") as f:
        f.write("\n".join(svg) + "\n")


if __name__ == "__main__":
    main()
