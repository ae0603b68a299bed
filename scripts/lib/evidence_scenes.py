"""Evidence stage `scenes`: the paper's scenes over meshes and couplings, and what their modelling costs.

Accuracy against time: every scene over meshes (-n) and couplings (built-in qf9pT and qf5pT, dlmfsi exact
and quadrature); the figure's error against the run's CPU time, one chart per scene, with the Pareto front
(runs not beaten in both error and time):
  falling disk : |vterm - vref| / |vref|, vref the body-fitted reference (edp/reference/values.idp);
  rotating disk: l2err, the relative L2 distance to the 1D axisymmetric reference at T;
  FSI-3        : y-amplitude and frequency of the tip against Turek-Hron (the larger error for the front).
Modelling choices, at one mesh per scene: fixed against remeshed fluid mesh (-remesh 1), AA/BB assembled
once against every step (-reassemble 1), and the listing as printed (built-in qf9pT, the printed gradient
product, BA by mapt, AA/BB every step, a new LU of the whole system every step, and for listings 5.1 and 5.3
the fluid mesh rebuilt every step): the run time split into coupling, solve and the first AA/BB assembly,
the CPU time per step -> modelling.md and time_per_step.csv.
"""
import csv
import os

from charts import Series, chart
from ffrun import ROOT, Job, fmt, reference_values, relative_error, run_jobs

LISTING = ["-coupling", "builtin", "-qft", "qf9pT", "-gradient", "listing", "-bamapt", "1", "-reassemble", "1",
           "-solver", "umfpack"]
COLOURS = {"qf9pT": "#c03030", "qf5pT": "#e08020", "exact": "#208020", "quadrature": "#3050c0"}


def _cargs(c):
    return ["-coupling", "builtin", "-qft", c] if c.startswith("qf") else ["-coupling", c]


def _sizes(quick):
    if quick:
        return dict(fd_ns=[4, 6], fd_mid=6, fd_args=["-T", "0.1"], rd_ns=[2, 3], rd_mid=3,
                    rd_args=["-T", "0.05", "-n1d", "40", "-sub1d", "2", "-nr1d", "40"],
                    f3_ns=["0.5"], f3_args=["-T", "0.06", "-tstat", "0"], f3_extra=[], f3_short=["-T", "0.06"],
                    timeout=120)
    # the flag swings from t ~ 1.2: amplitude and frequency over the last 3 periods after t = 3
    return dict(fd_ns=[8, 12, 18], fd_mid=12, fd_args=[], rd_ns=[2, 3, 5], rd_mid=5, rd_args=[],
                f3_ns=["1"], f3_args=["-T", "4", "-tstat", "3"], f3_extra=[("exact", "0.75")],
                f3_short=["-T", "0.3", "-tstat", "0"], timeout=900)


def jobs_for(quick):
    z = _sizes(quick)
    edp = lambda s: os.path.join(ROOT, "edp", s + ".edp")
    jobs = []
    add = lambda tag, scene, args, **meta: jobs.append(Job(tag, edp(scene), args, scene=scene, **meta))
    # FSI-3 first: the longest runs, so that the parallel workers end together
    for n in z["f3_ns"]:
        for c in ("exact", "qf9pT", "qf5pT"):
            add("fsi3__%s__%s" % (c, n), "fsi3", _cargs(c) + ["-n", n] + z["f3_args"], coupling=c, n=n, variant="base")
    for c, n in z["f3_extra"]:
        add("fsi3__%s__%s" % (c, n), "fsi3", _cargs(c) + ["-n", n] + z["f3_args"], coupling=c, n=n, variant="base")
    for scene, ns, extra in (("falling_disk", z["fd_ns"], z["fd_args"]), ("rotating_disk", z["rd_ns"], z["rd_args"])):
        for n in ns:
            for c in ("qf9pT", "qf5pT", "exact", "quadrature"):
                add("%s__%s__%s" % (scene, c, n), scene, _cargs(c) + ["-n", n] + extra, coupling=c, n=n, variant="base")
    fd, rd = z["fd_mid"], z["rd_mid"]
    add("falling_disk__qf9pT__%s__listing" % fd, "falling_disk", LISTING + ["-remesh", "1", "-n", fd] + z["fd_args"],
        coupling="qf9pT", n=fd, variant="listing")
    add("rotating_disk__qf9pT__%s__listing" % rd, "rotating_disk", LISTING + ["-n", rd] + z["rd_args"],
        coupling="qf9pT", n=rd, variant="listing")
    for c in ("qf9pT", "exact"):
        add("falling_disk__%s__%s__remesh" % (c, fd), "falling_disk", _cargs(c) + ["-n", fd, "-remesh", "1"] + z["fd_args"],
            coupling=c, n=fd, variant="remesh")
        add("falling_disk__%s__%s__reassemble" % (c, fd), "falling_disk",
            _cargs(c) + ["-n", fd, "-reassemble", "1"] + z["fd_args"], coupling=c, n=fd, variant="reassemble")
        add("rotating_disk__%s__%s__reassemble" % (c, rd), "rotating_disk",
            _cargs(c) + ["-n", rd, "-reassemble", "1"] + z["rd_args"], coupling=c, n=rd, variant="reassemble")
    # FSI-3's modelling rows on a shorter run (cost per step; no amplitude)
    n3 = z["f3_ns"][0]
    for tag, args in (("short", _cargs("qf9pT")), ("short-remesh", _cargs("qf9pT") + ["-remesh", "1"]),
                      ("short-reassemble", _cargs("qf9pT") + ["-reassemble", "1"]),
                      ("short-listing", LISTING + ["-remesh", "1"])):
        add("fsi3__qf9pT__%s__%s" % (n3, tag), "fsi3", args + ["-n", n3] + z["f3_short"], coupling="qf9pT", n=n3,
            variant=tag)
    add("fsi3__exact__%s__short" % n3, "fsi3", _cargs("exact") + ["-n", n3] + z["f3_short"], coupling="exact", n=n3,
        variant="short")
    return jobs, z


