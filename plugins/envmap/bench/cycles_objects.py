#!/usr/bin/env python3
"""Per-object error of an image against shadelab-xcheck's Cycles image, on the interiors xcheck
uses (pixels whose four neighbours carry the same object index): prints alpha,rel_rms,mean_ratio
per object, object k of DIR/report.json being index k + 1 of DIR/index.exr (plugins/envmap/bench/
cycles.sh: EEVEE's images, which xcheck reports only over all interiors together).
Usage: cycles_objects.py XCHECK_DIR IMAGE.exr   (needs oiiotool)"""
import json, math, re, subprocess, sys


def load(path):
    lines = subprocess.run(["oiiotool", "--dumpdata", path], capture_output=True, text=True, check=True).stdout.splitlines()
    w, h = map(int, re.search(r"(\d+) x\s+(\d+)", lines[0]).groups())
    px = [None] * (w * h)
    for line in lines[1:]:
        m = re.match(r"\s*Pixel \((\d+), (\d+)\): (.*)", line)
        if m:
            px[int(m.group(2)) * w + int(m.group(1))] = [float(v) for v in m.group(3).split()[:3]]
    return w, h, px


def main():
    d, image = sys.argv[1], sys.argv[2]
    names = [o["name"] for o in json.load(open(d + "/report.json"))["objects"]]
    w, h, index = load(d + "/index.exr")
    _, _, cycles = load(d + "/cycles.exr")
    _, _, test = load(image)
    ids = [int(round(p[0])) for p in index]
    sums = {}
    for y in range(1, h - 1):
        for x in range(1, w - 1):
            i = y * w + x
            k = ids[i]
            if k < 1 or any(ids[j] != k for j in (i - 1, i + 1, i - w, i + w)):
                continue
            s = sums.setdefault(k, [0.0, 0.0, 0.0, 0.0])
            for c in range(3):
                s[0] += (test[i][c] - cycles[i][c]) ** 2
                s[1] += cycles[i][c] ** 2
            s[2] += sum(test[i])
            s[3] += sum(cycles[i])
    for k, s in sorted(sums.items()):
        if k <= len(names):
            print("%s,%.6f,%.6f" % (names[k - 1].lstrip("s"), math.sqrt(s[0] / s[1]), s[2] / s[3]))


main()
