"""Charts in one style for every driver (gnuplot, PNG): the legend below the data, axes named with
their units, a reference drawn as a dashed line, point labels only where they do not collide.

Each chart also leaves its data (<name>.dat) and gnuplot script (<name>.gp) beside the PNG, so that it
can be redrawn or restyled by hand: the script finds its data and writes its PNG in its own folder
(HERE below), so `gnuplot path/to/<name>.gp` works from any folder and the folder can be moved whole.
"""
import math
import os
import shutil
import subprocess

COLOURS = ["#c03030", "#e08020", "#208020", "#3050c0", "#8040a0", "#404040", "#20a0a0", "#a06020"]
HAVE_GNUPLOT = shutil.which("gnuplot") is not None


class Series:
    """One legend entry: points (x, y), drawn as points, lines or linespoints."""

    def __init__(self, name, points, style="linespoints", colour=None, pt=7, dash=None, width=2):
        self.name, self.style, self.colour, self.pt, self.dash, self.width = name, style, colour, pt, dash, width
        self.points = [(x, y) for x, y in points if _finite(x) and _finite(y)]


def _finite(v):
    return isinstance(v, (int, float)) and v == v and abs(v) != float("inf")


# gnuplot lines that set `here` to the folder of the script being run (ARG0 up to its last '/', "." for a
# script named without a folder); data and PNG paths are written as here.'/<file>'.
HERE = ["here = ARG0; i = strlen(here); while (i > 0 && here[i:i] ne '/') { i = i - 1 }",
        "here = (i > 1 ? here[1:i-1] : (i == 1 ? '/' : '.'))"]


def here_file(path, folder):
    """path as a gnuplot string expression for a script kept in folder: here.'/<relative path>' when path
    lies in folder, else path itself, absolute."""
    rel = os.path.relpath(os.path.abspath(path), os.path.abspath(folder))
    if rel == os.pardir or rel.startswith(os.pardir + os.sep):
        return _squote(os.path.abspath(path))
    return "here.%s" % _squote("/" + rel)


def _squote(text):
    return "'" + str(text).replace("'", "''") + "'"


def _quote(text):
    return '"' + str(text).replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'


def _axis_range(values, log):
    """The range gnuplot's autoscale gives (whole decades on a log axis), so that labels are placed in the
    coordinates of the drawn chart."""
    vals = [v for v in values if _finite(v) and (v > 0 or not log)]
    if not vals:
        return None
    lo, hi = min(vals), max(vals)
    if log:
        # whole decades, with a margin so that no point sits on the frame
        return 10.0 ** math.floor(math.log10(lo) - 0.1), 10.0 ** math.ceil(math.log10(hi) + 0.1)
    if hi == lo:
        return lo - 1, hi + 1
    pad = 0.05 * (hi - lo)
    step = 10.0 ** math.floor(math.log10(hi - lo))
    return math.floor((lo - pad) / step) * step, math.ceil((hi + pad) / step) * step


def _placed_labels(labels, xr, yr, logx, logy, size):
    """Keep the labels whose boxes (in the drawn chart's coordinates) do not overlap a kept one. The data
    area is about 88 % of the width and 70 % of the height (the title above, the legend below); a character
    of the labels' font is about 6.5 pixels wide and a line 14 pixels high."""
    if not xr or not yr:
        return []
    fx = (lambda v: math.log10(v)) if logx else (lambda v: v)
    fy = (lambda v: math.log10(v)) if logy else (lambda v: v)
    sx, sy = (fx(xr[1]) - fx(xr[0])) or 1.0, (fy(yr[1]) - fy(yr[0])) or 1.0
    char_w, line_h = 6.5 / (0.88 * size[0]), 14.0 / (0.7 * size[1])
    kept, boxes = [], []
    for x, y, text in labels:
        if (logx and x <= 0) or (logy and y <= 0) or not (_finite(x) and _finite(y)):
            continue
        u, v = (fx(x) - fx(xr[0])) / sx, (fy(y) - fy(yr[0])) / sy
        box = (u + 0.005, v + 0.005, u + 0.015 + char_w * len(str(text)), v + 0.01 + line_h)
        if any(not (box[2] < b[0] or b[2] < box[0] or box[3] < b[1] or b[3] < box[1]) for b in boxes):
            continue
        boxes.append(box)
        kept.append((x, y, text))
    return kept


