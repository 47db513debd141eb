#!/usr/bin/python3
"""devices.py - swell's shaders through the real GPUs' compilers (issue 15).

Runs swell (surfaceless, one frame) under Mesa's own drivers for the target GPUs with their noop
drm-shims (tools/mesa-shim.sh builds them), on every tier swell picks there and on forced
gles2-min, in both qualities. swell's start-up probe (src/renderer.c probe_programs) draws every
ocean variant and the sky once, each between two labelled lines on stderr
(SWELL_SHADER_LABELS=1), so the statistics each driver prints while compiling it (MESA_DEBUG=
context and the driver's shaderdb switch) are told apart by program.

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
         limits={"vertex": 512}),
    dict(name="VideoCore IV", driver="vc4", shim="vc4", env={"VC4_DEBUG": "shaderdb"},
         limits={}, fs_threads=2),
    dict(name="VideoCore VI", driver="v3d", shim="v3d", env={"V3D_DEBUG": "shaderdb"},
         limits={}),
    dict(name="Mali-G31", driver="panfrost", shim="panfrost",
         env={"PAN_GPU_ID": "0x7093", "BIFROST_MESA_DEBUG": "shaderdb"}, limits={}),
    dict(name="Mali-T860", driver="panfrost", shim="panfrost",
         env={"PAN_GPU_ID": "0x860", "MIDGARD_MESA_DEBUG": "shaderdb"}, limits={}),
    dict(name="Adreno 307", driver="msm", shim="freedreno",
         env={"FD_GPU_ID": "307", "FD_MESA_DEBUG": "shaderdb"}, limits={}),
    dict(name="Adreno 530", driver="msm", shim="freedreno",
         env={"FD_GPU_ID": "530", "FD_MESA_DEBUG": "shaderdb"}, limits={}),
    dict(name="Adreno 630", driver="msm", shim="freedreno",
         env={"FD_GPU_ID": "630", "FD_MESA_DEBUG": "shaderdb"}, limits={}),
    dict(name="GC2000", driver="etnaviv", shim="etnaviv",
         env={"ETNA_SHIM_GPU": "GC2000", "ETNA_MESA_DEBUG": "shaderdb"},
         limits={"vertex": 256, "fragment": 256}, etna=True),
    dict(name="GC3000", driver="etnaviv", shim="etnaviv",
         env={"ETNA_SHIM_GPU": "GC3000", "ETNA_MESA_DEBUG": "shaderdb"}, limits={}, etna=True),
    dict(name="GC7000L", driver="etnaviv", shim="etnaviv",
         env={"ETNA_SHIM_GPU": "GC7000L", "ETNA_MESA_DEBUG": "shaderdb"}, limits={},
         etna=True),
]

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


def program_name(vs, defines):
    """The probe's name for a build: 'ocean k=1 kw=0 high', 'sky', 'sky sun'."""
    d = dict(kv.split("=", 1) if "=" in kv else (kv, "") for kv in defines.split())
    if vs.startswith("ocean"):
        return "ocean k=%s kw=%s %s" % (d.get("FS_PATTERNS", "?"), d.get("FS_WHITECAPS", "?"),
                                        "high" if "QUALITY_HIGH" in d else "low")
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
            span = [(program_name(m.group(1), m.group(3)), tier)]
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
                                cycles=(f.get("estimated-cycles", f.get("cycles")) if f else None)))
    return gpu, tier, records


def problems(rec, model):
    out = []
    if not rec["probed"]:
        out.append("not probed (swell stopped before)")
    elif not rec["compiled"]:
        out.append("refused by the driver")
    if rec["spills"]:
        out.append("%d spills" % rec["spills"])
    if rec["limit"] and rec["instructions"] and rec["instructions"] > 0.9 * rec["limit"]:
        out.append("%d of %d instructions (over 90 %%)" % (rec["instructions"], rec["limit"]))
    want = model.get("fs_threads")
    if want and rec["stage"] == "fragment" and rec["threads"] and rec["threads"] < want:
        out.append("%d thread(s), not %d" % (rec["threads"], want))
    return out


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
        for tier in ("auto", "gles2-min"):
            for quality in ("high", "low"):
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
                       "--out", os.path.join(out_dir, "frame.png")]
                if tier != "auto":
                    cmd += ["--tier", tier]
                try:
                    p = subprocess.run(cmd, env=env, cwd=root, stdout=subprocess.PIPE,
                                       stderr=subprocess.STDOUT, text=True, timeout=120)
                    text, rc = p.stdout, p.returncode
                except subprocess.TimeoutExpired as e:
                    text, rc = (e.stdout or b"").decode(errors="replace"), "timeout"
                tag = "%s_%s_%s" % (model["name"].replace(" ", "-"), tier, quality)
                with open(os.path.join(out_dir, tag + ".log"), "w") as f:
                    f.write(text)
                gpu, picked, recs = parse_log(text, model)
                for r in recs:
                    r["quality_asked"] = quality
                    r["tier_asked"] = tier
                    pr = problems(r, model)
                    r["problems"] = pr
                    if pr:
                        failures.append("%s %s %s %s %s: %s" % (model["name"], r["tier"], quality,
                                                                r["program"], r["stage"],
                                                                "; ".join(pr)))
                all_records += recs
                m = re.findall(r"trying --quality (\S+)", text)
                drew = "none" if rc != 0 else (m[-1] if m else quality)
                runs.append(dict(model=model["name"], gpu=gpu, tier_asked=tier, tier=picked,
                                 quality=quality, drew=drew, exit=rc,
                                 programs=len({r["program"] for r in recs})))
                if rc != 0:
                    failures.append("%s %s %s: swell exited %s (log %s.log)" %
                                    (model["name"], tier, quality, rc, tag))
                print("devices: %-12s %-9s %-4s exit %s, %d records" %
                      (model["name"], tier, quality, rc, len(recs)), file=sys.stderr)
    with open(os.path.join(out_dir, "results.json"), "w") as f:
        json.dump(dict(runs=runs, records=all_records), f, indent=1)
    write_doc(os.path.join(root, "docs", "devices.md"), runs, all_records)
    for line in failures:
        print("devices: FAIL " + line, file=sys.stderr)
    print("devices: %d runs, %d records, %d problems; build/devices/results.json, docs/devices.md"
          % (len(runs), len(all_records), len(failures)), file=sys.stderr)
    return 1 if failures else 0


def write_doc(path, runs, records):
    lines = ["# swell on the real GPUs' compilers", "",
             "Made by `make test-devices` (tools/devices.py): swell's start-up probe draws every "
             "ocean variant and the sky once under Mesa 22.3's own drivers for each GPU, run "
             "without the hardware through Mesa's noop drm-shim; the numbers are what each "
             "driver's compiler reports (instructions; spills; threads or cycles where it "
             "says). `ok` means the program compiled and the driver ran its draw; `refused`: "
             "the driver said it cannot (swell then draws those rows with a variant fetching "
             "fewer patterns, or falls back to the other quality). Frame rates are not "
             "estimated yet.", ""]
    lines += ["## Runs", "", "| GPU | tier asked | tier | quality asked | drawn in | exit | programs |",
              "|---|---|---|---|---|---|---|"]
    for r in runs:
        lines.append("| %s | %s | %s | %s | %s | %s | %d |" % (
            r["model"], r["tier_asked"], r["tier"], r["quality"], r["drew"], r["exit"],
            r["programs"]))
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
        key = (r["model"], r["tier"], r["program"].split()[-1])
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
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build/rel")
    ap.add_argument("--only", default="")
    ap.add_argument("--prefix", default="")
    sys.exit(run(ap.parse_args()))
