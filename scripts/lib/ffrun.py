"""Running the scenes and reading what they print: shared by the drivers under scripts/.

A scene's last line is its summary, ``dlmfsi-result scene=... key=value ... seconds=<wall> cpu=<cpu>``;
the reference figures live once in edp/reference/values.idp as ``real NAME = VALUE;`` lines.
"""
import os
import re
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
FF = os.path.join(ROOT, "bin", "ff")


def reference_values(path=os.path.join(ROOT, "edp", "reference", "values.idp")):
    """The `real NAME = VALUE;` lines of values.idp as a dict NAME -> float."""
    values = {}
    with open(path) as f:
        for line in f:
            m = re.match(r"\s*real\s+(\w+)\s*=\s*([-+0-9.eE]+)\s*;", line)
            if m:
                values[m.group(1)] = float(m.group(2))
    return values


def parse_result(line):
    """A `dlmfsi-result key=value ...` line as a dict; numbers as floats (nan for nan), words as str."""
    fields = {}
    for word in line.split()[1:]:
        if "=" not in word:
            continue
        key, value = word.split("=", 1)
        try:
            fields[key] = float(value)
        except ValueError:
            fields[key] = value
    return fields


def run_scene(script, args, log_path, progress=True, label=""):
    """Run `bin/ff script args`, the whole output to log_path; progress lines ("  step k/N ...") echoed
    to stderr with the label. Returns (summary dict or None, exit code, wall seconds)."""
    cmd = [FF, script] + [str(a) for a in args]
    t0 = time.time()
    summary = None
    with open(log_path, "w") as log:
        log.write("# " + " ".join(cmd) + "\n")
        proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                errors="replace", cwd=ROOT)
        for line in proc.stdout:
            log.write(line)
            if line.startswith("dlmfsi-result"):
                summary = parse_result(line)
            elif progress and line.startswith("  step "):
                sys.stderr.write("    %s%s" % (label + ": " if label else "", line.strip() + "\n"))
        rc = proc.wait()
    return summary, rc, time.time() - t0


def fmt(value, digits=4):
    """A figure for a table: nan as 'nan', strings as they are, floats with `digits` significant digits."""
    if isinstance(value, str):
        return value
    if value is None or value != value:
        return "nan"
    return "%.*g" % (digits, value)


class Job:
    """One FreeFEM run of a driver: a tag (its folder name under the runs folder), a script, options."""

    def __init__(self, tag, script, args, **meta):
        self.tag, self.script, self.args, self.meta = tag, script, [str(a) for a in args], meta
        self.summary, self.rc, self.wall, self.timeout = None, None, None, False

    @property
    def failed(self):
        return self.summary is None or self.rc != 0

    def get(self, key, default=float("nan")):
        return default if self.summary is None else self.summary.get(key, default)


def read_log(log_path):
    """A log's text, "" when there is no log."""
    if not os.path.exists(log_path):
        return ""
    with open(log_path, errors="replace") as log:
        return log.read()


def last_summary(text):
    """The last `dlmfsi-result` line of a log's text as a dict, or None."""
    lines = [l for l in text.splitlines() if l.startswith("dlmfsi-result")]
    return parse_result(lines[-1]) if lines else None


def run_jobs(jobs, runs_dir, parallel=2, cpu_limit=None, out_option=True, reuse=False, resume=False,
             say=sys.stderr.write):
    """Run the jobs, `parallel` at a time, each in runs_dir/<tag>/ (log.txt; with out_option, `-out` that
    folder). cpu_limit: CPU seconds per process (RLIMIT_CPU, so that the other jobs on the machine do not
    count; a wall cap of 4x stops a process that waits), recorded as job.timeout. reuse: read the logs of
    an earlier run instead of running (a job without a log gets no summary); resume: the same for the jobs
    whose log has a summary line, the others are run. Fills job.summary, rc, wall, timeout; returns the
    jobs."""
    import concurrent.futures
    import resource

    def limit():
        if cpu_limit:
            resource.setrlimit(resource.RLIMIT_CPU, (int(cpu_limit), int(cpu_limit) + 5))

    def one(job):
        d = os.path.join(runs_dir, job.tag)
        log_path = os.path.join(d, "log.txt")
        kept = reuse or (resume and last_summary(read_log(log_path)) is not None)
        if not kept:
            os.makedirs(d, exist_ok=True)
            cmd = [FF, job.script] + job.args + (["-out", d] if out_option else [])
            t0 = time.time()
            with open(log_path, "w") as log:
                log.write("# " + " ".join(cmd) + "\n")
                log.flush()
                try:
                    job.rc = subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                            cwd=ROOT, preexec_fn=limit,
                                            timeout=4 * cpu_limit if cpu_limit else None).returncode
                except subprocess.TimeoutExpired:
                    job.rc = 124
            job.wall = time.time() - t0
        text = read_log(log_path)
        job.summary = last_summary(text)
        if kept:
            job.rc = 0 if job.summary else 1
            job.wall = job.get("seconds")
        # over the CPU cap: SIGXCPU/SIGKILL (the plugin re-run's parent then prints "Killed" and exits 1)
        job.timeout = job.rc in (124, -9, -24, 137, 152) or "\nKilled" in text
        say("  %s %s (%.1f s, exit %s)\n" % ("kept" if kept else "done", job.tag, job.wall or 0, job.rc))
        return job

    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, parallel)) as pool:
        return list(pool.map(one, jobs))


def relative_error(value, reference):
    """|value - reference| / |reference|, nan when either is nan or missing."""
    if value is None or reference is None or value != value or reference != reference or reference == 0:
        return float("nan")
    return abs(value - reference) / abs(reference)
