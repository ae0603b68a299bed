#!/usr/bin/env python3
"""check_core.py must fail on each kind of violation: a small core is built in a temporary folder, first clean
(no problem), then with one violation at a time, each of which must be reported by name."""
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
CLEAN = {
    "plugin/core/point.hpp": "#pragma once\nstruct Point { double x, y; };\n",
    "plugin/core/geometry/clip.hpp": '#pragma once\n#include "point.hpp"\nint clip();\n',
    "plugin/core/geometry/clip.cpp": '#include "geometry/clip.hpp"\nint clip() { return 1; }\n',
    "plugin/core/mesh/mesh.hpp": '#pragma once\n#include "geometry/clip.hpp"\nstruct Mesh { int n; };\n',
    "plugin/core/mesh/mesh.cpp": '#include "mesh/mesh.hpp"\n',
    "tests/core/test_x.cpp": '#include "mesh/mesh.hpp"\n',
}
LONG = "int long_one() {\n" + "  int a = 0;\n" * 160 + "  return a;\n}\n"
BIG = "class Big {\n public:\n" + "  int f%d() const { return %d; }\n" * 0 + "".join(
    "  int m%d = %d;\n" % (i, i) for i in range(310)) + "};\n"
CASES = {
    "folder geometry/ may not include mesh/": {"plugin/core/geometry/clip.cpp": '#include "geometry/clip.hpp"\n#include "mesh/mesh.hpp"\n'},
    "is not a core header written from plugin/core": {"plugin/core/mesh/mesh.cpp": '#include "mesh.hpp"\n'},
    "write it from plugin/core": {"tests/core/test_x.cpp": '#include "clip.hpp"\n'},
    "include cycle": {"plugin/core/mesh/a.hpp": '#pragma once\n#include "mesh/b.hpp"\n',
                      "plugin/core/mesh/b.hpp": '#pragma once\n#include "mesh/a.hpp"\n'},
    "function long_one has": {"plugin/core/geometry/clip.cpp": '#include "geometry/clip.hpp"\n' + LONG},
    "class Big has": {"plugin/core/geometry/big.hpp": "#pragma once\n" + BIG},
    "is not in the rule": {"plugin/core/attic/old.hpp": "#pragma once\n"},
}


def run(files):
    with tempfile.TemporaryDirectory() as root:
        for path, text in files.items():
            os.makedirs(os.path.dirname(os.path.join(root, path)), exist_ok=True)
            with open(os.path.join(root, path), "w") as f:
                f.write(text)
        p = subprocess.run([sys.executable, os.path.join(HERE, "check_core.py"), root], capture_output=True, text=True)
        return p.returncode, p.stdout


failures = 0
code, out = run(CLEAN)
if code != 0:
    print("the clean tree was refused:\n" + out)
    failures += 1
for expected, change in CASES.items():
    code, out = run({**CLEAN, **change})
    if code == 0 or expected not in out:
        print(f"not caught: '{expected}' (exit {code}):\n{out}")
        failures += 1
print(f"catches: {len(CASES)} violations, {failures} failure(s)")
sys.exit(1 if failures else 0)
