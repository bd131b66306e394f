#!/usr/bin/env python3
"""Reads `perf script -F comm,tid,time,event,ip,dso,trace` of one start (startup_timeline.sh) and
prints (1) per time slice, the cores used by llvmpipe's rasteriser threads, by the main thread
(LLVM code generation counted apart), by other threads, and the cores left idle; (2) when the
record holds the libLLVM module probe, the CPU of LLVM code generation per compiled module and
thread: each LLVM sample of a thread is given to the module that thread created last (module
names are Mesa's: fsN_variantK fragment programs, draw_llvm_vs_variantK vertex programs,
setup_variant_K triangle set-up). A reading aid for issue 18 item 5, not a test."""
import collections
import re
import sys


def main():
    if len(sys.argv) < 3:
        sys.exit("usage: startup_timeline.py PERF_SCRIPT_OUTPUT HZ [SLICE_S] [CORES]")
    path, hz = sys.argv[1], float(sys.argv[2])
    step = float(sys.argv[3]) if len(sys.argv) > 3 else 0.1
    cores = float(sys.argv[4]) if len(sys.argv) > 4 else 2.0
    main_tid, t0 = None, None
    slices = collections.defaultdict(collections.Counter)
    modules, current, llvm = [], {}, collections.Counter()
    for line in open(path, errors="replace"):
        f = line.split()
        if len(f) < 4 or not f[2].endswith(":"):
            continue
        comm, tid, t = f[0], f[1], float(f[2].rstrip(":"))
        if t0 is None:
            t0 = t
        if main_tid is None and comm == "shadelab":
            main_tid = tid
        if "LLVMModuleCreateWithNameInContext" in line:
            m = re.search(r'name="([^"]*)"', line)
            modules.append((t - t0, m.group(1) if m else "?", tid))
            current[tid] = len(modules) - 1
            continue
        is_llvm = "libLLVM" in line
        if comm.startswith("llvmpipe"):
            kind = "raster"
        elif tid == main_tid:
            kind = "main-llvm" if is_llvm else "main-other"
        else:
            kind = "other"
        slices[int((t - t0) / step)][kind] += 1
        if is_llvm and tid in current:
            llvm[current[tid]] += 1
    if t0 is None:
        sys.exit("startup_timeline.py: no samples in " + path)
    per = hz * step
    print("# cores in use per %.2f s slice (%g cores): rasteriser threads, main thread (LLVM / rest), other threads, idle" % (step, cores))
    print("%6s %7s %9s %10s %6s %5s" % ("t (s)", "raster", "main-llvm", "main-other", "other", "idle"))
    for k in range(max(slices) + 1):
        c = slices[k]
        used = sum(c.values()) / per
        print("%6.1f %7.2f %9.2f %10.2f %6.2f %5.2f" % (k * step, c["raster"] / per, c["main-llvm"] / per,
                                                         c["main-other"] / per, c["other"] / per, max(cores - used, 0)))
    total = {kind: sum(s[kind] for s in slices.values()) / hz for kind in ("raster", "main-llvm", "main-other", "other")}
    idle = sum(max(cores - sum(s.values()) / per, 0) * step for s in slices.values())
    print("# totals (CPU s): raster %.2f, main LLVM %.2f, main other %.2f, other threads %.2f; idle core-seconds %.2f"
          % (total["raster"], total["main-llvm"], total["main-other"], total["other"], idle))
    if not modules:
        return
    print("# LLVM code generation per module (>= 5 ms), in the order created")
    print("%8s %-8s %-26s %7s" % ("t (s)", "thread", "module", "ms"))
    for i, (t, name, tid) in enumerate(modules):
        ms = llvm[i] * 1000 / hz
        if ms >= 5:
            print("%8.3f %-8s %-26s %7.0f" % (t, "main" if tid == main_tid else tid, name, ms))
    by_kind = collections.Counter()
    for i, (t, name, tid) in enumerate(modules):
        kind = "fragment" if name.startswith("fs") else "vertex" if name.startswith("draw_llvm_vs") else "set-up" if name.startswith("setup") else "other"
        by_kind[kind] += llvm[i] * 1000 / hz
    print("# LLVM per kind (ms): " + ", ".join("%s %.0f" % (k, v) for k, v in sorted(by_kind.items())))


if __name__ == "__main__":
    main()
