#!/usr/bin/python3
"""devices.py - swell's shaders through the real GPUs' compilers (issue 15).

Runs swell (surfaceless, one frame) under Mesa's own drivers for the target GPUs with their noop
drm-shims (tools/mesa-shim.sh builds them), on every tier swell picks there and on forced
gles2-min, in both qualities. swell's start-up probe (src/render/renderer.c probe_programs) draws every
ocean variant and the sky once, each between two labelled lines on stderr
(SWELL_SHADER_LABELS=1), so the statistics each driver prints while compiling it (MESA_DEBUG=
context and the driver's shaderdb switch) are told apart by program. Each is run again with the
demo boat and a wave mask (--boat --mask: an ocean with reflections, wakes, shadows,
refractions and the mask), whose ocean programs (named with " objects") are recorded too; the frame-rate estimates are the sea's
alone.

Writes build/devices/results.json (one record per GPU model, tier, quality, program and stage)
and docs/devices.md, and exits 1 when a program does not compile or run, spills, or exceeds 90 %
of a hard limit of its GPU.

usage: tools/devices.py [--build DIR] [--only NAME,...] [--prefix MESA_PREFIX]
"""
import argparse
import json
import os
import re
import subprocess
import sys

# GPU models: the driver Mesa loads, its shim, the switches that select the model and make it
# print statistics, and the hard limits known per stage (instructions; None: none known).
MODELS = [
    dict(name="Mali-450", driver="lima", shim="lima", env={"LIMA_DEBUG": "shaderdb"},
         limits={"vertex": 512}, cost="inst"),
    dict(name="VideoCore IV", driver="vc4", shim="vc4", env={"VC4_DEBUG": "shaderdb"},
         limits={}, fs_threads=2, cost="estimated-cycles"),
    dict(name="VideoCore VI", driver="v3d", shim="v3d", env={"V3D_DEBUG": "shaderdb"},
         limits={}, cost="inst-and-stalls"),
    dict(name="Mali-G31", driver="panfrost", shim="panfrost",
         env={"PAN_GPU_ID": "0x7093", "BIFROST_MESA_DEBUG": "shaderdb"}, limits={},
         cost="tuples"),
    dict(name="Mali-T860", driver="panfrost", shim="panfrost",
         env={"PAN_GPU_ID": "0x860", "MIDGARD_MESA_DEBUG": "shaderdb"}, limits={},
         cost="bundles"),
    dict(name="Adreno 307", driver="msm", shim="freedreno",
         env={"FD_GPU_ID": "307", "FD_MESA_DEBUG": "shaderdb"}, limits={}, cost="inst"),
    dict(name="Adreno 530", driver="msm", shim="freedreno",
         env={"FD_GPU_ID": "530", "FD_MESA_DEBUG": "shaderdb"}, limits={}, cost="inst"),
    dict(name="Adreno 630", driver="msm", shim="freedreno",
         env={"FD_GPU_ID": "630", "FD_MESA_DEBUG": "shaderdb"}, limits={}, cost="inst"),
    dict(name="GC2000", driver="etnaviv", shim="etnaviv",
         env={"ETNA_SHIM_GPU": "GC2000", "ETNA_MESA_DEBUG": "shaderdb"},
         limits={"vertex": 256, "fragment": 256}, etna=True, cost="instructions"),
    dict(name="GC3000", driver="etnaviv", shim="etnaviv",
         env={"ETNA_SHIM_GPU": "GC3000", "ETNA_MESA_DEBUG": "shaderdb"}, limits={}, etna=True,
         cost="instructions"),
    dict(name="GC7000L", driver="etnaviv", shim="etnaviv",
         env={"ETNA_SHIM_GPU": "GC7000L", "ETNA_MESA_DEBUG": "shaderdb"}, limits={},
         etna=True, cost="instructions"),
]

