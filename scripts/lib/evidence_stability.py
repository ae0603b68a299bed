"""Evidence stage `stability`: where the falling disk and the rotating disk stay stable, built-in qf9pT against
dlmfsi exact.

Axes (each grid varies two, the others at the base value):
  dt    : multiples of the scene's default step: falling disk 1, 2.5, 5 x 0.2/n (2, 5, 10 x listing 5.1's 0.1/n),
          rotating disk 1, 3, 10 x 0.005 (listing 5.2's step);
  ratio : solid / fluid mesh size h_s/h_f (-sratio): 1/8, 1/2, 1, 2, 8;
  mu    : the solid's shear modulus: 10, 1e3, 1e5;
  gap   : falling disk only, the gap between the disk and the left side wall (-xc R+gap) or the bottom wall
          (-yc R+gap), in fluid cells: 8, 2, 0.5, 0.1.
Outcome of a run: stable, or unstable with the reason: fail (no summary: the run stopped), fail-coupling (the
coupling raised an error, e.g. a folded map), fail-nan, fail-left (falling disk: the disk crossed a wall), area (solid area drift above 1 %), growth (falling
disk: v^2 over the last quarter of the run above 4x its maximum before; rotating disk: l2err(T) > 1). A run
over RUN_TIMEOUT CPU seconds is stopped and recorded as a timeout (too slow to be of use: a finding too).
Error: falling disk |vterm - vref| / |vref| (a deviation, not an error, where mu or the gap changes the
physics); rotating disk l2err against the 1D reference with the same mu and dt.
"""
import csv
import os

from charts import grid_chart
from ffrun import ROOT, Job, fmt, reference_values, relative_error, run_jobs

R = 0.0625


def _params(quick):
    if quick:
        return dict(fd_n=4, fd_T=0.2, rd_n=2, rd_T=0.03, rd_extra=["-n1d", "40", "-sub1d", "2", "-nr1d", "40"],
                    fd_dts=["1", "5"], rd_dts=["1", "10"], ratios=["1", "4"], mus=["1e5"], gaps=["0.25"],
                    timeout=60)
    return dict(fd_n=10, fd_T=0.7, rd_n=2, rd_T=0.25, rd_extra=[], fd_dts=["1", "2.5", "5"], rd_dts=["1", "3", "10"],
                ratios=["0.125", "0.5", "1", "2", "8"], mus=["10", "1e3", "1e5"], gaps=["8", "2", "0.5", "0.1"],
                timeout=60)


def _grids(scene):
    return ["dt-mu", "dt-ratio", "ratio-mu"] + (["sidegap-dt", "bottomgap-dt"] if scene == "falling_disk" else [])


def jobs_for(quick):
    p = _params(quick)
    fd_dt0, rd_dt0 = 0.2 / p["fd_n"], 0.005
    fd_h = 2 * 3.141592653589793 * 0.25 / (8 * p["fd_n"])      # the falling disk's fluid size around the disk
    fd_mu0, rd_mu0 = "%.6g" % (1e4 / 1.3 / 2), "100"
    jobs, member = {}, []

    def point(scene, grid, c, dtf, ratio, mu, gk, gap):
        tag = "__".join([scene, c, dtf, ratio, mu, gk, gap])
        member.append((grid, tag))
        if tag in jobs:
            return
        if scene == "falling_disk":
            args = ["-n", p["fd_n"], "-T", p["fd_T"], "-dt", "%.8g" % (fd_dt0 * float(dtf)), "-sratio", ratio, "-mu", mu]
            if gk != "none":
                args += ["-xc" if gk == "side" else "-yc", "%.8g" % (R + float(gap) * fd_h)]
        else:
            args = ["-n", p["rd_n"], "-T", p["rd_T"], "-dt", "%.8g" % (rd_dt0 * float(dtf)), "-sratio", ratio,
                    "-mu", mu] + p["rd_extra"]
        args = (["-coupling", "builtin", "-qft", "qf9pT"] if c == "builtin" else ["-coupling", c]) + args
        jobs[tag] = Job(tag, os.path.join(ROOT, "edp", scene + ".edp"), args, scene=scene, coupling=c, dtf=dtf,
                        ratio=ratio, mu=mu, gapkind=gk, gap=gap)

    for scene in ("falling_disk", "rotating_disk"):
        mu0 = fd_mu0 if scene == "falling_disk" else rd_mu0
        dts = p["fd_dts"] if scene == "falling_disk" else p["rd_dts"]
        for c in ("builtin", "exact"):
            for d in dts:
                for m in p["mus"]:
                    point(scene, "dt-mu", c, d, "1", m, "none", "0")
                for r in p["ratios"]:
                    point(scene, "dt-ratio", c, d, r, mu0, "none", "0")
            for r in p["ratios"]:           # without 1/8: its runs are the slowest, and dt x ratio has it
                for m in p["mus"]:
                    if r != "0.125":
                        point(scene, "ratio-mu", c, "1", r, m, "none", "0")
            if scene == "falling_disk":
                for d in dts:
                    for g in p["gaps"]:
                        point(scene, "sidegap-dt", c, d, "1", mu0, "side", g)
                        point(scene, "bottomgap-dt", c, d, "1", mu0, "bottom", g)
    # the finest solids first: the longest runs, so that the workers end together
    ordered = sorted(jobs.values(), key=lambda j: j.meta["ratio"] != "0.125")
    return ordered, member, p, dict(fd_mu0=fd_mu0, rd_mu0=rd_mu0, fd_dt0=fd_dt0, rd_dt0=rd_dt0, fd_h=fd_h)


