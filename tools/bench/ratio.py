#!/usr/bin/env python3
"""Ratio benchmark: shadelab's frame against the hand-written floor (issue 18 item 1).

Compiles ../shared/bench/baseline_ggx.c (a single-file OSMesa renderer: one textured 16 k-triangle
GGX + Lambert sphere, N point lights, back faces culled), renders the matching scene
scenes/ratio_sphere.json in shadelab, runs both interleaved per configuration (256x256, 1280x720,
1920x1080 x 1, 4, 16, 64 lights; antialiasing off, as the scene has it, and at its default) and
prints ms/frame of each, their ratio, shadelab's forward pass alone against the baseline's frame,
the share of the frame TAA takes, the per-light cost of each (the slope between light counts) and
the load average. With aa at its default the frames measured are those of a TAA still before it
converges (aa.taa_frames=64 keeps the whole run there; a frame costs what each of the default 16
costs): a converged still only copies its history. tools/bench/benchmarks-table.sh puts
its 720p figures into docs/benchmarks.md. Benchmarks print figures; nothing here is a
timed assertion. Run it through tools/bench/ratio.sh (it finds the build directory).
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCENE = os.path.join(ROOT, "scenes", "ratio_sphere.json")
SIZES = [(256, 256), (1280, 720), (1920, 1080)]
LIGHTS = [1, 4, 16, 64]
SCENE_LIGHTS = 64


def png_coverage(path):
    """Fraction of pixels whose red or green byte is non-zero: the baseline's own 'covered' rule
    (it reads its 8-bit RGBA buffer). Counted by OpenImageIO's oiiotool (a build dependency):
    R + G outside [0, 0]."""
    out = subprocess.run(["oiiotool", path, "--ch", "R,G", "--chsum", "--rangecheck", "0", "0"],
                         capture_output=True, text=True, check=True).stdout
    above = int(re.search(r"(\d+)\s+> 0", out).group(1))
    inside = int(re.search(r"(\d+)\s+within range", out).group(1))
    return above / float(above + inside)


def loadavg():
    try:
        return os.getloadavg()
    except OSError:
        return (float("nan"),) * 3


def run_baseline(exe, w, h, n, frames):
    out = subprocess.run([exe, str(w), str(h), str(n), str(frames)], capture_output=True, text=True, check=True).stdout
    ms = float(re.search(r"ms/frame=([0-9.]+)", out).group(1))
    cov = float(re.search(r"covered=([0-9.]+)%", out).group(1)) / 100.0
    return ms, cov


AA_SETTINGS = {"off": [], "default": ["--set", "aa.enabled=true", "--set", "aa.taa_frames=64"]}


def shadelab_cmd(exe, w, h, n, frames, extra, aa="off"):
    cmd = [exe, "--headless", "--backend", "osmesa", "-q", "--size", "%dx%d" % (w, h), "--frames", str(frames)]
    cmd += AA_SETTINGS[aa]
    for i in range(n, SCENE_LIGHTS):  # the first n lights stay on: a toggle, no recompilation
        cmd += ["--set", "light.l%02d.enabled=false" % i]
    return cmd + extra + [SCENE]


def run_shadelab(exe, w, h, n, frames, aa):
    """Medians of shadelab's own --bench (CPU wall time, glFinish'ed; start-up and, from 10 frames
    on, 3 warm-up frames excluded): (frame, forward pass, aa-taa pass or 0)."""
    out = subprocess.run(shadelab_cmd(exe, w, h, n, frames, ["--bench"], aa), capture_output=True, text=True,
                         check=True).stdout

    def pass_ms(name):
        m = re.search(r"^\s*%s\s+([0-9.]+)" % re.escape(name), out, re.M)
        return float(m.group(1)) if m else 0.0
    return pass_ms("frame (CPU wall)"), pass_ms("forward"), pass_ms("aa-taa")


def shadelab_coverage(exe, w, h, n, tmp):
    png = os.path.join(tmp, "shadelab_%dx%d_%d.png" % (w, h, n))
    subprocess.run(shadelab_cmd(exe, w, h, n, 1, ["--output", png]), capture_output=True, check=True)
    return png_coverage(png)


def median(v):
    s = sorted(v)
    k = len(s) // 2
    return s[k] if len(s) % 2 else 0.5 * (s[k - 1] + s[k])


def frames_for(w, h, n, quick):
    """Enough frames for a stable median, few enough that the whole table takes minutes: the
    baseline costs about 25 ns per pixel-light at 720p on this machine's llvmpipe."""
    est_ms = 2.0 + w * h * 0.15 * n * 2.5e-5 + w * h * 4e-5
    f = int(max(8, min(60, 4000.0 / (3.0 * est_ms))))
    return max(3, f // 2) if quick else f


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--shadelab", required=True, help="the shadelab executable")
    ap.add_argument("--shared", default=os.path.join(ROOT, "..", "shared"),
                    help="the shared directory holding bench/baseline_ggx.c (default ../shared)")
    ap.add_argument("--quick", action="store_true", help="256x256 and 720p, 1 interleaved round, fewer frames")
    ap.add_argument("--rounds", type=int, default=0, help="interleaved rounds per configuration (default 3, quick 1)")
    ap.add_argument("--sizes", default="", help="e.g. 256x256,1280x720 (default all three)")
    ap.add_argument("--lights", default="", help="e.g. 1,16 (default 1,4,16,64)")
    ap.add_argument("--aa", default="off,default", help="antialiasing: off, default or both (default off,default)")
    a = ap.parse_args()

    src = os.path.join(a.shared, "bench", "baseline_ggx.c")
    if not os.path.isfile(src):
        print("ratio: %s not found: the hand-written baseline lives outside the repository (../shared/bench); "
              "nothing to compare against, skipped" % os.path.normpath(src))
        return 0
    sizes = [tuple(int(x) for x in s.split("x")) for s in a.sizes.split(",")] if a.sizes else \
        (SIZES[:2] if a.quick else SIZES)
    lights = [int(x) for x in a.lights.split(",")] if a.lights else LIGHTS
    rounds = a.rounds or (1 if a.quick else 3)
    aas = [x for x in a.aa.split(",") if x]
    if not aas or any(x not in AA_SETTINGS for x in aas):
        print("ratio: --aa takes off, default or off,default", file=sys.stderr)
        return 2
    tmp = tempfile.mkdtemp(prefix="shadelab-ratio-")
    base = os.path.join(tmp, "baseline")
    cc = os.environ.get("CC", "cc")
    subprocess.run([cc, "-O2", src, "-o", base, "-lOSMesa", "-lm"], check=True)
    ver = subprocess.run([a.shadelab, "--version"], capture_output=True, text=True).stdout.strip()
    rev = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    started = time.time()
    load0 = loadavg()
    print("ratio: %s (%s) against %s, %d interleaved round(s); load average %.2f %.2f %.2f"
          % (ver or a.shadelab, rev, os.path.normpath(src), rounds, *load0))
    hdr = ("| size | lights | aa | baseline ms | shadelab ms | ratio | forward ms | forward / baseline | TAA share "
           "| coverage base / shadelab | load (1 min) |")
    results = {}
    print(hdr)
    print("|---|---:|---|---:|---:|---:|---:|---:|---:|---|---:|")
    for (w, h) in sizes:
        for n in lights:
            for aa in aas:
                fr = frames_for(w, h, n, a.quick)
                bms, sms, fms, taa, ratios, fratios, loads = [], [], [], [], [], [], []
                cov_b = None
                for r in range(rounds):
                    # interleaved: baseline, shadelab, shadelab, baseline, ... (the order alternates per round)
                    got = {}
                    for who in ("b", "s") if r % 2 == 0 else ("s", "b"):
                        if who == "b":
                            got["b"], cov_b = run_baseline(base, w, h, n, fr)
                        else:
                            got["s"] = run_shadelab(a.shadelab, w, h, n, fr, aa)
                    frame, forward, t = got["s"]
                    bms.append(got["b"])
                    sms.append(frame)
                    fms.append(forward)
                    taa.append(t / frame if frame > 0 else float("nan"))
                    ratios.append(frame / got["b"])
                    fratios.append(forward / got["b"])
                    loads.append(loadavg()[0])
                cov_s = shadelab_coverage(a.shadelab, w, h, n, tmp)
                cov_ok = abs(cov_s - cov_b) <= 0.02 * cov_b + 0.0005  # the baseline prints 0.1 %
                results[(w, h, n, aa)] = (median(bms), median(sms))
                row = "| %dx%d | %d | %s | %.1f | %.1f | **%.2f** | %.1f | **%.2f** | %s | %.1f %% / %.2f %%%s | %.1f |" % (
                    w, h, n, aa, median(bms), median(sms), median(ratios), median(fms), median(fratios),
                    "%.0f %%" % (100 * median(taa)) if aa != "off" else "-", 100 * cov_b, 100 * cov_s,
                    "" if cov_ok else " (differs by > 2 %)", median(loads))
                print(row, flush=True)
    # per-light cost: the slope of ms/frame between the smallest and largest light count
    if len(lights) >= 2:
        lo, hi = lights[0], lights[-1]
        print("\nper-light cost (slope of ms/frame from %d to %d lights):" % (lo, hi))
        print("| size | aa | baseline ms/light | shadelab ms/light | ratio |")
        for (w, h) in sizes:
            for aa in aas:
                b = (results[(w, h, hi, aa)][0] - results[(w, h, lo, aa)][0]) / (hi - lo)
                s = (results[(w, h, hi, aa)][1] - results[(w, h, lo, aa)][1]) / (hi - lo)
                line = "| %dx%d | %s | %.3f | %.3f | **%.2f** |" % (w, h, aa, b, s, s / b if b > 0 else float("nan"))
                print(line)
    load1 = loadavg()
    took = time.time() - started
    print("\nratio: %.0f s; load average at the end %.2f %.2f %.2f" % (took, *load1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
