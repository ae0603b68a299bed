"""Evidence stage `coupling`: the coupling matrix alone (edp/evidence/coupling_accuracy.edp).

1. Error of lambda' B u against the assembly time, every method (built-in rules and orders, dlmfsi
   quadrature tolerances, dlmfsi exact), kinked and smooth data, P1 and P1b maps, one mesh pair each.
2. Convergence in h_f at fixed h_s/h_f = 1/4, 1, 4 (smooth data, P1 map): least-squares rates against the
   rates predicted for quadrature-based coupling (Boffi-Credali-Gastaldi: mass about h^1.5, gradient
   about h^0.5 + h_s/h_f). dlmfsi exact is the reference of every error (exact to round-off).
"""
import csv
import math
import os
import subprocess

from charts import Series, chart
from ffrun import FF, ROOT

HEADER = "data,map,nf,solid_triangles,hf,hs,ratio,method,param,err_mass,err_gradient,seconds"
SCRIPT = os.path.join(ROOT, "edp", "evidence", "coupling_accuracy.edp")
PREDICTED = {"mass": "1.5", "gradient": "0.5 (+h_s/h_f)"}


def _run(args, csv_path):
    r = subprocess.run([FF, SCRIPT] + [str(a) for a in args] + ["-csv", csv_path], cwd=ROOT,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        raise RuntimeError("coupling_accuracy.edp %s failed:\n%s" % (" ".join(map(str, args)), r.stdout[-2000:]))


def _rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def _slope(points):
    """Least-squares slope of log(e) against log(h)."""
    xs = [math.log(h) for h, _ in points]
    ys = [math.log(e) for _, e in points]
    n = len(xs)
    d = n * sum(x * x for x in xs) - sum(xs) ** 2
    return (n * sum(x * y for x, y in zip(xs, ys)) - sum(xs) * sum(ys)) / d


def run(out, quick, say):
    acc = os.path.join(out, "coupling_accuracy.csv")
    conv = os.path.join(out, "coupling_convergence.csv")
    if os.environ.get("REUSE", "0") == "1" and os.path.exists(acc) and os.path.exists(conv):
        say("REUSE=1: the tables and charts from %s and %s\n" % (acc, conv))
    else:
        _run_all(out, quick, acc, conv)
    _report(out, acc, conv, say)


def _run_all(out, quick, acc, conv):
    with open(acc, "w") as f:
        f.write(HEADER + "\n")
    nf, methods = (6, "fast") if quick else (16, "all")
    for data in ("kinked", "smooth"):
        for mapkind in ("p1", "p1b"):
            _run(["-data", data, "-map", mapkind, "-nf", nf, "-methods", methods], acc)
    # The solid disk (radius 0.6 in [-1,1]^2) needs 8 boundary segments at least, so h_s = 4 h_f only holds
    # from nf = 32 on: ratio 4 runs finer meshes.
    with open(conv, "w") as f:
        f.write(HEADER + "\n")
    for ratio in ("0.25", "1", "4"):
        sizes = (32, 64) if quick and ratio == "4" else (4, 8) if quick else \
            (32, 64, 128, 256) if ratio == "4" else (8, 16, 32, 64)
        for n in sizes:
            _run(["-data", "smooth", "-map", "p1", "-nf", n, "-ratio", ratio, "-methods", "fast"], conv)


def _report(out, acc, conv, say):
    rows = _rows(acc)
    say("Coupling accuracy vs time (relative error of lambda' B u; reference: dlmfsi exact):\n")
    for r in rows:
        say("  %-7s %-4s %-18s %-14s mass %9.2e  gradient %9.2e  %8.4f s\n" % (
            r["data"], r["map"], r["method"], r["param"], float(r["err_mass"]), float(r["err_gradient"]),
            float(r["seconds"])))

    # rates per ratio, method and term
    series = {}
    for r in _rows(conv):
        if r["method"] == "dlmfsi-exact":
            continue
        key = (float(r["ratio"]), r["method"] + " " + r["param"])
        for term in ("mass", "gradient"):
            e = float(r["err_" + term])
            if e > 0:
                series.setdefault(key + (term,), []).append((float(r["hf"]), e))
    rates = os.path.join(out, "coupling_rates.csv")
    with open(rates, "w") as f:
        f.write("ratio,method,term,rate,predicted\n")
        for (ratio, method, term), pts in sorted(series.items()):
            if len(pts) >= 2:
                f.write("%g,%s,%s,%.2f,%s\n" % (ratio, method, term, _slope(pts), PREDICTED[term]))
    say("\nConvergence rates in h_f at fixed h_s/h_f (smooth data; predicted for quadrature-based coupling:\n"
        "mass about h^1.5, gradient about h^0.5 + h_s/h_f; dlmfsi exact is the reference, exact to round-off):\n")
    for r in _rows(rates):
        say("  %-6s %-28s %-9s %-6s %s\n" % (r["ratio"], r["method"], r["term"], r["rate"], r["predicted"]))

    # charts: error against time per case; errors below 1e-16 drawn at 1e-16
    floor = lambda e: max(float(e), 1e-16)
    for data in ("kinked", "smooth"):
        for mapkind in ("p1", "p1b"):
            for term in ("mass", "gradient"):
                sel = [r for r in rows if r["data"] == data and r["map"] == mapkind]
                ser, labels = [], []
                for method, name, colour, pt in (
                        ("builtin", "built-in (qft rule / qforder)", "#c03030", 7),
                        ("dlmfsi-quadrature", "dlmfsi quadrature (tol)", "#3050c0", 5),
                        ("dlmfsi-exact", "dlmfsi exact (the reference; drawn at 1e-16)", "#208020", 9)):
                    pts = [(float(r["seconds"]), floor(r["err_" + term])) for r in sel if r["method"] == method]
                    ser.append(Series(name, pts, style="points", colour=colour, pt=pt))
                    if method != "dlmfsi-exact":
                        labels += [(float(r["seconds"]), floor(r["err_" + term]), r["param"])
                                   for r in sel if r["method"] == method]
                chart(os.path.join(out, "accuracy_%s_%s_%s.png" % (data, mapkind, term)),
                      "Coupling %s term, %s data, %s map: error against assembly time" % (term, data, mapkind),
                      "assembly time of both terms (CPU s)", "relative error of lambda' B u", ser,
                      logx=True, logy=True, labels=labels)
    conv_rows = _rows(conv)
    for term in ("mass", "gradient"):
        ser = []
        for m, q, dash in (("builtin", "qf9pT", None), ("dlmfsi-quadrature", "tol=0.015", 2)):
            for i, ratio in enumerate(("0.25", "1", "4")):
                pts = sorted((float(r["hf"]), float(r["err_" + term])) for r in conv_rows
                             if r["method"] == m and r["param"] == q and float(r["ratio"]) == float(ratio))
                name = "%s %s, h_s/h_f = %s" % ("built-in" if m == "builtin" else "dlmfsi quadrature", q, ratio)
                ser.append(Series(name, pts, colour=["#c03030", "#208020", "#3050c0"][i], dash=dash))
        chart(os.path.join(out, "convergence_%s.png" % term),
              "Coupling %s term, smooth data: error against the fluid mesh size at fixed h_s/h_f" % term,
              "fluid mesh size h_f (the domain is [-1,1]^2)", "relative error of lambda' B u", ser,
              logx=True, logy=True)
    say("\nCharts: %s/accuracy_*.png %s/convergence_*.png\n" % (out, out))