# The cost model (docs/devices.md states it): a board's fragment rate is its clock times the
# pixel-cost units it retires per cycle (lanes) over the compiler's cost per pixel of the
# program (the statistic named by the model's cost above: lima and ir3 instructions, vc4's
# estimated cycles, v3d's instructions and stalls, Bifrost's tuples,
# Midgard's bundles, etnaviv's instructions); a frame's time is the sum over programs of its
# share of the screen (measured: swell --debug variants on llvmpipe, same tier, quality, size
# and view) times the pixels times that cost, plus every grid vertex through the vertex
# shader at vs_lanes. Clocks and lanes are the boards' published figures, assumed, not
# measured: no GPU ran anything. Targets: issue 15 item 4.
BOARDS = [
    dict(board="Mali-400 MP2 (500 MHz)", model="Mali-450", clock=500e6, lanes=2, vs_lanes=1,
         note="2 fragment processors, one instruction word a cycle each; one vertex processor "
              "(lima compiles the Mali-400 and -450 ISA alike)",
         targets={("high", "1280x720"): 30, ("low", "1920x1080"): 60}),
    dict(board="Raspberry Pi 3, VideoCore IV (300 MHz)", model="VideoCore IV", clock=300e6,
         lanes=48, vs_lanes=48, note="12 QPUs of 4 lanes (a 16-wide instruction in 4 cycles)",
         targets={("high", "1280x720"): 30}),
    dict(board="Raspberry Pi 4, VideoCore VI (500 MHz)", model="VideoCore VI", clock=500e6,
         lanes=32, vs_lanes=32, note="8 QPUs of 4 lanes", targets={("high", "1920x1080"): 60}),
    dict(board="Mali-G31 MP2 (650 MHz)", model="Mali-G31", clock=650e6, lanes=8, vs_lanes=8,
         note="2 cores of one 4-lane execution engine, a tuple a lane a cycle (Mesa's Bifrost "
              "'cycles' are normalised to a wider core, so its tuples are counted)",
         targets={("high", "1280x720"): 60}),
    dict(board="Mali-T860 MP4 (800 MHz, RK3399)", model="Mali-T860", clock=800e6, lanes=8,
         vs_lanes=8, note="4 cores of 2 arithmetic pipes, a bundle a cycle each", targets={}),
    dict(board="Adreno 307 (600 MHz)", model="Adreno 307", clock=600e6, lanes=32, vs_lanes=32,
         note="32 ALU lanes (assumed, like the Adreno 306/308)", targets={}),
    dict(board="Adreno 530 (624 MHz)", model="Adreno 530", clock=624e6, lanes=256,
         vs_lanes=256, note="256 ALU lanes", targets={}),
    dict(board="Adreno 630 (710 MHz)", model="Adreno 630", clock=710e6, lanes=512,
         vs_lanes=512, note="512 ALU lanes", targets={}),
    dict(board="i.MX6 Quad, GC2000 (594 MHz)", model="GC2000", clock=594e6, lanes=4,
         vs_lanes=4, note="4 vec4 shader cores, one instruction a cycle each", targets={}),
    dict(board="i.MX6 QuadPlus, GC3000 (720 MHz)", model="GC3000", clock=720e6, lanes=4,
         vs_lanes=4, note="4 vec4 shader cores", targets={}),
    dict(board="i.MX8M, GC7000L (800 MHz)", model="GC7000L", clock=800e6, lanes=4, vs_lanes=4,
         note="4 vec4 shader cores (16 ALU lanes)", targets={}),
]
SIZES = ("1280x720", "1920x1080")
# render scales estimated (swell --scale, src/render/upscale.h): the frame drawn at scale x the output
# and stretched over it; the devices' runs build the stretch at the last one
SCALES = (1.0, 0.5)
VIEWS = [("default", []), ("surface", ["--path", "surface"]), ("1km", ["--path", "1km"]),
         ("10km", ["--path", "10km"])]

STAGES = {
    "MESA_SHADER_VERTEX": "vertex", "VERT": "vertex", "MESA_SHADER_POSITION": "vertex",
    "MESA_SHADER_FRAGMENT": "fragment", "FRAG": "fragment",
    "MESA_SHADER_VERTEX_BIN": "binning", "BVERT": "binning",
    "MESA_SHADER_VARYING": "varying",   # Bifrost splits the vertex stage: position, varyings
}
STATS = re.compile(r"^Mesa debug output: (\S+) shader: (.*)$")
PROBE = re.compile(r"^swell-program: probe (.*)$")
END = re.compile(r"^swell-program: end (ok|refused)$")


def parse_fields(text):
    """'2389 inst, 1 threads, 0:0 spills:fills, 0.5 cycles' -> {'inst': 2389, ...}"""
    out = {}
    for part in text.split(","):
        part = part.strip()
        m = re.match(r"^(\d+):(\d+) spills:fills$", part)
        if m:
            out["spills"] = int(m.group(1))
            out["fills"] = int(m.group(2))
            continue
        m = re.match(r"^([0-9.]+) (\S+)$", part)
        if m:
            v = float(m.group(1))
            out[m.group(2)] = int(v) if v.is_integer() else v
    return out


BEGIN = re.compile(r"^swell-program: begin (\S+) \+ (\S+) \[(.*)\] tier (\S+)$")