def _classify(job, runs_dir, vref):
    """(status, reason, error, maxarea, growth) of a finished run."""
    log = ""
    path = os.path.join(runs_dir, job.tag, "log.txt")
    if os.path.exists(path):
        with open(path, errors="replace") as f:
            log = f.read()
    if job.timeout:
        return "timeout", "timeout", float("nan"), float("nan"), float("nan")
    scene = job.meta["scene"]
    if scene == "falling_disk":
        err, area = relative_error(job.get("vterm"), vref), job.get("maxarea")
        v = []
        csv_path = os.path.join(runs_dir, job.tag, "falling_disk.csv")
        if os.path.exists(csv_path):
            with open(csv_path) as f:
                v = [float(r["v"]) for r in csv.DictReader(f)]
        if err != err and v and "NaN at step" not in log:
            err = relative_error(v[-1], vref)     # no step inside the averaging window (large steps)
        growth = float("nan")
        if len(v) >= 2:
            k = max(1, int(0.75 * len(v)))
            a, b = max(x * x for x in v[:k]), max(x * x for x in v[k:]) if v[k:] else 0
            growth = b / a if a > 0 else 0
    else:
        err, area, growth = job.get("l2err"), job.get("area"), job.get("l2err")
    reason = ""
    if job.failed or "NaN at step" in log or "coupling failed" in log or "blow-up" in log or "left the channel" in log:
        reason = ("fail-coupling" if "coupling failed" in log else "fail-nan" if "NaN at step" in log
                  else "fail-left" if "left the channel" in log else "fail")
    elif err != err:
        reason = "fail-nan"
    elif area != area or abs(area) > 0.01:
        reason = "area"
    elif scene == "falling_disk" and growth == growth and growth > 4:
        reason = "growth"
    elif scene == "rotating_disk" and growth > 1:
        reason = "growth"
    return ("unstable" if reason else "stable"), (reason or "none"), err, area, growth


