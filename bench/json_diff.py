#!/usr/bin/env python3
"""Lists what differs between two trees of foglab outputs (bench/json_compare.sh).

Usage: json_diff.py [--summary] OLD_DIR NEW_DIR

Files are paired by relative path. Identical files are counted. JSON files
that differ are walked value by value: every changed number is printed with
its relative change, every added or removed field by name. Other files that
differ are shown as a unified diff (first lines). Exit status 0 when
everything is identical, 1 otherwise. With --summary, each differing JSON
file gets one line for its changed numbers (how many, the largest relative
change and where) and its other changes are listed in full.
"""
import re
import difflib
import json
import math
import os
import sys


def walk(a, b, path, out):
    if isinstance(a, dict) and isinstance(b, dict):
        for key in a.keys() | b.keys():
            if key not in b:
                out.append(f"{path}.{key}: removed")
            elif key not in a:
                out.append(f"{path}.{key}: added = {json.dumps(b[key])[:120]}")
            else:
                walk(a[key], b[key], f"{path}.{key}", out)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out.append(f"{path}: length {len(a)} -> {len(b)}")
        for i, (x, y) in enumerate(zip(a, b)):
            walk(x, y, f"{path}[{i}]", out)
    elif isinstance(a, (int, float)) and isinstance(b, (int, float)) and \
            not isinstance(a, bool) and not isinstance(b, bool):
        if a != b and not (math.isnan(a) and math.isnan(b)):
            scale = max(abs(a), abs(b))
            rel = abs(a - b) / scale if scale > 0 else 0.0
            out.append(f"{path}: {a!r} -> {b!r} (relative {rel:.2e})")
    elif a != b:
        out.append(f"{path}: {json.dumps(a)[:80]} -> {json.dumps(b)[:80]}")


NUMBER_CHANGE = re.compile(r"^(.*): \S+ -> \S+ \(relative ([0-9.e+-]+)\)$")


def summarize(out):
    """Changed numbers in one line; everything else as it is."""
    numbers = [(float(m.group(2)), m.group(1)) for m in map(NUMBER_CHANGE.match, out) if m]
    others = [line for line in out if not NUMBER_CHANGE.match(line)]
    lines = []
    if numbers:
        worst = max(numbers)
        lines.append(f"{len(numbers)} numbers changed, largest relative {worst[0]:.2e} at {worst[1]}")
    return lines + others


def main():
    args = sys.argv[1:]
    summary = "--summary" in args
    args = [a for a in args if a != "--summary"]
    old_dir, new_dir = args[0], args[1]
    files = set()
    for top in (old_dir, new_dir):
        for root, _, names in os.walk(top):
            for name in names:
                files.add(os.path.relpath(os.path.join(root, name), top))
    same = 0
    differing = 0
    for rel in sorted(files):
        a_path, b_path = os.path.join(old_dir, rel), os.path.join(new_dir, rel)
        if not os.path.exists(a_path) or not os.path.exists(b_path):
            print(f"{rel}: only in {'new' if os.path.exists(b_path) else 'old'}")
            differing += 1
            continue
        with open(a_path, "rb") as fa, open(b_path, "rb") as fb:
            a_bytes, b_bytes = fa.read(), fb.read()
        if a_bytes == b_bytes:
            same += 1
            continue
        differing += 1
        print(f"== {rel}")
        if rel.endswith(".json"):
            out = []
            walk(json.loads(a_bytes), json.loads(b_bytes), "", out)
            for line in summarize(out) if summary else out:
                print(f"   {line}")
        else:
            lines = difflib.unified_diff(a_bytes.decode(errors="replace").splitlines(),
                                         b_bytes.decode(errors="replace").splitlines(),
                                         lineterm="", n=0)
            for line in list(lines)[2:42]:
                print(f"   {line}")
    print(f"{same} files identical, {differing} differ")
    return 0 if differing == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