def program_name(vs, defines, fs=""):
    """The probe's name for a build: 'ocean k=1 kw=0 high', then ' cpu-vertex' with the
    vertex's terms on the CPU and ' no-detile' without the lattice (renderer.c
    renderer_program_name), 'sky', 'sky sun'; the reflection atlas's copy (reflect.c, an
    objects program) 'reflection copy objects'."""
    d = dict(kv.split("=", 1) if "=" in kv else (kv, "") for kv in defines.split())
    if vs.startswith("ocean"):
        objects = any(k in d for k in ("SWELL_REFLECT", "SWELL_WAKE", "SWELL_SHADOW",
                                       "SWELL_REFRACT", "SWELL_MASK"))
        return "ocean k=%s kw=%s %s%s%s%s" % (
            d.get("FS_PATTERNS", "?"), d.get("FS_WHITECAPS", "?"),
            "high" if "QUALITY_HIGH" in d else "low",
            " cpu-vertex" if "CPU_VERTEX_TERMS" in d else "",
            " no-detile" if "SWELL_NO_DETILE" in d else "",
            " objects" if objects else "")
    if fs.startswith("refl_copy"):
        return "reflection copy objects"
    if fs.startswith("stream_blend"):
        return "loop blend"
    if vs.startswith("upscale"):
        return "upscale"
    if vs.startswith("boat"):
        return "boat"
    return "sky sun" if "SUN_DISC" in d else "sky"


