#!/usr/bin/env python3
"""The host's stages (host/sources.cmake), in the order a render runs
through them: no source includes a header of a later stage, no object
calls a function of a later stage's, and no two objects call each other,
directly or around a longer circle (read from the objects' symbols with
nm, so a header declared apart from its code cannot hide one).

usage: check_layers.py HOST_DIR OBJECT..."""
import os
import re
import subprocess
import sys

STAGES = ["base", "scene", "pack", "gpu", "render", "write", "app"]


def main():
    host, objects = sys.argv[1], sys.argv[2:]
    stage_of, bad = {}, []
    for stage in sorted(os.listdir(host)):
        folder = os.path.join(host, stage)
        if not os.path.isdir(folder):
            continue
        if stage not in STAGES:
            bad.append(f"host/{stage}/ is not one of the stages {STAGES}")
            continue
        for name in os.listdir(folder):
            stage_of[name] = stage
    rank = lambda name: STAGES.index(stage_of[name])

    for name in sorted(stage_of):
        path = os.path.join(host, stage_of[name], name)
        text = open(path, encoding="utf-8").read()
        for inc in re.findall(r'^\s*#\s*include\s+"([^"]+)"', text, re.M):
            if inc in stage_of and rank(inc) > rank(name):
                bad.append(f"host/{stage_of[name]}/{name} includes "
                           f"host/{stage_of[inc]}/{inc}, a later stage")

    # Which object defines each function and global, which ones each uses.
    defines, uses = {}, {}
    for obj in objects:
        src = os.path.basename(obj).removesuffix(".o")  # NAME.c
        if src not in stage_of:
            bad.append(f"{obj}: no host source {src}")
            continue
        out = subprocess.run(["nm", obj], capture_output=True, text=True,
                             check=True).stdout
        uses[src] = set()
        for line in out.splitlines():
            parts = line.split()
            if len(parts) == 2 and parts[0] == "U":
                uses[src].add(parts[1])
            elif len(parts) == 3 and parts[1] in "TDBR":
                defines[parts[2]] = src
    calls = {src: {defines[s] for s in syms if s in defines} - {src}
             for src, syms in uses.items()}
    for src in sorted(calls):
        for dst in sorted(calls[src]):
            if rank(dst) > rank(src):
                bad.append(f"host/{stage_of[src]}/{src} calls "
                           f"host/{stage_of[dst]}/{dst}, a later stage")

    def reach(start):
        seen, todo = set(), list(calls.get(start, ()))
        while todo:
            m = todo.pop()
            if m not in seen:
                seen.add(m)
                todo.extend(calls.get(m, ()))
        return seen
    for src in sorted(calls):
        if src in reach(src):
            bad.append(f"{src} is in a circle of calls: it reaches "
                       f"{sorted(m for m in reach(src) if src in reach(m))}")

    for line in bad:
        print(line)
    print(f"{len(stage_of)} files in {len(STAGES)} stages, {len(calls)} "
          f"objects, {sum(map(len, calls.values()))} object-to-object calls: "
          f"{'ok' if not bad else f'{len(bad)} problems'}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
