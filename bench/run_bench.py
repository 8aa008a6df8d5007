#!/usr/bin/python3
"""eqmesh benchmark: rate-distortion, sizes, speed and memory against Draco and gltfpack.

usage: bench/run_bench.py [--meshes A.obj B.ply ...] [--quick] [--out DIR] [--eqmesh PATH]
                          [--runs N] [--skip-large] [--samples N]

Every codec codes the same canonical original: `eqmesh convert IN canon.ply` (positions and
triangles only, unreferenced vertices dropped). Every error is `eqmesh compare canon.ply X`
with one fixed --samples per mesh. Rates are bits per referenced input vertex.
Outputs in --out: results.csv, summary.md, rd_<mesh>.png, work/ (intermediate files), log.txt.
See bench/README.md.
"""
import argparse
import csv
import datetime
import gzip
import json
import math
import os
import platform
import re
import shutil
import statistics
import struct
import subprocess
import sys
import time
import types

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, HERE)
import bdrate  # noqa: E402

SHARED = os.environ.get("EQMESH_SHARED_DIR", os.path.join(os.path.dirname(ROOT), "shared"))
BENCH_MESHES = ["stanford-bunny.obj", "horse.ply", "armadillo_50k.obj", "skull_50k.obj",
                "igea.ply", "dragon_vrip.ply.gz"]
LARGE = {"dragon_vrip"}
QUICK_MESH = os.path.join(SHARED, "meshes", "small", "bunny_npm.obj")
RATES = [0.25, 0.5, 1.0, 2.0, 3.0, 4.0]
QPS = list(range(8, 17))
DRACO_LEVELS = [7, 10]

CSV_FIELDS = [
    "mesh", "codec", "variant", "param", "bytes_payload", "bytes_payload_gz", "bytes_glb",
    "bytes_glb_gz", "bpv", "bpv_glb", "psnr_db", "rms", "hausdorff", "encode_s", "decode_s",
    "remesh_s", "encode_peak_kb", "decode_peak_kb", "input_vertices", "triangles",
    "output_vertices", "output_triangles", "decode_tri_per_s", "runs", "samples", "error"]

T0 = time.time()
LOG = None
TIME_DIR = "/tmp"  # /usr/bin/time -o files; set to --out/work in main()


def log(msg):
    line = "[%7.1fs] %s" % (time.time() - T0, msg)
    print(line, file=sys.stderr, flush=True)
    if LOG:
        LOG.write(line + "\n")
        LOG.flush()


class StepError(Exception):
    pass


