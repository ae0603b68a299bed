"""What the convergence studies (scripts/study-*) share: the rate fitted to errors against h, and a gnuplot
chart written next to its script."""
import math
import os
import shutil
import subprocess
import sys

from charts import HERE, here_file  # noqa: F401  (here_file: the studies' data paths in their charts)


def lsq_rate(hs, errs):
    """Slope of log|err| against log h (least squares) and the constant C of |err| = C h^slope; nan with
    fewer than 2 usable points."""
    pts = [(math.log(h), math.log(abs(e))) for h, e in zip(hs, errs) if e == e and e != 0]
    if len(pts) < 2:
        return float("nan"), float("nan")
    n = len(pts)
    mx = sum(p[0] for p in pts) / n
    my = sum(p[1] for p in pts) / n
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    sxy = sum((p[0] - mx) * (p[1] - my) for p in pts)
    slope = sxy / sxx
    return slope, math.exp(my - slope * mx)


def gnuplot(out, name, body, size=(900, 600)):
    """out/name.png from out/name.gp (a PNG header, then body); a failed gnuplot is a note, not an error.
    The header sets `here`, the script's own folder, and writes the PNG there: body names its data files
    here_file(path, out), so `gnuplot out/name.gp` redraws the chart from any folder."""
    gp = os.path.join(out, name + ".gp")
    with open(gp, "w") as f:
        f.write("\n".join(HERE) + "\n")
        f.write("set terminal pngcairo size %d,%d font ',10'\n" % size)
        f.write(f"set output here.'/{name}.png'\n")
        f.write("set datafile separator ','\nset grid\n")
        f.write(body + "\n")
    if shutil.which("gnuplot") is None:
        print(f"note: gnuplot not found, {gp} not drawn", file=sys.stderr)
        return
    r = subprocess.run(["gnuplot", gp], capture_output=True, text=True)
    if r.returncode != 0:
        print(f"note: gnuplot failed on {gp}: {r.stderr.strip()[:200]}", file=sys.stderr)