def run(out, quick, say, parallel=2, reuse=False):
    ref = reference_values()
    vref = ref["refFallingDiskSlip"]
    jobs, member, p, base = jobs_for(quick)
    runs_dir = os.path.join(out, "runs")
    say("Stability map: %d runs, %d at a time; logs under %s\n" % (len(jobs), parallel, runs_dir))
    run_jobs(jobs, runs_dir, parallel=parallel, cpu_limit=p["timeout"], reuse=reuse, say=say)
    rows = {}
    for j in jobs:
        status, reason, err, area, growth = _classify(j, runs_dir, vref)
        rows[j.tag] = dict(scene=j.meta["scene"], coupling=j.meta["coupling"], dtfactor=j.meta["dtf"],
                           dt=fmt(j.get("dt"), 6), ratio=j.meta["ratio"], mu=j.meta["mu"], gapkind=j.meta["gapkind"],
                           gap_cells=j.meta["gap"], status=status, reason=reason, error=fmt(err, 3),
                           maxarea=fmt(area, 3), growth=fmt(growth, 3), steps=int(j.get("steps", 0) or 0),
                           cpu=fmt(j.get("cpu"), 4), wall=fmt(j.wall, 4))
    cols = list(next(iter(rows.values())).keys())
    with open(os.path.join(out, "stability.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, cols)
        w.writeheader()
        w.writerows(rows.values())

    units = {"ratio": "h_s / h_f", "mu": "mu (solid shear modulus)", "sidegap": "gap to the side wall (fluid cells)",
             "bottomgap": "gap to the bottom wall (fluid cells)"}
    for scene in ("falling_disk", "rotating_disk"):
        dts = p["fd_dts"] if scene == "falling_disk" else p["rd_dts"]
        values = {"dt": dts, "ratio": p["ratios"], "mu": p["mus"], "sidegap": p["gaps"], "bottomgap": p["gaps"]}
        unit = dict(units, dt=("time step / the scene's default 0.2/n (= 2x listing 5.1's 0.1/n)"
                               if scene == "falling_disk" else "time step / 0.005 (listing 5.2's)"))
        for grid in _grids(scene):
            px, py = grid.split("-")
            xs = [v for v in values[px] if not (grid == "ratio-mu" and v == "0.125")]
            ys = [v for v in values[py] if not (grid == "ratio-mu" and v == "0.125")]
            key = {"dt": "dtfactor", "ratio": "ratio", "mu": "mu", "sidegap": "gap_cells", "bottomgap": "gap_cells"}
            panels = []
            for c, name in (("builtin", "built-in qf9pT"), ("exact", "dlmfsi exact")):
                cells = []
                for g, tag in member:
                    r = rows[tag]
                    if g != grid or r["coupling"] != c or r["scene"] != scene:
                        continue
                    ix, iy = xs.index(r[key[px]]) if r[key[px]] in xs else -1, ys.index(r[key[py]]) if r[key[py]] in ys else -1
                    code = {"stable": 0, "timeout": 0.5}.get(r["status"], 1)
                    cells.append((ix, iy, code, r["error"] if r["status"] == "stable" else r["reason"]))
                panels.append((name, sorted(set(cells))))
            grid_chart(os.path.join(out, "%s_%s.png" % (scene, grid)),
                       "%s: stability over %s and %s" % (scene.replace("_", " "), unit[px], unit[py]), panels, xs, ys,
                       unit[px], unit[py], "green: stable (label: the error); red: unstable (the reason); orange: "
                       "stopped after %d CPU s" % p["timeout"])

    say("\nStability map per scene and coupling:\n")
    for scene in ("falling_disk", "rotating_disk"):
        for c in ("builtin", "exact"):
            sel = [r for r in rows.values() if r["scene"] == scene and r["coupling"] == c]
            reasons = {}
            for r in sel:
                if r["status"] == "unstable":
                    reasons[r["reason"]] = reasons.get(r["reason"], 0) + 1
            say("  %-24s %3d points, %3d unstable%s, %d timeout\n" % (
                scene + "," + c, len(sel), sum(reasons.values()),
                " (%s)" % " ".join("%s=%d" % kv for kv in sorted(reasons.items())) if reasons else "",
                sum(r["status"] == "timeout" for r in sel)))
    say("\nUnstable and timed-out points (scene coupling: dt factor, h_s/h_f, mu, gap -> reason):\n")
    for r in rows.values():
        if r["status"] != "stable":
            say("  %-13s %-8s dt x%-3s ratio %-6s mu %-6s %s -> %s\n" % (
                r["scene"], r["coupling"], r["dtfactor"], r["ratio"], r["mu"],
                "gap -" if r["gapkind"] == "none" else "%s gap %s cells" % (r["gapkind"], r["gap_cells"]), r["reason"]))
    say("\nBoundaries (per axis, the others at the base values; ok = stable, else the reason; dt as a multiple of "
        "the scene's default step):\n")
    look = {(r["scene"], r["coupling"], r["dtfactor"], r["ratio"], r["mu"], r["gapkind"], r["gap_cells"]): r
            for r in rows.values()}
    for scene in ("falling_disk", "rotating_disk"):
        mu0 = base["fd_mu0"] if scene == "falling_disk" else base["rd_mu0"]
        dts = p["fd_dts"] if scene == "falling_disk" else p["rd_dts"]
        axes = [("dt", dts, lambda v: (v, "1", mu0, "none", "0")), ("ratio", p["ratios"], lambda v: ("1", v, mu0, "none", "0")),
                ("mu", p["mus"], lambda v: ("1", "1", v, "none", "0"))]
        if scene == "falling_disk":
            axes += [("sidegap", p["gaps"], lambda v: ("1", "1", mu0, "side", v)),
                     ("bottomgap", p["gaps"], lambda v: ("1", "1", mu0, "bottom", v))]
        for c in ("builtin", "exact"):
            for axis, vals, at in axes:
                out_ = []
                for v in vals:
                    r = look.get((scene, c) + at(v))
                    out_.append("%s:%s" % (v, "?" if r is None else "ok" if r["status"] == "stable" else
                                           "timeout" if r["status"] == "timeout" else r["reason"]))
                say("  %-13s %-8s %-9s %s\n" % (scene, c, axis, " ".join(out_)))
    say("\nBase: falling disk n=%s T=%s dt0=%.4g mu0=%s (fluid size around the disk %.4g, vref=%g); rotating disk "
        "n=%s T=%s dt0=%g mu0=%s.\nCharts: %s/*.png; data: %s/stability.csv\n" % (
            p["fd_n"], p["fd_T"], base["fd_dt0"], base["fd_mu0"], base["fd_h"], vref, p["rd_n"], p["rd_T"],
            base["rd_dt0"], base["rd_mu0"], out, out))
