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
