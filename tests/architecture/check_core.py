#!/usr/bin/env python3
"""The core's architecture, checked from its sources (docs/architecture.md states the rules):

1. every include of a core header is written from plugin/core ("geometry/clip.hpp") and names a file that exists;
2. a folder includes only itself, the files at the core's top and the folders below it (FOLDERS);
3. no cycle between units (a unit: x.hpp with x.cpp; unit a uses unit b when x.hpp or x.cpp includes b's header);
4. no function longer than 150 lines, no class longer than 300.

Usage: check_core.py [REPO_ROOT]; prints each violation and exits 1 when there is one.
"""
import os
import re
import sys

# Each folder with the folders it may include (besides itself and the core's top files), lowest first.
FOLDERS = {
    "parallel": [],
    "geometry": [],
    "sparse": ["parallel"],
    "mesh": ["geometry", "parallel"],
    "fe": ["mesh", "geometry", "parallel"],
    "solid": ["fe", "mesh", "sparse", "geometry", "parallel"],
    "map": ["fe", "mesh", "geometry", "parallel"],
    "sides": ["map", "fe", "mesh", "sparse", "geometry", "parallel"],
    "integration": ["sides", "map", "fe", "mesh", "sparse", "geometry", "parallel"],
    "coupling": ["integration", "sides", "map", "fe", "mesh", "sparse", "geometry", "parallel"],
    "transfer": ["sides", "map", "fe", "mesh", "sparse", "geometry", "parallel"],
}
MAX_FUNCTION_LINES = 150
MAX_CLASS_LINES = 300
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def folder_of(rel):
    return rel.split("/")[0] if "/" in rel else ""


def strip_comments_and_strings(text):
    """The text with comments, string and character literals blanked (newlines kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("\n" * text.count("\n", i, j))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(" ")
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def long_blocks(path):
    """(kind, name, first line, lines) of the functions and classes over the limits in one source file."""
    text = strip_comments_and_strings(open(path).read())
    found = []
    # a block opened at depth d: its head is the text since the last ; { or } at that depth
    stack = []  # (kind, name, line) per open brace
    head_start, line = 0, 1
    for i, c in enumerate(text):
        if c == "\n":
            line += 1
        elif c == "{":
            head = text[head_start:i]
            inside_function = any(kind == "function" for kind, _, _ in stack)
            kind, name = "block", ""
            if not inside_function:
                m = re.search(r"\b(class|struct|union)\s+(\w+)[^;()]*$", head)
                f = re.search(r"([\w:~<>]+)\s*\([^;]*\)[^;(){}]*$", head)
                if m and not f:
                    kind, name = "class", m.group(2)
                elif f and not re.search(r"\b(if|for|while|switch|catch|return)\s*\(", head) and "=" not in head.split("(")[0]:
                    kind, name = "function", f.group(1)
            first = line - head.strip("\n").count("\n") if head.strip() else line
            first = line - len(head.rstrip().split("\n")) + 1 if head.strip() else line
            stack.append((kind, name, first))
            head_start = i + 1
        elif c == "}":
            if stack:
                kind, name, first = stack.pop()
                lines = line - first + 1
                if kind == "function" and lines > MAX_FUNCTION_LINES:
                    found.append(("function", name, first, lines))
                if kind == "class" and lines > MAX_CLASS_LINES:
                    found.append(("class", name, first, lines))
            head_start = i + 1
        elif c == ";":
            head_start = i + 1
    return found


def main():
    repo = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", ".."))
    core = os.path.join(repo, "plugin", "core")
    problems = []
    sources = {}
    for dirpath, _, names in os.walk(core):
        for name in names:
            if name.endswith((".hpp", ".cpp")):
                rel = os.path.relpath(os.path.join(dirpath, name), core)
                sources[rel] = open(os.path.join(dirpath, name)).read()
    for rel in sorted(sources):
        folder = folder_of(rel)
        if folder and folder not in FOLDERS:
            problems.append(f"plugin/core/{rel}: folder '{folder}' is not in the rule (tests/architecture/check_core.py)")
    # 1 and 2: includes in the core
    uses = {}
    for rel, text in sorted(sources.items()):
        unit = rel.rsplit(".", 1)[0]
        for target in INCLUDE.findall(text):
            if target not in sources:
                problems.append(f"plugin/core/{rel}: #include \"{target}\" is not a core header written from plugin/core")
                continue
            folder, to = folder_of(rel), folder_of(target)
            if folder and to and to != folder and to not in FOLDERS.get(folder, []):
                problems.append(f"plugin/core/{rel}: includes {target}: folder {folder}/ may not include {to}/")
            if not folder and to:
                problems.append(f"plugin/core/{rel}: a top file includes {target} from a folder")
            dep = target.rsplit(".", 1)[0]
            if dep != unit:
                uses.setdefault(unit, set()).add(dep)
    # includes of core headers from the adapter, the tests and the benchmarks, written from plugin/core
    for top in ["plugin/freefem", "tests", "bench"]:
        for dirpath, _, names in os.walk(os.path.join(repo, top)):
            for name in names:
                if not name.endswith((".hpp", ".cpp")):
                    continue
                path = os.path.join(dirpath, name)
                for target in INCLUDE.findall(open(path).read()):
                    base = os.path.basename(target)
                    if target not in sources and any(os.path.basename(s) == base for s in sources) \
                            and not os.path.exists(os.path.join(dirpath, target)):
                        problems.append(f"{os.path.relpath(path, repo)}: #include \"{target}\": write it from plugin/core")
    # 3: cycles between units
    state = {}

    def visit(unit, path):
        state[unit] = 1
        for dep in sorted(uses.get(unit, ())):
            if state.get(dep) == 1:
                cycle = path[path.index(dep):] + [dep] if dep in path else [unit, dep]
                problems.append("include cycle: " + " -> ".join(cycle))
            elif dep not in state:
                visit(dep, path + [dep])
        state[unit] = 2

    for unit in sorted(uses):
        if unit not in state:
            visit(unit, [unit])
    # 4: lengths
    for rel in sorted(sources):
        for kind, name, first, lines in long_blocks(os.path.join(core, rel)):
            limit = MAX_FUNCTION_LINES if kind == "function" else MAX_CLASS_LINES
            problems.append(f"plugin/core/{rel}:{first}: {kind} {name} has {lines} lines (at most {limit})")
    for p in problems:
        print(p)
    print(f"check_core: {len(sources)} files, {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
