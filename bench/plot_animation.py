#!/usr/bin/env python3
"""Per-shot plots of the animation benchmark (issue 12): PSNR and seconds per
frame, full ray tracing against reverse reprojection (colour and visibility
reuse) against holding the nearest keyframe (the do-nothing baseline).

Reads the per-frame tables (the paper's Table 1) of the reports that
bench/run_animation_bench.sh writes to bench/animation_reports/ and writes one
SVG per shot to bench/plots/. Standard library only.

Usage: python3 bench/plot_animation.py [SHOT...]   (default: every shot with reports)
"""
import math
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parent
REPORTS = ROOT / "animation_reports"
PLOTS = ROOT / "plots"

# (report suffix, legend, colour)
SERIES = [("reverse_color", "reverse, color reuse", "#d62728"),
          ("reverse_visibility", "reverse, visibility reuse", "#1f77b4")]


def per_frame(path):
    """Rows of the report's per-frame table as dicts (column name -> text)."""
    rows, header = [], None
    for line in path.read_text().splitlines():
        if line.startswith("| frame | kind"):
            header = [c.strip() for c in line.strip("|").split("|")]
        elif header and line.startswith("| ") and not line.startswith("|---"):
            cells = [c.strip() for c in line.strip("|").split("|")]
            if len(cells) == len(header):
                rows.append(dict(zip(header, cells)))
        elif header and not line.strip():
            break
    return rows


def number(text):
    try:
        return float(text)
    except ValueError:
        return math.nan


def nice_step(raw):
    """1, 2 or 5 times a power of ten, at least raw."""
    base = 10 ** math.floor(math.log10(raw))
    return next(m * base for m in (1, 2, 5, 10) if m * base >= raw - 1e-12)


def panel(x0, y0, w, h, frames, series, ylabel, ymin, ymax):
    """One SVG chart: series = [(legend, colour, [(frame, value)], dashed)]."""
    out = [f'<rect x="{x0}" y="{y0}" width="{w}" height="{h}" fill="none" stroke="#999"/>']
    sx = lambda f: x0 + w * f / max(1, frames - 1)
    sy = lambda v: y0 + h - h * (min(max(v, ymin), ymax) - ymin) / (ymax - ymin)
    step = nice_step((ymax - ymin) / 4)
    for k in range(int(math.floor((ymax - ymin) / step + 1e-9)) + 1):
        v = ymin + step * k
        out.append(f'<line x1="{x0}" x2="{x0 + w}" y1="{sy(v):.1f}" y2="{sy(v):.1f}" stroke="#eee"/>')
        out.append(f'<text x="{x0 - 6}" y="{sy(v) + 4:.1f}" text-anchor="end" font-size="11">{v:g}</text>')
    for f in range(0, frames, 20):
        out.append(f'<text x="{sx(f):.1f}" y="{y0 + h + 14}" text-anchor="middle" font-size="11">{f}</text>')
    out.append(f'<text x="{x0 - 52}" y="{y0 + h / 2}" font-size="12" transform="rotate(-90 {x0 - 52} {y0 + h / 2})"'
               f' text-anchor="middle">{ylabel}</text>')
    for legend, colour, points, dashed in series:
        pts = " ".join(f"{sx(f):.1f},{sy(v):.1f}" for f, v in points if math.isfinite(v))
        dash = ' stroke-dasharray="4 3"' if dashed else ""
        out.append(f'<polyline points="{pts}" fill="none" stroke="{colour}" stroke-width="1.3"{dash}/>')
    out.append(f'<rect x="{x0 + w - 196}" y="{y0 + 2}" width="194" height="{15 * len(series) + 4}" fill="white"'
               f' fill-opacity="0.85" stroke="#ccc"/>')
    for i, (legend, colour, points, dashed) in enumerate(series):
        dash = ' stroke-dasharray="4 3"' if dashed else ""
        ly = y0 + 14 + 15 * i
        out.append(f'<line x1="{x0 + w - 190}" x2="{x0 + w - 170}" y1="{ly - 4}" y2="{ly - 4}" stroke="{colour}"'
                   f' stroke-width="2"{dash}/>')
        out.append(f'<text x="{x0 + w - 165}" y="{ly}" font-size="11">{legend}</text>')
    return out


def plot(shot):
    runs = [(legend, colour, per_frame(REPORTS / f"{shot}_{suffix}.md"))
            for suffix, legend, colour in SERIES if (REPORTS / f"{shot}_{suffix}.md").exists()]
    if not runs:
        return None
    first = runs[0][2]
    frames = len(first)
    between = [r for r in first if r["kind"] != "key"]
    psnr = [(legend, colour, [(int(r["frame"]), number(r["PSNR dB"])) for r in rows if r["kind"] != "key"], False)
            for legend, colour, rows in runs]
    psnr.append(("hold nearest keyframe", "#555", [(int(r["frame"]), number(r["hold PSNR dB"])) for r in between], True))
    secs = [("full ray tracing", "#555", [(int(r["frame"]), number(r["full s"])) for r in first], True)]
    secs += [(legend, colour, [(int(r["frame"]), number(r["s"])) for r in rows], False) for legend, colour, rows in runs]
    finite = [v for _, _, pts, _ in psnr for _, v in pts if math.isfinite(v)]
    lo, hi = math.floor(min(finite) / 5) * 5, math.ceil(max(finite) / 5) * 5
    top = max(v for _, _, pts, _ in secs for _, v in pts if math.isfinite(v))
    W, H = 780, 520
    svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif">',
           f'<rect width="{W}" height="{H}" fill="white"/>',
           f'<text x="{W / 2}" y="20" text-anchor="middle" font-size="14">{shot}: {frames} frames, keyframe every 8'
           f' (PSNR against full ray tracing; keyframes are exact)</text>']
    svg += panel(80, 35, 660, 190, frames, psnr, "PSNR dB", lo, hi)
    step = nice_step(top / 4)
    svg += panel(80, 280, 660, 190, frames, secs, "seconds per frame", 0, step * math.ceil(top / step))
    svg.append(f'<text x="{W / 2}" y="{H - 12}" text-anchor="middle" font-size="12">frame</text>')
    svg.append("</svg>")
    PLOTS.mkdir(exist_ok=True)
    path = PLOTS / f"{shot}.svg"
    path.write_text("\n".join(svg) + "\n")
    return path


def main(argv):
    shots = argv or sorted({p.name.split("_")[0] for p in REPORTS.glob("*_reverse_color.md")})
    for shot in shots:
        path = plot(shot)
        print(path if path else f"{shot}: no reports in {REPORTS}", file=sys.stdout if path else sys.stderr)


if __name__ == "__main__":
    main(sys.argv[1:])