def run_timed(cmd, cwd=None):
    """Runs cmd under /usr/bin/time; returns (stdout, stderr, wall_s, peak_kb). Raises
    StepError with the tool's last error line on a non-zero exit."""
    tfile = os.path.join(TIME_DIR, ".time.%d" % os.getpid())
    full = ["/usr/bin/time", "-f", "%M", "-o", tfile] + [str(c) for c in cmd] \
        if os.path.exists("/usr/bin/time") else [str(c) for c in cmd]
    start = time.perf_counter()
    p = subprocess.run(full, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - start
    peak = None
    try:
        with open(tfile) as f:
            vals = [ln.strip() for ln in f if ln.strip()]
        peak = int(vals[-1])
        os.remove(tfile)
    except (OSError, ValueError, IndexError):
        pass
    if p.returncode != 0:
        msg = (p.stderr.strip().splitlines() or p.stdout.strip().splitlines() or ["?"])[-1]
        raise StepError("%s exited %d: %s" % (os.path.basename(str(cmd[0])), p.returncode, msg))
    return p.stdout, p.stderr, wall, peak


def json_of(stdout):
    start = stdout.find("{")
    if start < 0:
        raise StepError("no JSON in output")
    return json.loads(stdout[start:])


def median(xs):
    xs = [x for x in xs if x is not None]
    return statistics.median(xs) if xs else None


def gzip9_size(data):
    if shutil.which("gzip"):
        p = subprocess.run(["gzip", "-9", "-c", "-n"], input=data, stdout=subprocess.PIPE)
        if p.returncode == 0:
            return len(p.stdout)
    return len(gzip.compress(data, 9))


# ---------------------------------------------------------------- GLB helpers
def read_glb(path):
    with open(path, "rb") as f:
        data = f.read()
    magic, _version, _length = struct.unpack_from("<4sII", data, 0)
    if magic != b"glTF":
        raise StepError("%s: not a GLB" % path)
    clen, ctype = struct.unpack_from("<II", data, 12)
    if ctype != 0x4E4F534A:
        raise StepError("%s: first GLB chunk is not JSON" % path)
    return json.loads(data[20:20 + clen].decode("utf-8")), data


def meshopt_payload_bytes(gltf):
    total = 0
    for bv in gltf.get("bufferViews", []):
        ext = bv.get("extensions", {}).get("EXT_meshopt_compression")
        if ext:
            total += ext["byteLength"]
    return total


def draco_glb(drc_bytes, vertices, triangles, bbox_min, bbox_max, path):
    """A GLB whose only primitive is KHR_draco_mesh_compression-coded (positions + indices);
    the accessors carry count/min/max and no bufferView, as the extension allows."""
    n = len(drc_bytes)
    gltf = {
        "asset": {"version": "2.0", "generator": "eqmesh bench/run_bench.py"},
        "extensionsUsed": ["KHR_draco_mesh_compression"],
        "extensionsRequired": ["KHR_draco_mesh_compression"],
        "buffers": [{"byteLength": n}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": n}],
        "accessors": [
            {"componentType": 5126, "count": vertices, "type": "VEC3",
             "min": bbox_min, "max": bbox_max},
            {"componentType": 5125, "count": 3 * triangles, "type": "SCALAR"}],
        "meshes": [{"primitives": [{
            "attributes": {"POSITION": 0}, "indices": 1, "mode": 4,
            "extensions": {"KHR_draco_mesh_compression": {
                "bufferView": 0, "attributes": {"POSITION": 0}}}}]}],
        "nodes": [{"mesh": 0}],
        "scenes": [{"nodes": [0]}],
        "scene": 0,
    }
    js = json.dumps(gltf, separators=(",", ":")).encode("utf-8")
    js += b" " * ((4 - len(js) % 4) % 4)
    bin_ = drc_bytes + b"\0" * ((4 - n % 4) % 4)
    total = 12 + 8 + len(js) + 8 + len(bin_)
    out = struct.pack("<4sII", b"glTF", 2, total) + struct.pack("<II", len(js), 0x4E4F534A) + js \
        + struct.pack("<II", len(bin_), 0x004E4942) + bin_
    with open(path, "wb") as f:
        f.write(out)
    return len(out)


def ply_bbox(path):
    """Bounding box of a binary little-endian or ascii PLY's float/double x y z."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header") + len(b"end_header")
    while data[end:end + 1] in (b"\r", b"\n"):
        end += 1
        if data[end - 1:end] == b"\n":
            break
    header = data[:end].decode("ascii", "replace").splitlines()
    fmt = "ascii"
    nv = 0
    props = []
    in_vertex = False
    for ln in header:
        t = ln.split()
        if not t:
            continue
        if t[0] == "format":
            fmt = t[1]
        elif t[0] == "element":
            in_vertex = t[1] == "vertex"
            if in_vertex:
                nv = int(t[2])
        elif t[0] == "property" and in_vertex:
            props.append(t[1])
    lo = [math.inf] * 3
    hi = [-math.inf] * 3
    if fmt == "ascii":
        lines = data[end:].decode("ascii").split("\n")
        for ln in lines[:nv]:
            v = [float(x) for x in ln.split()[:3]]
            for k in range(3):
                lo[k], hi[k] = min(lo[k], v[k]), max(hi[k], v[k])
    else:
        codes = {"float": "f", "float32": "f", "double": "d", "float64": "d", "uchar": "B",
                 "uint8": "B", "char": "b", "int8": "b", "short": "h", "int16": "h", "ushort": "H",
                 "uint16": "H", "int": "i", "int32": "i", "uint": "I", "uint32": "I"}
        st = struct.Struct(("<" if fmt == "binary_little_endian" else ">")
                           + "".join(codes[p] for p in props))
        for i in range(nv):
            v = st.unpack_from(data, end + i * st.size)
            for k in range(3):
                lo[k], hi[k] = min(lo[k], v[k]), max(hi[k], v[k])
    return lo, hi


def python_canonical(src, ply_out, obj_out):
    """Fallback when this eqmesh has no `convert` command: OBJ / OFF / ascii PLY only.
    Positions + triangles (polygons fan-triangulated), unreferenced vertices dropped."""
    opener = gzip.open if src.endswith(".gz") else open
    with opener(src, "rt", errors="replace") as f:
        text = f.read()
    pos, faces = [], []
    base = src[:-3] if src.endswith(".gz") else src
    if base.endswith(".obj"):
        for ln in text.splitlines():
            t = ln.split()
            if not t:
                continue
            if t[0] == "v":
                pos.append(tuple(float(x) for x in t[1:4]))
            elif t[0] == "f":
                idx = [int(x.split("/")[0]) for x in t[1:]]
                idx = [i - 1 if i > 0 else len(pos) + i for i in idx]
                faces += [(idx[0], idx[k], idx[k + 1]) for k in range(1, len(idx) - 1)]
    elif base.endswith(".off"):
        toks = [ln.split("#")[0] for ln in text.splitlines()]
        toks = " ".join(toks).split()
        nv, nf = int(toks[1]), int(toks[2])
        i = 4
        for _ in range(nv):
            pos.append(tuple(float(x) for x in toks[i:i + 3]))
            i += 3
        for _ in range(nf):
            n = int(toks[i])
            idx = [int(x) for x in toks[i + 1:i + 1 + n]]
            i += 1 + n
            faces += [(idx[0], idx[k], idx[k + 1]) for k in range(1, len(idx) - 1)]
    else:
        raise StepError("%s: this eqmesh has no `convert` command and the Python fallback reads "
                        "only OBJ and OFF" % src)
    used = sorted({i for f in faces for i in f})
    remap = {old: new for new, old in enumerate(used)}
    with open(ply_out, "wb") as f:
        f.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\n"
                 "property float y\nproperty float z\nelement face %d\nproperty list uchar int "
                 "vertex_indices\nend_header\n" % (len(used), len(faces))).encode("ascii"))
        for i in used:
            f.write(struct.pack("<3f", *pos[i]))
        for a, b, c in faces:
            f.write(struct.pack("<B3i", 3, remap[a], remap[b], remap[c]))
    with open(obj_out, "w") as f:
        for i in used:
            f.write("v %.9g %.9g %.9g\n" % pos[i])
        for a, b, c in faces:
            f.write("f %d %d %d\n" % (remap[a] + 1, remap[b] + 1, remap[c] + 1))
    return {"vertices": len(used), "faces": len(faces),
            "dropped_unreferenced_vertices": len(pos) - len(used)}


# ---------------------------------------------------------------- the bench
class Bench:
    def __init__(self, args):
        self.args = args
        self.eq = args.eqmesh
        self.rows = []
        self.errors = 0
        self.meta = {}  # per mesh: remesh numbers, counts
        self.caps = self.detect()

    def detect(self):
        def help_of(cmd):
            p = subprocess.run([self.eq, cmd, "--help"], stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True)
            return p.stdout
        enc, rem = help_of("encode"), help_of("remesh")
        caps = {
            "zerotree": "zerotree" in enc,
            "srm": ".srm" in enc and ".srm" in rem,
            "original": "--original" in enc,
            "glb": bool(re.search(r"OUT[^\n]*\.glb", enc)),
            "convert": "usage" in help_of("convert").lower(),
        }
        if not caps["convert"]:
            log("WARNING: this eqmesh has no `convert` command: canonical originals are written by "
                "a Python fallback (OBJ/OFF only) and gltfpack reads canon.obj")
        log("eqmesh %s: zerotree coder %s, .srm remesh reuse %s, encode to .glb %s" % (
            self.eq, *("yes" if caps[k] else "no" for k in ("zerotree", "srm", "glb"))))
        return caps

    def add(self, **kw):
        row = {k: kw.get(k) for k in CSV_FIELDS}
        if row["error"]:
            self.errors += 1
            log("  ERROR %s %s %s: %s" % (row["codec"], row["variant"], row["param"], row["error"]))
        self.rows.append(row)
        self.write_csv()  # partial results survive an interrupted sweep
        return row

    def compare(self, canon, other, samples):
        out, _, _, _ = run_timed([self.eq, "compare", canon, other, "--samples", samples, "--json"])
        j = json_of(out)
        return j.get("psnr_db"), j.get("rms"), j.get("hausdorff"), j.get("faces_other")

    # -------------------------------------------------------------- one mesh
    def mesh(self, path):
        name = os.path.basename(path).split(".")[0]
        wd = os.path.join(self.args.work, name)
        os.makedirs(wd, exist_ok=True)
        log("%s: prepare canonical original" % name)
        canon = os.path.join(wd, "canon.ply")
        if self.caps["convert"]:
            out, _, _, _ = run_timed([self.eq, "convert", path, canon, "--json"])
            cj = json_of(out)
            run_timed([self.eq, "convert", canon, os.path.join(wd, "canon.glb")])
            self.gltf_src = os.path.join(wd, "canon.glb")
        else:
            cj = python_canonical(path, canon, os.path.join(wd, "canon.obj"))
            self.gltf_src = os.path.join(wd, "canon.obj")
        nv, nf = cj["vertices"], cj["faces"]
        samples = self.args.samples or max(1000000, 10 * nv)
        if self.args.quick:
            samples = self.args.samples or 200000
        m = {"name": name, "path": path, "vertices": nv, "triangles": nf, "samples": samples,
             "dropped": cj.get("dropped_unreferenced_vertices", 0)}
        self.meta[name] = m
        base = dict(mesh=name, input_vertices=nv, triangles=nf, samples=samples)
        log("%s: %d referenced vertices, %d triangles, %d compare samples" % (name, nv, nf, samples))
        self.remesh(m, wd, canon, base)
        self.eqmesh(m, wd, canon, base)
        if not self.args.no_peers:
            self.draco(m, wd, canon, base)
            self.gltfpack(m, wd, canon, base)

    def remesh(self, m, wd, canon, base):
        log("%s: remesh (ceiling)" % m["name"])
        target = os.path.join(wd, "remesh.srm" if self.caps["srm"] else "remesh.ply")
        try:
            out, _, wall, peak = run_timed([self.eq, "remesh", canon, target, "--json"])
            j = json_of(out)
            m["remesh_s"] = j.get("seconds", wall)
            m["remesh_psnr_tool"] = j.get("psnr_db")
            m["remesh_levels"] = j.get("levels")
            m["srm"] = target if self.caps["srm"] else None
            ply = target
            if self.caps["srm"]:
                ply = os.path.join(wd, "remesh.ply")
                try:
                    run_timed([self.eq, "convert", target, ply])
                except StepError:  # convert cannot read .srm: remesh once more to a plain mesh
                    run_timed([self.eq, "remesh", canon, ply])
            psnr, rms, haus, ftri = self.compare(canon, ply, m["samples"])
            m["remesh_psnr"] = psnr
            self.add(**base, codec="remesh", variant="semi-regular", param=j.get("levels"),
                     psnr_db=psnr, rms=rms, hausdorff=haus, remesh_s=m["remesh_s"],
                     encode_peak_kb=peak, output_vertices=j.get("output_vertices"),
                     output_triangles=ftri, runs=1)
            log("%s: remesh %.1f s, %s levels, PSNR %.2f dB" % (m["name"], m["remesh_s"],
                                                              j.get("levels"), psnr or float("nan")))
        except (StepError, KeyError, ValueError) as e:
            m["srm"] = None
            self.add(**base, codec="remesh", variant="semi-regular", error=str(e))

    def eqmesh(self, m, wd, canon, base):
        variants = [("eq", "lifted"), ("eq", "unlifted")]
        if self.caps["zerotree"]:
            variants += [("zerotree", "lifted"), ("zerotree", "unlifted")]
        if self.args.variants:
            variants = [v for v in variants if "%s-%s" % v in self.args.variants]
        rates = self.args.rates or RATES
        if self.args.quick:
            variants, rates = [("eq", "unlifted")], [1.0, 4.0]
        src = m.get("srm") or canon
        # A .srm carries no original: the encoder needs it to choose the level count.
        extra = ["--original", canon] if (m.get("srm") and self.caps["original"]) else []
        enc_runs = self.args.runs if (m.get("srm") or self.args.encode_runs_full) else 1
        if self.args.encode_runs:
            enc_runs = self.args.encode_runs
        if self.args.quick:
            enc_runs = 1
        glb_rates = self.args.glb_rates if self.args.glb_rates is not None else [1.0]
        for coder, transform in variants:
            vname = "%s-%s" % (coder, transform)
            for bpv in rates:
                log("%s: eqmesh %s %g bpv" % (m["name"], vname, bpv))
                row = dict(base, codec="eqmesh", variant=vname, param=bpv)
                stream = os.path.join(wd, "eq_%s_%g.eqm" % (vname, bpv))
                dec = os.path.join(wd, "eq_%s_%g.ply" % (vname, bpv))
                try:
                    enc_s, rem_s, peaks, j = [], [], [], None
                    for _ in range(enc_runs):
                        out, _, wall, peak = run_timed(
                            [self.eq, "encode", src, stream, "--bpv", bpv, "--transform", transform,
                             "--coder", coder, "--json"] + extra)
                        j = json_of(out)
                        enc_s.append(j.get("encode_seconds", wall))
                        rem_s.append(j.get("remesh_seconds"))
                        peaks.append(peak)
                    nbytes = os.path.getsize(stream)
                    dec_s, dpeaks, dj = [], [], None
                    for _ in range(self.args.runs):
                        out, _, wall, peak = run_timed([self.eq, "decode", stream, dec, "--json"])
                        dj = json_of(out)
                        dec_s.append(dj.get("decode_seconds", wall))
                        dpeaks.append(peak)
                    psnr, rms, haus, ftri = self.compare(canon, dec, m["samples"])
                    glb_bytes = None
                    if self.caps["glb"] and (self.args.quick or bpv in glb_rates):
                        glb = stream[:-4] + ".glb"
                        try:  # the whole-GLB size is extra: its failure must not lose the point
                            run_timed([self.eq, "encode", canon, glb, "--bpv", bpv, "--transform",
                                       transform, "--coder", coder])
                            glb_bytes = os.path.getsize(glb)
                        except StepError as e:
                            log("  GLB size not measured: %s" % e)
                    with open(stream, "rb") as f:
                        gz = gzip9_size(f.read())
                    d = median(dec_s)
                    rs = median(rem_s)
                    if m.get("srm"):
                        rs = m.get("remesh_s")
                    row.update(bytes_payload=nbytes, bytes_payload_gz=gz, bytes_glb=glb_bytes,
                               bpv=8.0 * nbytes / m["vertices"],
                               bpv_glb=8.0 * glb_bytes / m["vertices"] if glb_bytes else None,
                               psnr_db=psnr, rms=rms, hausdorff=haus, encode_s=median(enc_s),
                               decode_s=d, remesh_s=rs, encode_peak_kb=max(p or 0 for p in peaks),
                               decode_peak_kb=max(p or 0 for p in dpeaks),
                               output_vertices=dj.get("vertices"),
                               output_triangles=dj.get("faces", ftri),
                               decode_tri_per_s=(dj.get("faces") or 0) / d if d else None,
                               runs=self.args.runs)
                    self.add(**row)
                    log("%s:   %d B, %.3f bpv, %.2f dB, enc %.2fs dec %.3fs" % (
                        m["name"], nbytes, row["bpv"], psnr or float("nan"), row["encode_s"] or 0, d or 0))
                    if coder == "eq":
                        self.budget(m, base, canon, stream, vname, bpv, nbytes)
                    if coder == "eq" and bpv == max(rates) and not self.args.quick:
                        self.levels(m, base, canon, stream, vname, bpv, j)
                except (StepError, KeyError, ValueError) as e:
                    row["error"] = str(e)
                    self.add(**row)

    def budget(self, m, base, canon, stream, vname, bpv, nbytes):
        """The same stream decoded within the input's own triangle count (decode --max-triangles)."""
        dec = stream[:-4] + "_budget.ply"
        row = dict(base, codec="eqmesh-budget", variant=vname, param=bpv)
        try:
            out, _, wall, _ = run_timed([self.eq, "decode", stream, dec, "--max-triangles",
                                         m["triangles"], "--json"])
            dj = json_of(out)
            psnr, rms, haus, ftri = self.compare(canon, dec, m["samples"])
            row.update(bytes_payload=nbytes, bpv=8.0 * nbytes / m["vertices"], psnr_db=psnr, rms=rms,
                       hausdorff=haus, decode_s=dj.get("decode_seconds", wall),
                       output_vertices=dj.get("vertices"), output_triangles=dj.get("faces", ftri), runs=1)
            self.add(**row)
            log("%s:   within %d triangles: %s triangles, %.2f dB" % (
                m["name"], m["triangles"], dj.get("faces"), psnr or float("nan")))
        except (StepError, KeyError, ValueError) as e:
            row["error"] = str(e)
            self.add(**row)

    def levels(self, m, base, canon, stream, vname, bpv, enc_json):
        """Progressive access: decode every level of one stream and measure it."""
        coded = enc_json.get("levels") or 0
        for k in range(0, int(coded) + 1):
            dec = stream[:-4] + "_L%d.ply" % k
            row = dict(base, codec="eqmesh-level", variant=vname, param="%g:L%d" % (bpv, k))
            try:
                out, _, wall, _ = run_timed([self.eq, "decode", stream, dec, "--level", k, "--json"])
                dj = json_of(out)
                psnr, rms, haus, ftri = self.compare(canon, dec, m["samples"])
                row.update(psnr_db=psnr, rms=rms, hausdorff=haus, decode_s=dj.get("decode_seconds", wall),
                           output_vertices=dj.get("vertices"), output_triangles=dj.get("faces", ftri),
                           bytes_payload=(dj.get("level_offsets", []) + [dj.get("bytes")])[k]
                           if k < len(dj.get("level_offsets", [])) else dj.get("bytes"), runs=1)
                self.add(**row)
                log("%s:   level %d: %s vertices, %.2f dB" % (m["name"], k, dj.get("vertices"),
                                                           psnr or float("nan")))
            except (StepError, KeyError, ValueError, TypeError) as e:
                row["error"] = str(e)
                self.add(**row)

    def draco(self, m, wd, canon, base):
        levels, qps = DRACO_LEVELS, self.args.qps or QPS
        if self.args.quick:
            levels, qps = [10], [10, 12]
        lo, hi = ply_bbox(canon)
        for cl in levels:
            for qp in qps:
                log("%s: draco cl%d qp%d" % (m["name"], cl, qp))
                row = dict(base, codec="draco", variant="cl%d" % cl, param=qp)
                drc = os.path.join(wd, "draco_cl%d_qp%d.drc" % (cl, qp))
                dec = os.path.join(wd, "draco_cl%d_qp%d.ply" % (cl, qp))
                try:
                    enc_s, epk, dec_s, dpk = [], [], [], []
                    for _ in range(self.args.runs):
                        out, err, wall, peak = run_timed(
                            ["draco_encoder", "-i", canon, "-o", drc, "-qp", qp, "-cl", cl,
                             "--skip", "NORMAL"])
                        mm = re.search(r"\((\d+) ms to encode\)", out + err)
                        enc_s.append(int(mm.group(1)) / 1000.0 if mm else wall)
                        epk.append(peak)
                    for _ in range(self.args.runs):
                        out, err, wall, peak = run_timed(["draco_decoder", "-i", drc, "-o", dec])
                        mm = re.search(r"\((\d+) ms to decode\)", out + err)
                        if not mm:
                            raise StepError("draco_decoder printed no decode time")
                        dec_s.append(int(mm.group(1)) / 1000.0)
                        dpk.append(peak)
                    psnr, rms, haus, ftri = self.compare(canon, dec, m["samples"])
                    with open(drc, "rb") as f:
                        drc_bytes = f.read()
                    glb_bytes = draco_glb(drc_bytes, m["vertices"], m["triangles"], lo, hi,
                                          drc[:-4] + ".glb")
                    with open(drc[:-4] + ".glb", "rb") as f:
                        glb_gz = gzip9_size(f.read())
                    d = median(dec_s)
                    row.update(bytes_payload=len(drc_bytes), bytes_payload_gz=gzip9_size(drc_bytes),
                               bytes_glb=glb_bytes, bytes_glb_gz=glb_gz,
                               bpv=8.0 * len(drc_bytes) / m["vertices"],
                               bpv_glb=8.0 * glb_bytes / m["vertices"], psnr_db=psnr, rms=rms,
                               hausdorff=haus, encode_s=median(enc_s), decode_s=d,
                               encode_peak_kb=max(p or 0 for p in epk),
                               decode_peak_kb=max(p or 0 for p in dpk), output_triangles=ftri,
                               decode_tri_per_s=(ftri or 0) / d if d else None, runs=self.args.runs)
                    self.add(**row)
                    log("%s:   %d B, %.3f bpv, %.2f dB, dec %.3fs" % (
                        m["name"], len(drc_bytes), row["bpv"], psnr or float("nan"), d or 0))
                except (StepError, ValueError) as e:
                    row["error"] = str(e)
                    self.add(**row)

    def gltfpack(self, m, wd, canon, base):
        vps = [12] if self.args.quick else (self.args.qps or QPS)
        src = self.gltf_src
        for vp in vps:
            log("%s: gltfpack -cc -vp %d" % (m["name"], vp))
            row = dict(base, codec="gltfpack", variant="cc", param=vp)
            out_glb = os.path.join(wd, "gltfpack_vp%d.glb" % vp)
            q_glb = os.path.join(wd, "gltfpack_q_vp%d.glb" % vp)
            try:
                enc_s, epk = [], []
                for _ in range(self.args.runs):
                    _, _, wall, peak = run_timed(["gltfpack", "-i", src, "-o", out_glb, "-cc",
                                                  "-vp", vp])
                    enc_s.append(wall)
                    epk.append(peak)
                gltf, data = read_glb(out_glb)
                payload = meshopt_payload_bytes(gltf)
                if payload == 0:
                    raise StepError("no EXT_meshopt_compression buffer views in gltfpack output")
                # The payload bytes as a server would gzip them: the compressed buffer (buffer 0).
                bin_off = 20 + struct.unpack_from("<I", data, 12)[0] + 8
                raw_payload = data[bin_off:bin_off + gltf["buffers"][0]["byteLength"]]
                run_timed(["gltfpack", "-i", src, "-o", q_glb, "-vp", vp])
                try:
                    psnr, rms, haus, ftri = self.compare(canon, q_glb, m["samples"])
                except StepError as e:
                    raise StepError("quantized GLB does not load in eqmesh compare: %s" % e)
                row.update(bytes_payload=payload, bytes_payload_gz=gzip9_size(raw_payload),
                           bytes_glb=len(data), bytes_glb_gz=gzip9_size(data),
                           bpv=8.0 * payload / m["vertices"], bpv_glb=8.0 * len(data) / m["vertices"],
                           psnr_db=psnr, rms=rms, hausdorff=haus, encode_s=median(enc_s),
                           encode_peak_kb=max(p or 0 for p in epk), output_triangles=ftri,
                           runs=self.args.runs)
                self.add(**row)
                log("%s:   payload %d B (gz %d), glb %d B, %.2f dB" % (
                    m["name"], payload, row["bytes_payload_gz"], len(data), psnr or float("nan")))
            except (StepError, KeyError, ValueError) as e:
                row["error"] = str(e)
                self.add(**row)

    # -------------------------------------------------------------- outputs
    def write_csv(self):
        path = os.path.join(self.args.out, "results.csv")
        with open(path, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=CSV_FIELDS)
            w.writeheader()
            for r in self.rows:
                w.writerow({k: ("%.6g" % v if isinstance(v, float) else v) for k, v in r.items()})
        return path


# ---------------------------------------------------------------- curves and report
def ok_rows(rows, mesh, codec=None, variant=None):
    return [r for r in rows if r["mesh"] == mesh and not r["error"] and r["psnr_db"] is not None
            and (codec is None or r["codec"] == codec)
            and (variant is None or r["variant"] == variant)]


def curves(rows, mesh, nv):
    """name -> list of (bpv, psnr) for every curve of one mesh (payload bytes unless *glb*)."""
    c = {}
    for v in ("eq-lifted", "zerotree-lifted", "eq-unlifted", "zerotree-unlifted"):
        pts = [(r["bpv"], r["psnr_db"]) for r in ok_rows(rows, mesh, "eqmesh", v)]
        if pts:
            c[v] = sorted(pts)
    for v in ("eq-lifted", "eq-unlifted"):
        pts = [(r["bpv"], r["psnr_db"]) for r in ok_rows(rows, mesh, "eqmesh-budget", v)]
        if pts:
            c[v + "-budget"] = sorted(pts)
    eq_all = c.get("eq-lifted", []) + c.get("eq-unlifted", [])
    if eq_all:
        c["eq-best"] = bdrate.pareto_front(eq_all)
    zt_all = c.get("zerotree-lifted", []) + c.get("zerotree-unlifted", [])
    if zt_all:
        c["zerotree-best"] = bdrate.pareto_front(zt_all)
    for v in DRACO_LEVELS:
        pts = [(r["bpv"], r["psnr_db"]) for r in ok_rows(rows, mesh, "draco", "cl%d" % v)]
        if pts:
            c["draco-cl%d" % v] = sorted(pts)
    dr = ok_rows(rows, mesh, "draco")
    if dr:
        c["draco-best"] = bdrate.pareto_front([(r["bpv"], r["psnr_db"]) for r in dr])
        c["draco-best-glb"] = bdrate.pareto_front([(r["bpv_glb"], r["psnr_db"]) for r in dr])
    gp = ok_rows(rows, mesh, "gltfpack")
    if gp:
        c["gltfpack"] = bdrate.pareto_front([(r["bpv"], r["psnr_db"]) for r in gp])
        c["gltfpack-gzip"] = bdrate.pareto_front(
            [(8.0 * r["bytes_payload_gz"] / nv, r["psnr_db"]) for r in gp])
        c["gltfpack-glb"] = bdrate.pareto_front([(r["bpv_glb"], r["psnr_db"]) for r in gp])
    eg = [(r["bpv_glb"], r["psnr_db"]) for r in ok_rows(rows, mesh, "eqmesh")
          if r["variant"].startswith("eq-") and r["bpv_glb"]]
    if eg:
        c["eq-best-glb"] = bdrate.pareto_front(eg)
    return c


PLOT_STYLE = [("eq-lifted", "EQ lifted"), ("eq-unlifted", "EQ unlifted"),
              ("eq-lifted-budget", "EQ lifted, within the input triangle count"),
              ("eq-unlifted-budget", "EQ unlifted, within the input triangle count"),
              ("zerotree-lifted", "ZT lifted"), ("zerotree-unlifted", "ZT unlifted"),
              ("draco-cl7", "Draco cl7"), ("draco-cl10", "Draco cl10"),
              ("gltfpack", "gltfpack -cc"), ("gltfpack-gzip", "gltfpack -cc + gzip -9")]


def plot_mesh(rows, mesh, meta, png, workdir):
    """PSNR vs bpv (log x), every codec, remesh ceiling as a dashed line. Needs gnuplot."""
    if not shutil.which("gnuplot"):
        log("gnuplot not found (Debian gnuplot-nox): no plot for %s" % mesh)
        return False
    c = curves(rows, mesh, meta["vertices"])
    wd = os.path.join(workdir, mesh)
    plots = []
    for key, title in PLOT_STYLE:
        if key not in c:
            continue
        dat = os.path.join(wd, "plot_%s.dat" % key)
        with open(dat, "w") as f:
            for x, y in sorted(c[key]):
                f.write("%g %g\n" % (x, y))
        dash = " dt 3" if key.startswith("zerotree") else ""
        # gnuplot's single-quoted strings escape a quote by doubling it.
        plots.append("'%s' using 1:2 with linespoints lw 2%s title '%s'" % (dat, dash, title.replace("'", "''")))
    if not plots:
        return False
    ceiling = meta.get("remesh_psnr")
    if ceiling:
        plots.append("%g with lines dt 2 lc rgb 'black' title 'remesh ceiling'" % ceiling)
    script = "\n".join([
        "set terminal pngcairo size 900,600 noenhanced" if "pngcairo" in _gnuplot_terms()
        else "set terminal png size 900,600",
        "set output '%s'" % png,
        "set title 'Rate-distortion: %s (%d vertices, %d triangles)'" % (
            mesh, meta["vertices"], meta["triangles"]),
        "set xlabel 'bits per input vertex (geometry payload)'",
        "set ylabel 'PSNR (dB)'",
        "set logscale x 2", "set grid", "set key top left opaque box",
        "plot " + ", ".join(plots), ""])
    p = subprocess.run(["gnuplot"], input=script, text=True, stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE)
    if p.returncode != 0 or not os.path.exists(png):
        log("gnuplot failed for %s: %s" % (mesh, p.stderr.strip()[-300:]))
        return False
    return True


_TERMS = None


def _gnuplot_terms():
    global _TERMS
    if _TERMS is None:
        p = subprocess.run(["gnuplot", "-e", "set terminal"], stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, text=True)
        _TERMS = p.stdout
    return _TERMS


def fmt(x, spec="%.2f", na="n/a"):
    return na if x is None else spec % x


def machine():
    def sh(cmd):
        try:
            return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                                  text=True, shell=True).stdout.strip()
        except OSError:
            return ""
    model = sh("lscpu | sed -n 's/^Model name: *//p'")
    mem = sh("free -h | awk '/^Mem:/ {print $2\" total, \"$7\" available\"}'")
    return "%s; %s logical CPUs (nproc); memory %s; %s %s" % (
        model or platform.processor(), sh("nproc"), mem, platform.system(), platform.release())


def tool_versions():
    v = []
    p = subprocess.run(["gltfpack", "-v"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    v.append((p.stdout.strip().splitlines() or ["gltfpack ?"])[0])
    p = subprocess.run("dpkg-query -W -f '${Version}' draco 2>/dev/null", shell=True,
                       stdout=subprocess.PIPE, text=True)
    v.append("draco (Debian) " + (p.stdout.strip() or "?"))
    return ", ".join(v)


def bd(c, anchor, test):
    if anchor not in c or test not in c:
        return None, "n/a (missing curve)"
    try:
        pct, lo, hi = bdrate.bd_rate(c[anchor], c[test])
        return pct, "%+.1f %% over %.1f-%.1f dB" % (pct, lo, hi)
    except bdrate.BDError as e:
        return None, "n/a (%s)" % e


def write_summary(bench, started, path):
    rows, args = bench.rows, bench.args
    runs_seen = [r["runs"] for r in rows if isinstance(r["runs"], int)] or [args.runs]
    L = []
    L.append("# eqmesh benchmark%s" % (" (quick mode)" if args.quick else ""))
    L.append("")
    L.append("Generated by `bench/run_bench.py%s` on %s. Machine: %s. Peers: %s. eqmesh binary: "
             "`%s` (zerotree coder: %s; .srm reuse: %s; encode to GLB: %s)." % (
                 " --quick" if args.quick else "", started.strftime("%Y-%m-%d %H:%M"), machine(),
                 tool_versions(), os.path.relpath(args.eqmesh, ROOT),
                 *(cap_word(bench.caps[k]) for k in ("zerotree", "srm", "glb"))))
    L.append("")
    L.append("Every codec codes the canonical original (`eqmesh convert IN canon.ply`: positions "
             "and triangles, unreferenced vertices dropped). PSNR = 20 log10(bbox diagonal / "
             "symmetric Metro RMS) from `eqmesh compare canon.ply DECODED --samples N` (one N per "
             "mesh). bpv = 8 x bytes / referenced input vertices. *Payload* = the geometry stream "
             "alone (.eqm, .drc, meshopt buffer views); *GLB* = the whole file. Timings are medians "
             "of %s run(s) (column `runs`); peak memory is the maximum RSS (/usr/bin/time %%M)." % (
                 "-".join(str(x) for x in sorted({min(runs_seen), max(runs_seen)}))))
    L.append("")
    checks = []  # (expectation, verdict, detail) over all meshes
    for mesh, meta in bench.meta.items():
        nv = meta["vertices"]
        c = curves(rows, mesh, nv)
        L.append("## %s" % mesh)
        L.append("")
        L.append("%d referenced vertices (%s unreferenced dropped), %d triangles, %d compare "
                 "samples. Remesh: %s levels, %s s, PSNR %s dB (the ceiling of every eqmesh "
                 "point)." % (nv, fmt(meta.get("dropped"), "%d"), meta["triangles"], meta["samples"],
                              meta.get("remesh_levels", "?"), fmt(meta.get("remesh_s")),
                              fmt(meta.get("remesh_psnr"))))
        L.append("")
        # Table 1 layout
        L.append("### PSNR (dB) vs bits per vertex (layout of the seed's Table 1)")
        L.append("")
        L.append("Cells: PSNR @ achieved bpv. Draco: best of cl 7/10 interpolated at the row's "
                 "bpv (n/a below its lowest rate, qp 8).")
        L.append("")
        L.append("| bpv | EQ lifted | ZT lifted | EQ unlifted | ZT unlifted | Draco |")
        L.append("|---|---|---|---|---|---|")
        eqr = ok_rows(rows, mesh, "eqmesh")
        rates = sorted({r["param"] for r in rows if r["mesh"] == mesh and r["codec"] == "eqmesh"})
        for b in rates:
            cells = []
            for v in ("eq-lifted", "zerotree-lifted", "eq-unlifted", "zerotree-unlifted"):
                hit = [r for r in eqr if r["variant"] == v and r["param"] == b]
                err = [r for r in rows if r["mesh"] == mesh and r["codec"] == "eqmesh"
                       and r["variant"] == v and r["param"] == b and r["error"]]
                if hit:
                    cells.append("%.2f @%.2f" % (hit[0]["psnr_db"], hit[0]["bpv"]))
                elif err:
                    cells.append("error")
                else:
                    cells.append("missing" if v.startswith("zerotree") and not bench.caps["zerotree"]
                                 else "–")
            dp = bdrate.psnr_at_rate(c["draco-best"], b) if "draco-best" in c else None
            L.append("| %g | %s | %s |" % (b, " | ".join(cells), fmt(dp)))
        L.append("")
        # all eqmesh points
        L.append("### eqmesh points")
        L.append("")
        L.append("| variant | target bpv | bytes | bpv | GLB bytes | PSNR | Hausdorff | remesh s "
                 "| encode s | decode s | Mtri/s out | enc peak MB | dec peak MB |")
        L.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        for r in [r for r in rows if r["mesh"] == mesh and r["codec"] == "eqmesh"]:
            if r["error"]:
                L.append("| %s | %g | error: %s |||||||||||" % (r["variant"], r["param"], r["error"]))
                continue
            L.append("| %s | %g | %d | %.3f | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                r["variant"], r["param"], r["bytes_payload"], r["bpv"],
                fmt(r["bytes_glb"], "%d"), fmt(r["psnr_db"]), fmt(r["hausdorff"], "%.3g"),
                fmt(r["remesh_s"]), fmt(r["encode_s"], "%.3f"), fmt(r["decode_s"], "%.4f"),
                fmt(r["decode_tri_per_s"] and r["decode_tri_per_s"] / 1e6, "%.2f"),
                fmt(r["encode_peak_kb"] and r["encode_peak_kb"] / 1024.0, "%.0f"),
                fmt(r["decode_peak_kb"] and r["decode_peak_kb"] / 1024.0, "%.0f")))
        L.append("")
        lv = [r for r in rows if r["mesh"] == mesh and r["codec"] == "eqmesh-level" and not r["error"]]
        if lv:
            L.append("### Progressive decoding (`decode --level K` of the highest-rate EQ streams)")
            L.append("")
            L.append("| variant | stream @ level | vertices | bytes read | PSNR | decode s |")
            L.append("|---|---|---|---|---|---|")
            for r in lv:
                L.append("| %s | %s | %s | %s | %s | %s |" % (
                    r["variant"], r["param"], fmt(r["output_vertices"], "%d"),
                    fmt(r["bytes_payload"], "%d"), fmt(r["psnr_db"]), fmt(r["decode_s"], "%.4f")))
            L.append("")
        # peers
        L.append("### Peers")
        L.append("")
        L.append("| codec | setting | payload bytes | bpv | payload gz | GLB bytes | GLB gz | PSNR "
                 "| encode s | decode s | Mtri/s out | enc peak MB | dec peak MB |")
        L.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        for r in [r for r in rows if r["mesh"] == mesh and r["codec"] in ("draco", "gltfpack")]:
            setting = "%s %s %s" % (r["variant"], "qp" if r["codec"] == "draco" else "vp", r["param"])
            if r["error"]:
                L.append("| %s | %s | error: %s |||||||||||" % (r["codec"], setting, r["error"]))
                continue
            L.append("| %s | %s | %d | %.3f | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                r["codec"], setting, r["bytes_payload"], r["bpv"], fmt(r["bytes_payload_gz"], "%d"),
                fmt(r["bytes_glb"], "%d"), fmt(r["bytes_glb_gz"], "%d"), fmt(r["psnr_db"]),
                fmt(r["encode_s"], "%.3f"), fmt(r["decode_s"], "%.4f"),
                fmt(r["decode_tri_per_s"] and r["decode_tri_per_s"] / 1e6, "%.2f"),
                fmt(r["encode_peak_kb"] and r["encode_peak_kb"] / 1024.0, "%.0f"),
                fmt(r["decode_peak_kb"] and r["decode_peak_kb"] / 1024.0, "%.0f")))
        L.append("gltfpack has no stand-alone decoder: its decode time is not measured; its PSNR "
                 "is that of `gltfpack -vp N` without -cc (the same quantization), loaded through "
                 "KHR_mesh_quantization.")
        L.append("")
        # BD-rates and ratios
        L.append("### BD-rate and size ratios (negative BD-rate: eqmesh needs fewer bytes)")
        L.append("")
        L.append("| eqmesh curve | anchor | BD-rate |")
        L.append("|---|---|---|")
        pairs = [("eq-best", "draco-best"), ("eq-best", "gltfpack"), ("eq-best", "gltfpack-gzip"),
                 ("eq-lifted", "draco-best"), ("eq-unlifted", "draco-best"),
                 ("eq-best-glb", "draco-best-glb"), ("eq-best-glb", "gltfpack-glb"),
                 ("eq-lifted", "zerotree-lifted"), ("eq-unlifted", "zerotree-unlifted")]
        bdv = {}
        for test, anchor in pairs:
            if test not in c and anchor not in c:
                continue
            pct, text = bd(c, anchor, test)
            bdv[(test, anchor)] = pct
            L.append("| %s | %s | %s |" % (test, anchor, text))
        L.append("")
        L.append("| PSNR | Draco best / eqmesh | gltfpack / eqmesh | gltfpack+gzip / eqmesh "
                 "| eqmesh bpv | Draco bpv |")
        L.append("|---|---|---|---|---|---|")
        ratios = {}
        for target in (70.0, 80.0):
            eb = c.get("eq-best", [])
            rd = bdrate.size_ratio(c.get("draco-best", []), eb, target)
            rg = bdrate.size_ratio(c.get("gltfpack", []), eb, target)
            rz = bdrate.size_ratio(c.get("gltfpack-gzip", []), eb, target)
            ratios[target] = rd
            L.append("| %g dB | %s | %s | %s | %s | %s |" % (
                target, fmt(rd, "%.2f x"), fmt(rg, "%.2f x"), fmt(rz, "%.2f x"),
                fmt(bdrate.rate_at_psnr(eb, target), "%.3f"),
                fmt(bdrate.rate_at_psnr(c.get("draco-best", []), target), "%.3f")))
        L.append("")
        # timings
        eq_tps = median([r["decode_tri_per_s"] for r in eqr if r["variant"].startswith("eq-")])
        dr_tps = median([r["decode_tri_per_s"] for r in ok_rows(rows, mesh, "draco")])
        rem_enc = [(r["remesh_s"] or 0) + (r["encode_s"] or 0) for r in eqr]
        per_m = max(rem_enc) / (meta["triangles"] / 1e6) if rem_enc else None
        L.append("### Timings")
        L.append("")
        L.append("Median decode throughput (output triangles per second, decode only): eqmesh %s "
                 "Mtri/s (EQ points), Draco %s Mtri/s (all cl/qp). Remesh + encode: worst %s s per "
                 "million input triangles (remesh %s s once per mesh%s)." % (
                     fmt(eq_tps and eq_tps / 1e6), fmt(dr_tps and dr_tps / 1e6), fmt(per_m, "%.1f"),
                     fmt(meta.get("remesh_s")),
                     "" if meta.get("srm") else "; repeated inside every encode"))
        L.append("")
        L.append("![rate-distortion](rd_%s.png)" % mesh)
        L.append("")
        # analysis
        L.append("### Analysis")
        L.append("")
        A = []
        for t in ("lifted", "unlifted"):
            e, z = c.get("eq-" + t), c.get("zerotree-" + t)
            if e and z:
                diffs = []
                for b in rates:
                    pe = [r["psnr_db"] for r in eqr if r["variant"] == "eq-" + t and r["param"] == b]
                    pz = bdrate.psnr_at_rate(z, [r["bpv"] for r in eqr if r["variant"] == "eq-" + t
                                                 and r["param"] == b][0]) if pe else None
                    if pe and pz is not None:
                        diffs.append((b, pe[0] - pz))
                if diffs:
                    mn = min(diffs, key=lambda x: x[1])
                    A.append("EQ vs ZT (%s): EQ minus ZT PSNR at equal rate ranges %+.2f to %+.2f "
                             "dB (lowest at %g bpv)." % (t, mn[1], max(d for _, d in diffs), mn[0]))
                    ok = all(d >= 0.5 for _, d in diffs)
                    checks.append(("EQ >= ZT + 0.5 dB over 0.25-4 bpv (%s, %s)" % (mesh, t),
                                   ok, "min %+.2f dB at %g bpv" % (mn[1], mn[0])))
            elif e:
                checks.append(("EQ >= ZT + 0.5 dB over 0.25-4 bpv (%s, %s)" % (mesh, t), None,
                               "zerotree coder not available"))
        if c.get("eq-lifted") and c.get("eq-unlifted"):
            pl, pu = [], []
            for b in rates:
                a1 = [r for r in eqr if r["variant"] == "eq-lifted" and r["param"] == b]
                a2 = [r for r in eqr if r["variant"] == "eq-unlifted" and r["param"] == b]
                if a1 and a2:
                    pl.append(a1[0]["psnr_db"] - a2[0]["psnr_db"])
            if pl:
                A.append("Lifted minus unlifted at the same target rate: %+.2f to %+.2f dB "
                         "(mean %+.2f)." % (min(pl), max(pl), sum(pl) / len(pl)))
        ceil = meta.get("remesh_psnr")
        if ceil and c.get("eq-best"):
            top = max(p for _, p in c["eq-best"])
            near = [b for b, p in sorted(c["eq-best"]) if p >= ceil - 1.0]
            A.append("Remesh ceiling %.2f dB; best eqmesh point %.2f dB (%.2f dB below). %s" % (
                ceil, top, ceil - top,
                ("The curve comes within 1 dB of the ceiling from %.2f bpv on: beyond that, more "
                 "bits cannot help; only a finer remesh can." % near[0]) if near else
                "The curve stays more than 1 dB below the ceiling at every rate measured."))
        pct = bdv.get(("eq-best", "draco-best"))
        if pct is not None:
            A.append("BD-rate against Draco (best cl): %+.1f %%; against gltfpack %s; against "
                     "gltfpack+gzip %s." % (pct, fmt(bdv.get(("eq-best", "gltfpack")), "%+.1f %%"),
                                            fmt(bdv.get(("eq-best", "gltfpack-gzip")), "%+.1f %%")))
        else:
            eb = c.get("eq-best", [])
            db = c.get("draco-best", [])
            if eb and db:
                A.append("No BD-rate against Draco: eqmesh covers %.1f-%.1f dB, Draco %.1f-%.1f dB."
                         % (min(p for _, p in eb), max(p for _, p in eb),
                            min(p for _, p in db), max(p for _, p in db)))
        eq_max_bpv = max([b for k in ("eq-lifted", "eq-unlifted") for b, _ in c.get(k, [])] or [0])
        for target, need in ((70.0, 8.0), (80.0, 4.0)):
            r = ratios.get(target)
            eb = c.get("eq-best", [])
            why = ("eqmesh reaches at most %.2f dB" % max(p for _, p in eb)) if eb and \
                bdrate.rate_at_psnr(eb, target) is None else "Draco does not cover it"
            verdict = None if r is None else r >= need
            detail = "%.2fx" % r if r is not None else "not measurable: " + why
            drate = bdrate.rate_at_psnr(c.get("draco-best", []), target)
            if r is None and eb and drate is not None and bdrate.rate_at_psnr(eb, target) is None \
                    and max(p for _, p in eb) < target and eq_max_bpv >= drate / need:
                # We measured up to the rate the target allows and never reached the PSNR.
                verdict = False
                detail = ("eqmesh stays below %g dB (max %.2f dB) up to %.2f bpv, while %gx smaller "
                          "than Draco would be %.2f bpv (Draco: %.2f bpv)" % (
                              target, max(p for _, p in eb), eq_max_bpv, need,
                              drate / need, drate))
            checks.append(("at %g dB our stream >= %gx smaller than Draco's best (%s)" % (
                target, need, mesh), verdict, detail))
        small = meta["triangles"] < 20000
        if small:
            A.append("%d triangles is too few to judge speed per triangle (process start-up and "
                     "Draco's 1 ms timer resolution dominate): the speed expectations are n/a here."
                     % meta["triangles"])
        if eq_tps and dr_tps and not small:
            checks.append(("decoder >= 2x Draco's output triangles/s (%s)" % mesh,
                           eq_tps >= 2 * dr_tps, "%.2f vs %.2f Mtri/s (%.2fx)" % (
                               eq_tps / 1e6, dr_tps / 1e6, eq_tps / dr_tps)))
        if per_m is not None and not small:
            checks.append(("remesh + encode <= 30 s per million input triangles (%s)" % mesh,
                           per_m <= 30, "worst %.1f s/Mtri" % per_m))
        L.extend("- " + a for a in A)
        L.append("")
    L.append("## Expectations of the issue")
    L.append("")
    L.append("| expectation | verdict | measured |")
    L.append("|---|---|---|")
    for text, ok, detail in checks:
        L.append("| %s | %s | %s |" % (text, "n/a" if ok is None else ("holds" if ok else "**FAILS**"),
                                       detail))
    fails = [t for t, ok, _ in checks if ok is False]
    L.append("")
    nas = [t for t, ok, _ in checks if ok is None]
    L.append("Failing: " + ("; ".join(fails) if fails else "none") + ".")
    if nas:
        L.append("")
        L.append("Not measurable in this run (%d): %s." % (len(nas), "; ".join(nas)))
    errs = [r for r in rows if r["error"]]
    if errs:
        L.append("")
        L.append("## Errors (%d)" % len(errs))
        L.append("")
        for r in errs:
            L.append("- %s %s %s %s: %s" % (r["mesh"], r["codec"], r["variant"] or "",
                                           r["param"] if r["param"] is not None else "", r["error"]))
    with open(path, "w") as f:
        f.write("\n".join(L) + "\n")
    return path


def write_outputs(bench, started):
    csv_path = bench.write_csv()
    pngs = []
    for name in bench.meta:
        png = os.path.join(bench.args.out, "rd_%s.png" % name)
        if plot_mesh(bench.rows, name, bench.meta[name], png, bench.args.work):
            pngs.append(png)
    summary = write_summary(bench, started, os.path.join(bench.args.out, "summary.md"))
    return csv_path, summary, pngs


def cap_word(cap):
    """yes / no for a capability of the binary; None: not known (merged rows)."""
    return "as in log.txt" if cap is None else ("yes" if cap else "no")


def report_from_csv(args):
    """Rebuilds summary.md and the plots from earlier results.csv files (e.g. meshes run by
    separate invocations) without running any codec."""
    args.out = os.path.abspath(args.out)
    os.makedirs(args.out, exist_ok=True)
    rows = []
    for path in args.from_csv:
        with open(path, newline="") as f:
            for raw in csv.DictReader(f):
                row = {}
                for k in CSV_FIELDS:
                    v = raw.get(k, "")
                    if k in ("mesh", "codec", "variant", "error") or v == "":
                        row[k] = v if v != "" else None
                        continue
                    try:
                        row[k] = int(v)
                    except ValueError:
                        try:
                            row[k] = float(v)
                        except ValueError:
                            row[k] = v
                rows.append(row)
    bench = types.SimpleNamespace(rows=rows, errors=sum(1 for r in rows if r["error"]), meta={})
    args.runs = max([r["runs"] for r in rows if isinstance(r["runs"], int)] or [0])
    args.eqmesh = args.eqmesh or "(from %s)" % ", ".join(args.from_csv)
    bench.args = args
    bench.write_csv = lambda: Bench.write_csv(bench)
    # Whether the merged runs reused their remesh is in their log.txt, not in the rows.
    bench.caps = {"zerotree": any((r["variant"] or "").startswith("zerotree") for r in rows),
                  "srm": None, "convert": True,
                  "glb": any(r["codec"] == "eqmesh" and r["bytes_glb"] for r in rows)}
    for r in rows:
        m = bench.meta.setdefault(r["mesh"], {"name": r["mesh"], "vertices": r["input_vertices"],
                                              "triangles": r["triangles"], "samples": r["samples"],
                                              "dropped": None})
        if r["codec"] == "remesh" and not r["error"]:
            m.update(remesh_psnr=r["psnr_db"], remesh_s=r["remesh_s"], remesh_levels=r["param"])
        os.makedirs(os.path.join(args.work, r["mesh"]), exist_ok=True)
    started = datetime.datetime.fromtimestamp(min(os.path.getmtime(p) for p in args.from_csv))
    global LOG
    LOG = open(os.path.join(args.out, "log.txt"), "a")
    csv_path, summary, pngs = write_outputs(bench, started)
    log("merged %d rows: wrote %s, %s, %d plot(s)" % (len(rows), csv_path, summary, len(pngs)))
    return 0


def find_eqmesh():
    env = os.environ.get("EQMESH")
    if env:
        return env
    cands = []
    for d in os.listdir(ROOT):
        p = os.path.join(ROOT, d, "tools", "eqmesh")
        if d.startswith("build") and os.access(p, os.X_OK):
            cands.append((os.path.getmtime(p), p))
    if not cands:
        sys.exit("run_bench.py: no eqmesh binary found; build it or pass --eqmesh PATH")
    return max(cands)[1]


def main():
    global LOG
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--meshes", nargs="+", help="meshes to run (default: shared bench meshes)")
    ap.add_argument("--quick", action="store_true",
                    help="smoke run: bunny_npm, EQ unlifted at 1 and 4 bpv, Draco qp 10/12 cl 10, "
                         "gltfpack vp 12, one timing run")
    ap.add_argument("--out", default=os.path.join(HERE, "out"), help="output folder")
    ap.add_argument("--work", help="intermediate files (default OUT/work)")
    ap.add_argument("--eqmesh", help="eqmesh binary (default: $EQMESH or newest build*/tools/eqmesh)")
    ap.add_argument("--runs", type=int, help="timing runs per point, median reported "
                                             "(default 5, quick 1)")
    ap.add_argument("--encode-runs-full", action="store_true",
                    help="repeat eqmesh encode --runs times even when it must remesh every time "
                         "(default: once unless .srm input is supported)")
    ap.add_argument("--encode-runs", type=int,
                    help="timed eqmesh encode runs per point (default: --runs when encode reads .srm)")
    ap.add_argument("--glb-rates", type=float, nargs="*",
                    help="bpv values at which the whole-GLB size is also measured (default 1)")
    ap.add_argument("--no-peers", action="store_true",
                    help="run eqmesh only (e.g. to add points to an earlier run, merged with --from-csv)")
    ap.add_argument("--variants", nargs="+",
                    help="eqmesh variants to run, e.g. eq-unlifted zerotree-unlifted (default: all)")
    ap.add_argument("--rates", type=float, nargs="+",
                    help="eqmesh target bpv (default 0.25 0.5 1 2 3 4)")
    ap.add_argument("--qps", type=int, nargs="+",
                    help="Draco -qp and gltfpack -vp values (default 8..16)")
    ap.add_argument("--from-csv", nargs="+", metavar="CSV",
                    help="run nothing: merge these results.csv files and rewrite summary.md and "
                         "the plots in --out")
    ap.add_argument("--skip-large", action="store_true", help="skip dragon_vrip (437k vertices)")
    ap.add_argument("--samples", type=int, help="eqmesh compare --samples for every comparison "
                                                "(default max(1M, 10 x vertices); quick 200k)")
    args = ap.parse_args()
    args.work = os.path.abspath(args.work or os.path.join(args.out, "work"))
    if args.from_csv:
        return report_from_csv(args)
    args.eqmesh = os.path.abspath(args.eqmesh) if args.eqmesh else find_eqmesh()
    if args.runs is None:
        args.runs = 1 if args.quick else 5
    args.out = os.path.abspath(args.out)
    os.makedirs(args.out, exist_ok=True)
    LOG = open(os.path.join(args.out, "log.txt"), "w")
    global TIME_DIR
    TIME_DIR = args.work
    os.makedirs(TIME_DIR, exist_ok=True)
    for tool in ("draco_encoder", "draco_decoder", "gltfpack"):
        if not shutil.which(tool):
            sys.exit("run_bench.py: %s not found (Debian packages draco, gltfpack)" % tool)
    if args.meshes:
        meshes = args.meshes
    elif args.quick:
        if not os.path.exists(QUICK_MESH):
            print("run_bench.py: %s not found: skipping the quick bench" % QUICK_MESH)
            return 77  # ctest SKIP_RETURN_CODE
        meshes = [QUICK_MESH]
    else:
        meshes = [os.path.join(SHARED, "meshes", "bench", m) for m in BENCH_MESHES]
    if args.skip_large:
        meshes = [m for m in meshes if os.path.basename(m).split(".")[0] not in LARGE]
    bench = Bench(args)
    started = datetime.datetime.now()
    for path in meshes:
        try:
            bench.mesh(path)
        except (StepError, KeyError, ValueError, OSError) as e:
            bench.add(mesh=os.path.basename(path).split(".")[0], codec="input", error=str(e))
        csv_path, summary, pngs = write_outputs(bench, started)  # after each mesh: partial results
    if not meshes:
        csv_path, summary, pngs = write_outputs(bench, started)
    log("wrote %s, %s, %d plot(s); %d error(s)" % (csv_path, summary, len(pngs), bench.errors))
    if args.quick and (bench.errors or len(pngs) != len(bench.meta)):
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