def _figures(job, ref):
    """(figure, value, reference, error) rows of a finished job."""
    scene = job.meta["scene"]
    if scene == "falling_disk":
        vref = job.get("vref")
        if vref != vref:
            vref = ref["refFallingDiskNoslip" if job.get("sides", "slip") == "noslip" else "refFallingDiskSlip"]
        return [("vterm", job.get("vterm"), vref, relative_error(job.get("vterm"), vref))]
    if scene == "rotating_disk":
        return [("l2err", job.get("l2err"), "1D", job.get("l2err"))]
    return [(f, job.get(f), ref[k], relative_error(job.get(f), ref[k]))
            for f, k in (("yamp", "refFsi3Yamp"), ("yfreq", "refFsi3Yfreq"))]


def _status(job, error):
    if job.timeout:
        return "timeout"
    if job.failed:
        return "failed"
    return "ok" if error == error else "nofigure"


def run(out, quick, say, parallel=2, reuse=False):
    ref = reference_values()
    jobs, z = jobs_for(quick)
    say("Scene evidence: %d runs, %d at a time; logs under %s/runs\n" % (len(jobs), parallel, out))
    run_jobs(jobs, os.path.join(out, "runs"), parallel=parallel, cpu_limit=z["timeout"], reuse=reuse, say=say)

    rows = []
    for j in jobs:
        for fig, value, refval, err in _figures(j, ref):
            rows.append(dict(scene=j.meta["scene"], coupling=j.meta["coupling"], n=j.meta["n"],
                             variant=j.meta["variant"], figure=fig, value=fmt(value, 8), reference=fmt(refval, 6),
                             relerr=fmt(err, 4), cpu=fmt(j.get("cpu"), 5), abseconds=fmt(j.get("abseconds"), 5),
                             solveseconds=fmt(j.get("solveseconds"), 5), aabbseconds=fmt(j.get("aabbseconds"), 5),
                             steps=int(j.get("steps", 0) or 0), status=_status(j, err), pareto=0,
                             wall=fmt(j.wall, 4), _err=err, _cpu=j.get("cpu"), _job=j))
    # Pareto front per scene over the base runs, the error being the largest over the scene's figures
    runs = {}
    for r in rows:
        if r["variant"] == "base" and r["status"] == "ok":
            key = (r["scene"], r["coupling"], r["n"])
            runs[key] = (r["_cpu"], max(r["_err"], runs.get(key, (0, 0))[1]))
    front = {k for k, (t, e) in runs.items()
             if not any(k2[0] == k[0] and k2 != k and t2 <= t and e2 <= e and (t2 < t or e2 < e)
                        for k2, (t2, e2) in runs.items())}
    for r in rows:
        r["pareto"] = int((r["scene"], r["coupling"], r["n"]) in front and r["variant"] == "base")
    cols = ["scene", "coupling", "n", "variant", "figure", "value", "reference", "relerr", "cpu", "abseconds",
            "solveseconds", "aabbseconds", "steps", "status", "pareto", "wall"]
    with open(os.path.join(out, "scenes.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, cols, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)

    titles = {"falling_disk": "Falling disk: |vterm - vref| / |vref| against CPU time (vref: body-fitted, %g)"
              % ref["refFallingDiskSlip"],
              "rotating_disk": "Rotating disk: relative L2 error at T against CPU time (1D reference)",
              "fsi3": "FSI-3: error of the tip's y-amplitude and frequency against CPU time (Turek-Hron)"}
    for scene in ("falling_disk", "rotating_disk", "fsi3"):
        sel = [r for r in rows if r["scene"] == scene and r["variant"] == "base" and r["status"] == "ok"]
        series, labels = [], []
        for c in ("qf9pT", "qf5pT", "exact", "quadrature"):
            for fig, pt in (("vterm", 7), ("l2err", 7), ("yamp", 7), ("yfreq", 5)):
                pts = [(r["_cpu"], max(r["_err"], 1e-16)) for r in sel if r["coupling"] == c and r["figure"] == fig]
                if pts:
                    name = ("built-in " + c if c.startswith("qf") else "dlmfsi " + c) + \
                        (" (%s)" % fig if scene == "fsi3" else "")
                    series.append(Series(name, pts, style="points", colour=COLOURS[c], pt=pt))
                    labels += [(r["_cpu"], max(r["_err"], 1e-16), "n=%s" % r["n"])
                               for r in sel if r["coupling"] == c and r["figure"] == fig]
        pareto = sorted(runs[k] for k in front if k[0] == scene)
        series.append(Series("Pareto front (not beaten in both error and time)", pareto, style="lines",
                             colour="black", dash=2, width=1.5))
        chart(os.path.join(out, scene + "_error_vs_time.png"), titles[scene],
              "CPU time of the run (s)", "relative error", series, logx=True, logy=True, labels=labels)

    say("\nScene evidence: figure error against CPU time (%s/scenes.csv; wall times beside)\n" % out)
    for r in rows:
        say("  %-13s %-10s n=%-5s %-17s %-6s %12s  err %-10s cpu %7s s  wall %7s s  %s%s\n" % (
            r["scene"], r["coupling"], r["n"], r["variant"], r["figure"], r["value"], r["relerr"], r["cpu"],
            r["wall"], r["status"], "  PARETO" if r["pareto"] else ""))
    say("\nPareto winners per scene (not beaten in both error and CPU time):\n")
    for scene in ("falling_disk", "rotating_disk", "fsi3"):
        win = sorted((t, e, k) for k, (t, e) in runs.items() if k in front and k[0] == scene)
        say("  %s: %s\n" % (scene, "; ".join("%s n=%s (%.3g cpu-s, err %.3g)" % (k[1], k[2], t, e)
                                              for t, e, k in win) or "none"))
    _modelling(out, jobs, z, ref, quick, parallel, say)


def _modelling(out, jobs, z, ref, quick, parallel, say):
    by_tag = {j.tag: j for j in jobs}
    fd, rd, n3 = z["fd_mid"], z["rd_mid"], z["f3_ns"][0]

    def per_step(tag):
        j = by_tag.get(tag)
        return float("nan") if j is None or j.failed or not j.get("steps") else j.get("cpu") / j.get("steps")

    def error(tag):
        j = by_tag.get(tag)
        return float("nan") if j is None or j.failed else _figures(j, ref)[0][3]

    def row(label, tag):
        j = by_tag[tag]
        return "| %s | %s/%s | %s | %s | %s | %s | %s | %s |" % (
            label, fmt(j.wall, 3), fmt(j.get("cpu"), 4), fmt(per_step(tag), 4), fmt(j.get("abseconds"), 3),
            fmt(j.get("solveseconds"), 3), fmt(j.get("aabbseconds"), 3), int(j.get("steps", 0) or 0), fmt(error(tag), 3))

    lines = ["# What the scenes model, and what it costs", "",
             "Generated by `make evidence`%s, %d runs at a time (wall times include the other runs' share of the "
             "cores). Columns: wall / CPU seconds of the whole run; CPU seconds per time step (set-up included); "
             "CPU seconds of the coupling assembly and of the saddle-point solve, summed over the steps; CPU seconds "
             "of the first assembly of AA (fluid) and BB (solid); steps; the relative error of the scene's figure "
             "(falling disk vterm, rotating disk l2err, FSI-3 y-amplitude: nan on the short runs)."
             % (" QUICK=1 (tiny sizes: the numbers mean nothing)" if quick else "", parallel), "",
             "-reassemble 1 assembles AA and BB at every step; -remesh 1 rebuilds the fluid mesh around the mapped "
             "solid every step (the listings' way) and interpolates the fluid state. The listing as printed: "
             "built-in qf9pT with the printed product Grad(Xo,Yo)*Grad(u,v), BA by mapt, AA and BB every step, a new "
             "LU of the whole system every step and, for listings 5.1 and 5.3, the remeshed fluid mesh."]
    head = ["| choice | wall/CPU s | CPU s/step | coupling CPU s | solve CPU s | AA+BB once CPU s | steps | rel. error |",
            "|---|---|---|---|---|---|---|---|"]
    lines += ["", "## Falling disk (n=%s)" % fd, ""] + head + [
        row("listing as printed (remeshed)", "falling_disk__qf9pT__%s__listing" % fd)]
    for c in ("qf9pT", "exact"):
        lines += [row("%s, fixed mesh, AA/BB once%s" % (c, " (dlmfsi default)" if c == "exact" else ""),
                      "falling_disk__%s__%s" % (c, fd)),
                  row("%s, fixed mesh, AA/BB every step" % c, "falling_disk__%s__%s__reassemble" % (c, fd)),
                  row("%s, fluid mesh rebuilt every step" % c, "falling_disk__%s__%s__remesh" % (c, fd))]
    lines += ["", "## Rotating disk (n=%s)" % rd, ""] + head + [
        row("listing as printed", "rotating_disk__qf9pT__%s__listing" % rd)]
    for c in ("qf9pT", "exact"):
        lines += [row("%s, fixed mesh, AA/BB once%s" % (c, " (dlmfsi default)" if c == "exact" else ""),
                      "rotating_disk__%s__%s" % (c, rd)),
                  row("%s, fixed mesh, AA/BB every step" % c, "rotating_disk__%s__%s__reassemble" % (c, rd))]
    lines += ["", "The rotating disk's fluid mesh contains the interface r = R1 and the geometry does not change: "
              "nothing to remesh.",
              "", "## FSI-3 (n=%s; the modelling rows on a short run, %s)" % (n3, " ".join(z["f3_short"])), ""] + head + [
        row("exact, fixed mesh, AA/BB once (dlmfsi default), long run", "fsi3__exact__%s" % n3),
        row("listing as printed (remeshed), short run", "fsi3__qf9pT__%s__short-listing" % n3),
        row("exact, fixed mesh, AA/BB once (dlmfsi default), short run", "fsi3__exact__%s__short" % n3),
        row("qf9pT, fixed mesh, short run", "fsi3__qf9pT__%s__short" % n3),
        row("qf9pT, fixed mesh, AA/BB every step, short run", "fsi3__qf9pT__%s__short-reassemble" % n3),
        row("qf9pT, fluid mesh rebuilt every step, short run", "fsi3__qf9pT__%s__short-remesh" % n3)]
    with open(os.path.join(out, "modelling.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    say("\nModelling choices: %s/modelling.md\n" % out + "\n".join(lines) + "\n")

    tps = [("falling_disk", "falling_disk__qf9pT__%s__listing" % fd, "falling_disk__exact__%s" % fd),
           ("rotating_disk", "rotating_disk__qf9pT__%s__listing" % rd, "rotating_disk__exact__%s" % rd),
           ("fsi3", "fsi3__qf9pT__%s__short-listing" % n3, "fsi3__exact__%s__short" % n3)]
    with open(os.path.join(out, "time_per_step.csv"), "w") as f:
        f.write("scene,listing_s_per_step,dlmfsi_s_per_step,ratio,listing_run,dlmfsi_run\n")
        say("\nTime per step (CPU s / steps) at equal resolution: the listing as printed against the dlmfsi default\n")
        say("  %-14s %26s %22s %7s\n" % ("scene", "listing as printed s/step", "dlmfsi default s/step", "ratio"))
        for scene, a_tag, b_tag in tps:
            a, b = per_step(a_tag), per_step(b_tag)
            ratio = a / b if b == b and a == a and b > 0 else float("nan")
            f.write("%s,%s,%s,%s,%s,%s\n" % (scene, fmt(a, 4), fmt(b, 4), fmt(ratio, 3), a_tag, b_tag))
            say("  %-14s %26s %22s %7s\n" % (scene, fmt(a, 4), fmt(b, 4), fmt(ratio, 3)))