def parse_log(text, model):
    """The records of one run: per program, per stage, the largest shader the driver compiled
    while swell built it (some drivers compile at link) or while the probe drew it (others at
    the first draw); the smaller ones in those spans are Mesa's own clears and blits. The
    probe's verdict says whether the driver runs it. Programs are told apart by name and tier:
    where swell retries a tier (swell.c), the same names come again, built for another one."""
    gpu = tier = None
    stats, status, tiers, order = {}, {}, {}, []
    span = None
    for line in text.splitlines():
        m = re.match(r"^swell: GL (.*)$", line)
        if m:
            gpu = m.group(1).split(" | ")[1] if " | " in m.group(1) else m.group(1)
        m = BEGIN.match(line)
        if m:
            tier = m.group(4)
            span = [(program_name(m.group(1), m.group(3), m.group(2)), tier)]
            tiers[span[0]] = tier
            if span[0] not in order:
                order.append(span[0])
            continue
        m = PROBE.match(line)
        if m:
            span = [("sky", tier), ("sky sun", tier)] if m.group(1) == "sky" else \
                [(m.group(1), tier)]
            continue
        m = STATS.match(line)
        if m and span:
            stage = STAGES.get(m.group(1))
            if stage is None:
                continue
            f = parse_fields(m.group(2))
            n = f.get("inst", f.get("instructions", 0))
            if model.get("etna") and "instructions" in f:
                n = f["instructions"] // 4   # etnaviv reports its code size in dwords
            f["n"] = n
            c = f.get(model["cost"])
            f["cost"] = (c // 4 if model.get("etna") else c) if c is not None else None
            prog = span[0] if len(span) == 1 else None
            for name in ([prog] if prog else span):
                st = stats.setdefault(name, {})
                if stage not in st or n > st[stage]["n"]:
                    st[stage] = f
                if prog is None:
                    break   # the sky's span: the larger shaders are the first program's
            continue
        m = END.match(line)
        if m:
            for name in span or []:
                status[name] = m.group(1) == "ok"
            span = None
            continue
        if line == "swell-program: end":
            span = None
    records = []
    for name in order:
        st = stats.get(name, {})
        ok = status.get(name)
        for stage in sorted(set(st) | {"vertex", "fragment"}):
            f = st.get(stage)
            if stage in ("binning", "varying") and f is None:
                continue
            records.append(dict(gpu=gpu, model=model["name"], tier=tiers.get(name), program=name[0],
                                stage=stage, probed=ok is not None, compiled=bool(ok),
                                instructions=f["n"] if f else None,
                                limit=model["limits"].get(stage),
                                spills=f.get("spills") if f else None,
                                threads=f.get("threads") if f else None,
                                cycles=(f.get("estimated-cycles", f.get("cycles")) if f else None),
                                cost=f.get("cost") if f else None))
    return gpu, tier, records


def problems(rec, model):
    """What breaks issue 15's fit (item 3) in one record: (kind, text) pairs; the kind names the
    problem without its numbers (known_key)."""
    out = []
    if not rec["probed"]:
        out.append(("not probed", "not probed (swell stopped before)"))
    elif not rec["compiled"]:
        out.append(("refused", "refused by the driver"))
    if rec["spills"]:
        out.append(("spills", "%d spills" % rec["spills"]))
    if rec["limit"] and rec["instructions"] and rec["instructions"] > 0.9 * rec["limit"]:
        out.append(("over 90 %", "%d of %d instructions (over 90 %%)" % (rec["instructions"],
                                                                      rec["limit"])))
    want = model.get("fs_threads")
    if want and rec["stage"] == "fragment" and rec["threads"] and rec["threads"] < want:
        out.append(("threads", "%d thread(s), not %d" % (rec["threads"], want)))
    return out


def known_key(model, tier, quality, program, stage, kinds):
    """A problem as tests/devices/known-problems.txt lists it: where, and its kinds without
    numbers (a spill count that falls is not a new problem; a variant that starts to spill is)."""
    return "%s | %s | %s | %s | %s | %s" % (model, tier, quality, program, stage,
                                           ", ".join(sorted(kinds)))


def mesa_version(prefix):
    """The Debian version of the Mesa built under prefix (tools/mesa-shim.sh's cache key)."""
    return os.path.basename(os.path.dirname(prefix.rstrip("/"))).rsplit("-", 1)[0]


def read_known(path):
    keys = set()
    with open(path) as f:
        for line in f:
            line = line.strip()
            if line and not line.startswith("#"):
                keys.add(line)
    return keys


SHARE = re.compile(r"^swell: frame \d+: screen share: (.*)$")
USE = re.compile(r"refused \d+ ocean program\(s\)(?: \[([^\]]*)\])?;[^:]*: "
                 r"((?:\d+/\d+->\d+/\d+ ?)+)")
BUILD = re.compile(r"^programs: ocean k=K kw=KW (\S+)((?: [a-z-]+)*) \(")


def measure_shares(root, build, tables, tier, quality, detile, size, view, cache):
    """The screen's share of each ocean program and of the sky in one frame of a view, drawn on
    llvmpipe (the host's Mesa, not a shim: it draws) with swell --debug variants; and the grid's
    vertex count."""
    key = (tier, quality, detile, size, view[0])
    if key in cache:
        return cache[key]
    cmd = [os.path.join(build, "swell"), "--platform", "surfaceless", "--tables", tables,
           "--size", size, "--frames", "1", "--quality", quality, "--debug", "variants",
           "--verbose"] + view[1] + ([] if detile else ["--detile", "off"])
    if tier:
        cmd += ["--tier", tier]
    p = subprocess.run(cmd, cwd=root, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True, timeout=300)
    shares, verts = {}, None
    for line in p.stdout.splitlines():
        m = SHARE.match(line)
        if m:
            for part in m.group(1).split("; "):
                name, val = part.rsplit(" ", 1)
                shares[name] = float(val)
        m = re.search(r"(\d+) vertices,", line)
        if m:
            verts = int(m.group(1))
        m = re.search(r"blended on the GPU .*?(\d+) texels drawn a frame", line)
        if m:   # the loop blend's draws (render/stream_gpu.c), whatever the frame's size
            shares["_blend_texels"] = float(m.group(1))
    if p.returncode != 0 or not shares:
        sys.exit("devices: share run failed (%s): %s" % (" ".join(cmd), p.stdout[-400:]))
    cache[key] = (shares, verts)
    return cache[key]


def drawn_as(name, use, have, tags):
    """The program a device draws program name's rows with: swell's fallback (use: 'k/kw' ->
    'k/kw', printed at start-up) where it refused it; for a variant the device did not build
    (fewer texture units: fewer whitecap tables), the one with the same slope fetches and the
    most whitecap fetches it has, or its fallback."""
    m = re.match(r"^ocean k=(\d+) kw=(\d+) (\S+)", name)
    k, kw, q = int(m.group(1)), int(m.group(2)), m.group(3) + (" " + tags if tags else "")
    for w in range(kw, -1, -1):
        u = use.get("%d/%d" % (k, w))
        c = "ocean k=%s kw=%s %s" % (tuple(u.split("/")) + (q,)) if u else \
            "ocean k=%d kw=%d %s" % (k, w, q)
        if c in have:
            return c
    return None


def estimate(board, run, records, shares, verts, size, scale):
    """Frames per second by the cost model (BOARDS), or None where a program drawn has no cost
    statistic; with the ms per frame of fragment and vertex work. At a render scale below 1
    the shares are the scaled frame's and the stretch (one 'upscale' pass over every output
    pixel) is added; so are the loop blend's texels (render/stream_gpu.c, 'loop blend')."""
    cost = {}
    for r in records:
        if r["model"] == board["model"] and r["tier"] == run["tier"] and \
                r["quality_asked"] == run["quality"] and r["tier_asked"] == run["tier_asked"] \
                and r["compiled"]:
            cost[(r["program"], r["stage"])] = r["cost"]
    have = {p for (p, st) in cost if p.startswith("ocean")}
    w, h = (int(x) for x in size.split("x"))
    px, frag, vs = round(w * scale) * round(h * scale), 0.0, 0.0
    worst = 0
    for name, share in shares.items():
        if name == "mixed" or name.startswith("_"):
            continue
        prog = "sky" if name == "sky" else drawn_as(name, run["use"], have, run["tags"])
        c = cost.get((prog, "fragment")) if prog else None
        if c is None:
            return None
        frag += share * px * c
        if prog != "sky":
            vs = max(vs, cost.get((prog, "vertex")) or 0)
            worst = max(worst, c)
    frag += shares.get("mixed", 0.0) * px * worst   # drawn twice: at the costliest
    if shares.get("_blend_texels"):
        frag += shares["_blend_texels"] * (cost.get(("loop blend", "fragment")) or 0.0)
    if scale < 1:
        c = cost.get(("upscale", "fragment"))
        if c is None:
            return None
        frag += w * h * c
    t_frag = frag / (board["clock"] * board["lanes"])
    t_vert = verts * vs / (board["clock"] * board["vs_lanes"])
    return dict(fps=1.0 / (t_frag + t_vert), ms_fragment=1e3 * t_frag, ms_vertex=1e3 * t_vert)


def run(args):
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    build = os.path.join(root, args.build)
    out_dir = os.path.join(root, "build", "devices")
    os.makedirs(out_dir, exist_ok=True)
    prefix = args.prefix or subprocess.run(
        [os.path.join(root, "tools", "mesa-shim.sh")], check=True, stdout=subprocess.PIPE,
        text=True).stdout.strip().splitlines()[-1]
    lib = None
    for cand in (os.path.join(prefix, "lib", "x86_64-linux-gnu"), os.path.join(prefix, "lib")):
        if os.path.exists(os.path.join(cand, "libEGL.so.1")):
            lib = cand
            break
    if not lib:
        sys.exit("devices: no libEGL.so.1 under %s" % prefix)
    tables = os.path.join(out_dir, "tables")
    if not os.path.exists(os.path.join(tables, "manifest.swell")):
        subprocess.run([os.path.join(build, "swell-bake"), "--preset", "moderate", "--out",
                        tables], check=True, stdout=subprocess.DEVNULL, cwd=root)
    only = set(args.only.split(",")) if args.only else None
    all_records, failures, runs = [], [], []
    for model in MODELS:
        if only and model["name"] not in only:
            continue
        for tier, quality, boat in ((t, q, b) for b in (False, True)
                                    for t in ("auto", "gles2-min") for q in ("high", "low")):
                env = dict(os.environ)
                env.update(model["env"])
                env.update({"LD_LIBRARY_PATH": lib, "LIBGL_DRIVERS_PATH": os.path.join(lib, "dri"),
                            "MESA_LOADER_DRIVER_OVERRIDE": model["driver"],
                            "LD_PRELOAD": os.path.join(lib, "lib%s_noop_drm_shim.so" % model["shim"]),
                            "MESA_DEBUG": "context", "SWELL_SHADER_LABELS": "1",
                            # a program found in Mesa's disk cache is not compiled: no numbers
                            "MESA_SHADER_CACHE_DISABLE": "true"})
                cmd = [os.path.join(build, "swell"), "--platform", "surfaceless", "--tables",
                       tables, "--size", "640x360", "--frames", "1", "--quality", quality,
                       "--out", os.path.join(out_dir, "frame.png"), "--scale", str(SCALES[-1])]
                if tier != "auto":
                    cmd += ["--tier", tier]
                if boat:   # 4 m/s on course 30 deg: a wake, its reflection, shadow, refraction;
                    # and the wave mask of an island's lee (every objects program has it too)
                    cmd += ["--boat", "4,30", "--mask", "docs/lee-mask.png",
                            "--mask-area", "-1280,-1280,2560,2560"]
                try:
                    p = subprocess.run(cmd, env=env, cwd=root, stdout=subprocess.PIPE,
                                       stderr=subprocess.STDOUT, text=True, timeout=120)
                    text, rc = p.stdout, p.returncode
                except subprocess.TimeoutExpired as e:
                    text, rc = (e.stdout or b"").decode(errors="replace"), "timeout"
                tag = "%s_%s_%s%s" % (model["name"].replace(" ", "-"), tier, quality,
                                      "_boat" if boat else "")
                with open(os.path.join(out_dir, tag + ".log"), "w") as f:
                    f.write(text)
                gpu, picked, recs = parse_log(text, model)
                if boat:   # the sky, upscale and sea without objects are the run's before
                    recs = [r for r in recs if r["program"].endswith(" objects")]
                for r in recs:
                    r["quality_asked"] = quality
                    r["tier_asked"] = tier
                    pr = problems(r, model)
                    r["problems"] = [t for _, t in pr]
                    if pr:
                        failures.append(("%s %s %s %s %s: %s" % (
                            model["name"], r["tier"], quality, r["program"], r["stage"],
                            "; ".join(t for _, t in pr)), known_key(
                            model["name"], r["tier"], quality, r["program"], r["stage"],
                            [k for k, _ in pr])))
                all_records += recs
                # the quality drawn: the last one renderer_open tried; after it gave up the
                # objects' passes ("trying the sea without them") the one asked first again
                tried = [(mm.start(), mm.group(1)) for mm in
                         re.finditer(r"trying (?:--)?quality (\S+)", text)]
                bare = [mm.start() for mm in re.finditer(r"trying the sea without them", text)]
                drew = quality
                if tried and (not bare or tried[-1][0] > bare[-1]):
                    drew = tried[-1][1]
                if bare:
                    drew += ", no objects"
                if rc != 0:
                    drew = "none"
                # the build drawn: with or without the lattice (the retry of --detile auto),
                # and its fallbacks
                tags = [m.group(2).strip() for m in map(BUILD.match, text.splitlines()) if m]
                tags = tags[-1] if tags else ""
                use = [u[1] for u in USE.findall(text) if u[0] == tags]
                use = dict(kv.split("->") for kv in use[-1].split()) if use else {}
                runs.append(dict(model=model["name"], gpu=gpu, tier_asked=tier, tier=picked,
                                 quality=quality, boat=boat, drew=drew, exit=rc, use=use,
                                 detile="no-detile" not in tags, tags=tags,
                                 programs=len({r["program"] for r in recs})))
                if rc != 0:
                    failures.append(("%s %s %s%s: swell exited %s (log %s.log)" %
                                     (model["name"], tier, quality, " boat" if boat else "", rc,
                                      tag), None))
                print("devices: %-12s %-9s %-4s%s exit %s, %d records" %
                      (model["name"], tier, quality, " boat" if boat else "", rc, len(recs)),
                      file=sys.stderr)
    estimates, cache = [], {}
    for board in BOARDS:
        for rn in runs:
            if rn["model"] != board["model"] or rn["exit"] != 0 or \
                    rn["drew"] != rn["quality"] or rn["boat"]:
                continue
            for size, scale in ((z, c) for z in SIZES for c in SCALES):
                w, h = (int(x) for x in size.split("x"))
                drawn = "%dx%d" % (round(w * scale), round(h * scale))
                for view in VIEWS:
                    shares, verts = measure_shares(root, build, tables, rn["tier"],
                                                   rn["quality"], rn["detile"], drawn, view,
                                                   cache)
                    e = estimate(board, rn, all_records, shares, verts, size, scale)
                    estimates.append(dict(board=board["board"], model=board["model"],
                                          tier_asked=rn["tier_asked"], tier=rn["tier"],
                                          quality=rn["quality"], size=size, scale=scale,
                                          view=view[0], shares=shares, vertices=verts,
                                          target_fps=board["targets"].get((rn["quality"], size)),
                                          **(e or dict(fps=None))))
        print("devices: estimated %s" % board["board"], file=sys.stderr)
    with open(os.path.join(out_dir, "results.json"), "w") as f:
        json.dump(dict(runs=runs, records=all_records, estimates=estimates), f, indent=1)
    write_doc(os.path.join(root, "docs", "devices.md"), runs, all_records, estimates)
    # --known: the problems listed there are expected (tests/devices/known-problems.txt, the
    # ratchet CI runs while item 3 is open); a problem not listed fails, and so does a listed
    # one that is gone, so the list only shrinks as the shaders fit
    known = read_known(args.known) if args.known else None
    seen, bad = set(), 0
    for line, key in failures:
        if known is not None and key in known:
            seen.add(key)
            continue
        bad += 1
        print("devices: FAIL " + line + ("" if known is None else "  [not in %s (Mesa %s): %s]"
                                          % (args.known, mesa_version(prefix), key)),
              file=sys.stderr)
    ran = {m["name"] for m in MODELS if not only or m["name"] in only}
    gone = sorted(k for k in known - seen if k.split(" | ")[0] in ran) if known else []
    for key in gone:
        print("devices: FIXED %s: remove it from %s" % (key, args.known), file=sys.stderr)
    print("devices: %d runs, %d records, %d problems%s; build/devices/results.json, "
          "docs/devices.md" % (len(runs), len(all_records), len(failures),
                               "" if known is None else
                               " (%d known, %d new, %d fixed)" % (len(seen), bad, len(gone))),
          file=sys.stderr)
    if args.write_known:
        keys = sorted({k for _, k in failures if k})
        with open(args.write_known, "w") as f:
            f.write("# tools/devices.py --write-known: the problems make test-devices found "
                    "(issue 15 item 3)\n# under Mesa %s, one per line: GPU | tier | quality "
                    "asked | program | stage | kinds.\n# CI fails on any problem not listed here "
                    "and on any listed one that is gone.\n" % mesa_version(prefix))
            f.write("".join(k + "\n" for k in keys))
        print("devices: %d problems written to %s" % (len(keys), args.write_known),
              file=sys.stderr)
    return 1 if bad or gone else 0


def write_doc(path, runs, records, estimates):
    lines = ["# swell on the real GPUs' compilers", "",
             "Made by `make test-devices` (tools/devices.py): swell's start-up probe draws every "
             "ocean variant and the sky once under Mesa 22.3's own drivers for each GPU, run "
             "without the hardware through Mesa's noop drm-shim; the numbers are what each "
             "driver's compiler reports (instructions; spills; threads or cycles where it "
             "says). `ok` means the program compiled and the driver ran its draw; `refused`: "
             "the driver said it cannot (swell then builds its programs again without the lattice "
             "with the terms of each vertex on the CPU, then without the lattice of random offsets, "
             "if that makes the driver refuse fewer: the 'cpu-vertex' and 'no-detile' rows; "
             "draws a refused program's rows with a variant fetching fewer patterns; or falls "
             "back to the other quality). Frame rates are estimated "
             "from the compilers' statistics by the cost model below; no GPU ran anything.", ""]
    lines += ["## Runs", "", "Build: how swell built the programs it draws with (renderer.c "
              "renderer_create: as first built, else built again with the terms of each vertex "
              "on the CPU, 'cpu-vertex', and/or without the lattice of random offsets, "
              "'no-detile', as low quality always is); programs: every one built on the way.",
              "With the boat: `swell --boat 4,30 --mask docs/lee-mask.png --mask-area "
              "-1280,-1280,2560,2560`, an ocean with reflections, wakes, shadows, refractions and "
              "the wave mask (its ocean programs are named with 'objects').",
              "", "| GPU | tier asked | tier | quality asked | boat | drawn in | build | exit | "
              "programs |", "|---|---|---|---|---|---|---|---|---|"]
    for r in runs:
        lines.append("| %s | %s | %s | %s | %s | %s | %s | %s | %d |" % (
            r["model"], r["tier_asked"], r["tier"], r["quality"], "yes" if r["boat"] else "-",
            r["drew"], r.get("tags") or "as first built", r["exit"], r["programs"]))
    lines += ["", "## Ocean programs per GPU, tier and quality", "",
              "Over the variants (each fetching 0-4 patterns and 0-4 whitecap tables): how many "
              "the driver runs, the largest vertex and fragment shader (instructions as its "
              "compiler counts them; etnaviv's code size / 4), the hard limit where one is known, "
              "the variants that spill, the fewest threads reported. Every program's record is in "
              "build/devices/results.json.", "",
              "| GPU | tier | quality | run / refused | vertex max | fragment max | limit | spilling "
              "| threads min |", "|---|---|---|---|---|---|---|---|---|"]
    groups = {}
    for r in records:
        if not r["program"].startswith("ocean"):
            continue
        key = (r["model"], r["tier"], " ".join(r["program"].split()[3:]))
        g = groups.setdefault(key, dict(run=set(), refused=set(), v=0, f=0, spill=set(),
                                        thr=None, limit=set()))
        (g["run"] if r["compiled"] else g["refused"]).add(r["program"])
        if r["instructions"]:
            if r["stage"] == "vertex":
                g["v"] = max(g["v"], r["instructions"])
            elif r["stage"] == "fragment":
                g["f"] = max(g["f"], r["instructions"])
        if r["spills"]:
            g["spill"].add(r["program"])
        if r["threads"]:
            g["thr"] = r["threads"] if g["thr"] is None else min(g["thr"], r["threads"])
        if r["limit"]:
            g["limit"].add("%s %d" % (r["stage"], r["limit"]))
    for key in sorted(groups, key=lambda k: (k[0], str(k[1]), k[2])):
        g = groups[key]
        lines.append("| %s | %s | %s | %d / %d | %s | %s | %s | %d | %s |" % (
            key[0], key[1], key[2], len(g["run"]), len(g["refused"]), g["v"] or "-", g["f"] or "-",
            ", ".join(sorted(g["limit"])) or "-", len(g["spill"]),
            g["thr"] if g["thr"] is not None else "-"))
    lines += cost_doc(estimates)
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def cost_doc(estimates):
    """docs/devices.md's estimated frame rates: per board, the tier swell picks there and forced
    gles2-min, both qualities and sizes, the default view and the slowest of the four."""
    lines = ["", "## Estimated frame rates", "",
             "The cost model (tools/devices.py BOARDS): a frame takes, per program drawn, its "
             "share of the screen times the pixels times its cost per pixel as its compiler "
             "states it (lima and freedreno: instructions; vc4: estimated cycles; v3d: "
             "instructions and stalls; Bifrost: tuples; Midgard: bundles; "
             "etnaviv: instructions), over the board's clock times the lanes that retire one "
             "unit of that cost a cycle; plus every grid vertex through the largest vertex "
             "shader drawn. Shares are measured: swell --debug variants draws each run of rows "
             "in a colour naming its program (llvmpipe, the same tier, quality, size and view; "
             "a program the device refuses is replaced by the one swell draws its rows with "
             "there). Not modelled: texture and memory bandwidth, latency a single thread "
             "cannot hide (vc4 'threads 1'), the CPU's work (gles2-min: the grid and its "
             "shading, src/geometry/vshade.c), the display. So these are upper bounds of the shading "
             "alone, on clocks and lanes assumed from each board's published figures:", ""]
    seen = []
    for e in estimates:
        if e["board"] not in seen:
            seen.append(e["board"])
    for b in BOARDS:
        if b["board"] in seen:
            lines.append("- %s: %s." % (b["board"], b["note"]))
    lines += ["", "Views: swell's default camera (10 m up, pitch -10°), and --path surface, 1km "
              "and 10km at t = 0. fps: the default view's, the slowest view's in brackets; "
              "target: issue 15 item 4, set for frames shaded at the output's size. Size: the "
              "output's; at a render scale below 1 (swell --scale, src/render/upscale.h) the frame is "
              "shaded at the size in brackets and stretched over the output, the stretch's "
              "cost (the 'upscale' program over every output pixel) included: the trade "
              "offered where a target is missed, a blurrier picture for fewer pixels shaded. "
              "The loop blend's draws are included at every size (the 'loop blend' program "
              "over the texels swell says it draws a frame, src/render/stream_gpu.c: 87 040 in "
              "low quality, 130 560 in high with the default budget's tables; 1.4 ms of "
              "Mali-400 MP2 high, 1.3 ms of VideoCore IV high, where the CPU's blend cost "
              "no GPU time but 0.46-0.9 M CPU instructions and a 722 KiB upload a frame; "
              "SWELL_LOOP_BLEND=cpu takes that instead).",
              "", "| board | tier asked | tier | quality | size | fps default (slowest) | ms "
              "fragment / vertex (default) | target | |", "|---|---|---|---|---|---|---|---|---|"]
    groups = {}
    for e in estimates:
        size = e["size"]
        if e.get("scale", 1.0) < 1:
            w, h = (int(x) for x in size.split("x"))
            size += " (%dx%d)" % (round(w * e["scale"]), round(h * e["scale"]))
        groups.setdefault((e["board"], e["tier_asked"], e["tier"], e["quality"], size),
                          []).append(e)
    for key, es in groups.items():
        d = next((e for e in es if e["view"] == "default"), es[0])
        fps = [e["fps"] for e in es if e["fps"] is not None]
        if d["fps"] is None or not fps:
            lines.append("| %s | %s | %s | %s | %s | n/a | | %s | |" %
                         (key + (d["target_fps"] or "-",)))
            continue
        worst = min(fps)
        t = d["target_fps"]
        verdict = "" if not t else ("meets" if worst >= t else "misses (%.1fx short)" %
                                    (t / worst))
        lines.append("| %s | %s | %s | %s | %s | %.1f (%.1f) | %.1f / %.2f | %s | %s |" % (
            key + (d["fps"], worst, d["ms_fragment"], d["ms_vertex"], t or "-", verdict)))
    return lines


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build/rel")
    ap.add_argument("--only", default="")
    ap.add_argument("--prefix", default="")
    ap.add_argument("--known", default="", help="expected problems (one key a line): only "
                    "others fail, and listed ones that are gone")
    ap.add_argument("--write-known", default="", help="write this run's problems as keys")
    sys.exit(run(ap.parse_args()))
