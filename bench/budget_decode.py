#!/usr/bin/env python3
"""Decoding within the input's own triangle budget (issue #33): for each mesh and
rate, `eqmesh encode --bpv B`, then the decoded mesh three ways: every level
(uniform), the finest uniform level that fits the input's triangle count, and
`decode --max-triangles T` (adaptive). PSNR is `eqmesh compare` against the input;
Draco's bytes at the adaptive PSNR are interpolated (log bytes, linear in PSNR)
from the cl10 rows of bench/results/results.csv. A last line per mesh interpolates
eqmesh's bytes at 70 dB within the budget the same way and gives the ratio.

usage: bench/budget_decode.py [MESH ...]   (default: horse, stanford-bunny, armadillo_50k)
env:   EQMESH (default build/tools/eqmesh), RATES ("0.25 0.5 1 4")
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EQMESH = os.environ.get("EQMESH", os.path.join(ROOT, "build", "tools", "eqmesh"))
MESHES = os.path.join(ROOT, "..", "shared", "meshes", "bench")
RATES = [float(r) for r in os.environ.get("RATES", "0.25 0.5 1 4").split()]


def run_json(*args):
    out = subprocess.run([EQMESH, *args, "--json"], check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def psnr(original, decoded):
    return run_json("compare", original, decoded)["psnr_db"]


def interpolate(points, x):
    """log(y) linear in x between the two points around x; None outside."""
    points = sorted(points)
    for (x0, y0), (x1, y1) in zip(points, points[1:]):
        if x0 <= x <= x1 and x1 > x0:
            t = (x - x0) / (x1 - x0)
            return math.exp(math.log(y0) + t * (math.log(y1) - math.log(y0)))
    return None


def draco_curve(name):
    path = os.path.join(ROOT, "bench", "results", "results.csv")
    with open(path) as f:
        return [(float(r["psnr_db"]), float(r["bytes_payload"])) for r in csv.DictReader(f)
                if r["mesh"] == name and r["codec"] == "draco" and r["variant"] == "cl10" and r["psnr_db"]]


def measure(mesh, work):
    name = os.path.splitext(os.path.basename(mesh))[0]
    budget = run_json("info", mesh)["faces"]
    draco = draco_curve(name)
    curve = []
    for bpv in RATES:
        print(f"budget_decode: {name} at {bpv} bpv", file=sys.stderr)
        stream = os.path.join(work, f"{name}_{bpv}.eqm")
        enc = run_json("encode", mesh, stream, "--bpv", str(bpv))
        full = run_json("decode", stream, os.path.join(work, "full.ply"))
        cut = run_json("decode", stream, os.path.join(work, "cut.ply"), "--max-triangles", str(budget))
        level = full["levels_decoded"]
        while level > 0:
            uniform = run_json("decode", stream, os.path.join(work, "uniform.ply"), "--level", str(level))
            if uniform["faces"] <= budget:
                break
            level -= 1
        if level == 0:
            uniform = run_json("decode", stream, os.path.join(work, "uniform.ply"), "--level", "0")
        cut_psnr = psnr(mesh, os.path.join(work, "cut.ply"))
        uniform_psnr = psnr(mesh, os.path.join(work, "uniform.ply"))
        draco_bytes = interpolate(draco, cut_psnr)
        curve.append((cut_psnr, enc["bytes"]))
        print(f"| {name} | {budget:,} | {bpv} | {enc['bytes']:,} | {cut['faces']:,} | {cut_psnr:.2f} | "
              f"{uniform['faces']:,} (level {level}) | {uniform_psnr:.2f} | {cut_psnr - uniform_psnr:+.2f} | "
              f"{draco_bytes:,.0f} | {draco_bytes / enc['bytes']:.1f} | "
              f"{full['faces']:,} | {full['decode_seconds']:.3f} | {cut['decode_seconds']:.3f} |"
              if draco_bytes else
              f"| {name} | {budget:,} | {bpv} | {enc['bytes']:,} | {cut['faces']:,} | {cut_psnr:.2f} | "
              f"{uniform['faces']:,} (level {level}) | {uniform_psnr:.2f} | {cut_psnr - uniform_psnr:+.2f} | "
              f"outside Draco's range | | {full['faces']:,} | {full['decode_seconds']:.3f} | "
              f"{cut['decode_seconds']:.3f} |", flush=True)
    eq70, dr70 = interpolate(curve, 70.0), interpolate(draco, 70.0)
    if eq70 and dr70:
        print(f"| {name} | {budget:,} | at 70 dB | {eq70:,.0f} | | 70.00 | | | | {dr70:,.0f} | {dr70 / eq70:.1f} | | | |")


def main():
    meshes = sys.argv[1:] or [os.path.join(MESHES, m) for m in ("horse.ply", "stanford-bunny.obj", "armadillo_50k.obj")]
    print("| mesh | budget (input triangles) | bpv | bytes | triangles out | PSNR dB | uniform level that fits | "
          "its PSNR dB | gain dB | Draco bytes at that PSNR | Draco / eqmesh | triangles, all levels | "
          "decode s, all levels | decode s, budget |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as work:
        for mesh in meshes:
            measure(mesh, work)


if __name__ == "__main__":
    main()