def chart(png, title, xlabel, ylabel, series, logx=False, logy=False, refs=(), labels=(), xrange=None,
          yrange=None, size=(1000, 620), extra=()):
    """Draw series (a list of Series) into png. refs: (name, y) horizontal reference lines, dashed.
    labels: (x, y, text) point labels, dropped where they would collide. extra: more gnuplot lines."""
    base = os.path.splitext(png)[0]
    with open(base + ".dat", "w") as f:
        for i, s in enumerate(series):
            f.write("# %d %s\n" % (i, s.name))
            for x, y in s.points:
                f.write("%.10g %.10g\n" % (x, y))
            f.write("\n\n")
    lines = [
        *HERE,
        "set terminal pngcairo size %d,%d noenhanced font ',10'" % size,
        "set output %s" % here_file(png, os.path.dirname(png)),
        "set title %s" % _quote(title),
        "set xlabel %s" % _quote(xlabel),
        "set ylabel %s" % _quote(ylabel),
        "set grid",
        # below the data, in columns: the data keep the chart's width whatever the series' names
        "set key below center horizontal Left reverse samplen 2 spacing 1.2 maxcols 3 font ',9'",
    ]
    if logx:
        lines += ["set logscale x", "set format x '%g'"]   # 0.001, 1e-06: no padded decimals
    if logy:
        lines += ["set logscale y", "set format y '%g'"]
    allx = [x for s in series for x, _ in s.points] + [x for x, _, _ in labels]
    ally = [y for s in series for _, y in s.points] + [y for _, y, _ in labels] + [y for _, y in refs]
    xrange = xrange or _axis_range(allx, logx)
    yrange = yrange or _axis_range(ally, logy)
    if xrange:
        lines.append("set xrange [%.10g:%.10g]" % tuple(xrange))
    if yrange:
        lines.append("set yrange [%.10g:%.10g]" % tuple(yrange))
    for k, (x, y, text) in enumerate(_placed_labels(list(labels), xrange, yrange, logx, logy, size)):
        lines.append("set label %d %s at %.10g,%.10g offset 0.6,0.6 font ',8' tc rgb '#404040'"
                     % (k + 1, _quote(text), x, y))
    lines.extend(extra)
    plots = []
    for i, s in enumerate(series):
        if not s.points:
            continue
        colour = s.colour or COLOURS[i % len(COLOURS)]
        style = {"points": "points pt %d ps 1.5" % s.pt, "lines": "lines lw %g" % s.width,
                 "linespoints": "linespoints lw %g pt %d ps 1.3" % (s.width, s.pt)}[s.style]
        dash = " dt %d" % s.dash if s.dash else ""
        plots.append("%s index %d using 1:2 with %s%s lc rgb '%s' title %s"
                     % (here_file(base + ".dat", os.path.dirname(png)), i, style, dash, colour, _quote(s.name)))
    for name, y in refs:
        if _finite(y):
            plots.append("%.10g with lines dt 2 lw 2 lc rgb 'black' title %s" % (y, _quote(name)))
    if not plots:
        lines.append("set label 100 'no data: no run gave a value' at graph 0.5,0.5 center")
        lines.append("set xrange [0:1]; set yrange [0:1]; unset logscale")
        plots = ["2 notitle"]
    lines.append("plot " + ", \\\n     ".join(plots))
    return _draw(base, lines)


def grid_chart(png, title, panels, xticks, yticks, xlabel, ylabel, legend):
    """Categorical grids side by side (a stability map): panels = [(panel title, cells)], cells =
    [(ix, iy, code, label)], code 0 green, 0.5 orange, 1 red; legend: the colours' meaning (subtitle)."""
    base = os.path.splitext(png)[0]
    with open(base + ".dat", "w") as f:
        for p, (_, cells) in enumerate(panels):
            for ix, iy, code, label in cells:
                f.write("%d %d %d %g %s\n" % (p, ix, iy, code, _quote(label)))
    width = 420 + 480 * len(panels)
    lines = [
        *HERE,
        "set terminal pngcairo size %d,560 noenhanced font ',10'" % width,
        "set output %s" % here_file(png, os.path.dirname(png)),
        "set multiplot layout 1,%d title %s font ',11'" % (len(panels), _quote(title + "\n" + legend)),
        "set palette defined (0 '#70c070', 0.5 '#f0a030', 1 '#e05050')",
        "set cbrange [0:1]", "unset colorbox", "unset key",
        "set xrange [-0.5:%g]" % (len(xticks) - 0.5), "set yrange [-0.5:%g]" % (len(yticks) - 0.5),
        "set xtics (%s)" % ", ".join("%s %d" % (_quote(t), i) for i, t in enumerate(xticks)),
        "set ytics (%s)" % ", ".join("%s %d" % (_quote(t), i) for i, t in enumerate(yticks)),
        "set xlabel %s" % _quote(xlabel), "set ylabel %s" % _quote(ylabel),
        "set style fill solid 1.0 border lc rgb 'white'",
    ]
    for p, (name, _) in enumerate(panels):
        dat = here_file(base + ".dat", os.path.dirname(png))
        lines.append("set title %s" % _quote(name))
        lines.append("plot %s using ($1 == %d ? $2 : 1/0):3:(0.48):(0.48):4 with boxxyerror fc palette, \\\n"
                     "     %s using ($1 == %d ? $2 : 1/0):3:5 with labels font ',8'" % (dat, p, dat, p))
    lines.append("unset multiplot")
    return _draw(base, lines)


def _draw(base, lines):
    with open(base + ".gp", "w") as f:
        f.write("\n".join(lines) + "\n")
    if not HAVE_GNUPLOT:
        return False
    r = subprocess.run(["gnuplot", base + ".gp"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        raise RuntimeError("gnuplot failed on %s.gp: %s" % (base, r.stdout.strip()[-500:]))
    return True
