#!/usr/bin/env python3
"""Numeric model of ggx specular antialiasing on the grazing bumpy plane (plugins/ggx/README.md).

Not part of the build or the tests: an analysis aid, by hand. Needs python3-numpy (Debian's
package; run it with /usr/bin/python3 where another python3 comes first). For the nine
configurations of test_ggx_render's grid (camera 1.2/3/6 m above the 40 m plane at z = 19,
three suns, far field = hit points beyond 25 m) it prints the far-field mean of the green
channel of
  ref    the footprint average of normal-mapped Cook-Torrance over the map's own normals
         (bilinear, 4x upsampled), each through normal-map's view guard (a normal whose mirror
         direction falls below the plane bent back above it, as Cycles does; then n.v >= 0.02),
         i.e. what 8x8 supersampling converges to;
  masked the same with the normals unguarded, those facing away from the viewer masked (Smith
         G1(v) = 0): what ggx did before it took the guard;
  gauss  the guarded average over normals drawn from a Gaussian slope distribution whose
         per-axis variance is Toksvig's (1 - |N|)/|N| for the whole map (40000 samples);
  toks   this plugin's Toksvig lobe at the mean normal (alpha'^2 = alpha^2 + variance in D and G);
  off    the unfiltered shading at the flat mean normal.
The BRDF, guard and constants repeat shaders/ggx_brdf.glsl and shaders/normal_guard.glsl.
Usage: plugins/ggx/tools/specular_aa_model.py [alpha]   (default 0.05)
"""
import os
import struct
import sys
import zlib

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
MAP = os.path.join(HERE, "..", "..", "phong", "assets", "bumps32_tangent.png")
ALPHA = float(sys.argv[1]) if len(sys.argv) > 1 else 0.05
NDOTV_MIN = 0.02  # SL_MIN_NDOTV (shaders/normal_guard.glsl)
AW, AH, FOV_Y = 160, 90, 40.0


def read_png(path):
    """8-bit RGB or RGBA, non-interlaced PNG (what the map is) as an h x w x 3 array of 0..255"""
    data = open(path, "rb").read()
    pos, idat, w, h, channels = 8, b"", 0, 0, 0
    while pos < len(data):
        size, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + size]
        if kind == b"IHDR":
            w, h, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            channels = {2: 3, 6: 4}.get(colour)
            if depth != 8 or channels is None or interlace:
                sys.exit(f"{path}: only 8-bit RGB/RGBA non-interlaced PNGs")
        elif kind == b"IDAT":
            idat += body
        pos += 12 + size
    raw, stride = zlib.decompress(idat), w * channels
    rows, prev = [], bytearray(stride)
    for y in range(h):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):  # PNG's filters (spec section 9.2) undone in place
            a = line[i - channels] if i >= channels else 0
            b, c = prev[i], prev[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return np.frombuffer(b"".join(rows), np.uint8).reshape(h, w, channels)[..., :3].astype(float)


def upsample_bilinear(a, k=4):
    h, w, _ = a.shape
    ys = (np.arange(h * k) + 0.5) / k - 0.5
    xs = (np.arange(w * k) + 0.5) / k - 0.5
    y0, x0 = np.floor(ys).astype(int), np.floor(xs).astype(int)
    fy, fx = (ys - y0)[:, None, None], (xs - x0)[None, :, None]
    y1, x1, y0, x0 = (y0 + 1) % h, (x0 + 1) % w, y0 % h, x0 % w
    top = a[y0][:, x0] * (1 - fx) + a[y0][:, x1] * fx
    bottom = a[y1][:, x0] * (1 - fx) + a[y1][:, x1] * fx
    return top * (1 - fy) + bottom * fy


def tangent_to_world(nt):
    # plane y = 0: T = +X, B = -Z (v grows toward +Z, the image's top is the far edge), N = +Y
    return np.stack([nt[:, 0], nt[:, 2], -nt[:, 1]], 1)


def ggx_d(n_dot_h, a):
    d = n_dot_h * n_dot_h * (a * a - 1) + 1
    return np.where(n_dot_h > 0, a * a / (np.pi * d * d), 0.0)


def ggx_g1(x, n, h, a):
    xn, xh = n @ x, np.dot(x, h)
    c = np.clip(np.abs(xn), 1e-6, 1)
    t2 = (1 - c * c) / (c * c)
    ok = (xn != 0) & (xh / np.where(xn == 0, 1, xn) > 0)
    return np.where(ok, 2 / (1 + np.sqrt(1 + a * a * t2)), 0.0)


def fresnel_exact(c, eta=1 / 1.5):
    c = abs(c)
    b2 = 1 / eta**2 + c * c - 1
    if b2 < 0:
        return 1.0
    b = np.sqrt(b2)
    rs, rp = (c - b) / (c + b), (eta**2 * b - c) / (eta**2 * b + c)
    return 0.5 * (rs * rs + rp * rp)


def face_viewer(n, v):
    d = n @ v
    m = d < NDOTV_MIN
    n = n.copy()
    n[m] += (NDOTV_MIN - d[m])[:, None] * v
    return n / np.linalg.norm(n, axis=1, keepdims=True)


def valid_reflection(n, v):
    """sl_valid_reflection (shaders/normal_guard.glsl) on the plane (g = +Y): normals below the
    plane or whose mirror direction of v rises less than t above it tilted back toward g,
    azimuth kept"""
    vz = v[1]
    t = min(0.9 * vz, 0.01)
    nv = n @ v
    bend = (n[:, 1] < 0) | (2 * nv * n[:, 1] - vz < t)
    x = n[bend].copy()
    x[:, 1] = 0
    x /= np.maximum(np.linalg.norm(x, axis=1, keepdims=True), 1e-12)
    vx = x @ v
    p = vx * vx + vz * vz
    sq = np.abs(vx) * np.sqrt(np.maximum(p - t * t, 0))
    a2 = (vz - t) ** 2 / (2 * (p - vz * t + sq))
    b2 = (vz + t) ** 2 / (2 * (vx * vx + vz * (vz + t) + sq))
    ab = [(np.sqrt(a2), np.sqrt(1 - a2)), (np.sqrt(1 - b2), np.sqrt(b2))]
    err = [np.abs(2 * b * (a * vx + b * vz) - vz - t) for a, b in ab]
    pick = err[0] <= err[1]
    a, b = np.where(pick, ab[0][0], ab[1][0]), np.where(pick, ab[0][1], ab[1][1])
    out = n.copy()
    out[bend] = a[:, None] * x + b[:, None] * np.array([0, 1.0, 0])
    return out


def view_guard(n, v):
    return face_viewer(valid_reflection(n, v), v)


def shade(n, l, v, a_d, a_g, base=0.2, e=4.0):
    """green channel of the ggx model (exact Fresnel, k_s = 1) for normals n (k x 3)"""
    n = np.atleast_2d(n)
    nl, nv = n @ l, n @ v
    h = (l + v) / np.linalg.norm(l + v)
    dg = ggx_d(n @ h, a_d) * ggx_g1(v, n, h, a_g) * ggx_g1(l, n, h, a_g)
    dg = np.where((nl > 0) & (nv > 0), dg / (4 * np.maximum(nl, 1e-4) * np.maximum(nv, 1e-4)), 0.0)
    return (base / np.pi + fresnel_exact(np.dot(l, h)) * dg) * e * np.maximum(nl, 0)


def far_field_views(cam_y, step_x=10, step_y=3):
    cam = np.array([0, cam_y, 19.0])
    fwd = -cam / np.linalg.norm(cam)
    right = np.cross(fwd, [0, 1, 0])
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    tf = np.tan(np.radians(FOV_Y / 2))
    views = []
    for y in range(0, AH, step_y):
        for x in range(0, AW, step_x):
            d = fwd + up * (1 - 2 * (y + 0.5) / AH) * tf + right * (2 * (x + 0.5) / AW - 1) * tf * AW / AH
            d /= np.linalg.norm(d)
            if d[1] >= 0:
                continue
            t = -cam[1] / d[1]
            p = cam + t * d
            if abs(p[0]) < 20 and abs(p[2]) < 20 and t > 25:
                views.append((cam - p) / np.linalg.norm(cam - p))
    return views


def main():
    enc = read_png(MAP) / 255
    nt = upsample_bilinear(enc).reshape(-1, 3) * 2 - 1
    nt /= np.linalg.norm(nt, axis=1, keepdims=True)
    normals = tangent_to_world(nt)[::7]
    mean_len = np.linalg.norm(tangent_to_world(nt).mean(0))
    var = (1 - mean_len) / mean_len
    rng = np.random.default_rng(1)
    s = rng.normal(0, np.sqrt(var), (40000, 2))
    gauss = np.stack([-s[:, 0], np.ones(len(s)), -s[:, 1]], 1)
    gauss /= np.linalg.norm(gauss, axis=1, keepdims=True)
    flat = np.array([0, 1.0, 0])
    a_t = np.sqrt(ALPHA * ALPHA + var)
    print(f"alpha {ALPHA}, Toksvig variance of the whole map {var:.4f}")
    print("camera  sun                      ref    masked gauss  toks   off")
    for cam_y in (1.2, 3.0, 6.0):
        for sun in ((0, -0.25, 0.968), (0, -0.6, 0.8), (0.5, -0.5, 0.707)):
            l = -np.array(sun, float)
            l /= np.linalg.norm(l)
            acc = np.zeros(5)
            views = far_field_views(cam_y)
            for v in views:
                acc += [shade(view_guard(normals, v), l, v, ALPHA, ALPHA).mean(),
                        shade(normals, l, v, ALPHA, ALPHA).mean(),
                        shade(view_guard(gauss, v), l, v, ALPHA, ALPHA).mean(),
                        shade(flat, l, v, a_t, a_t)[0], shade(flat, l, v, ALPHA, ALPHA)[0]]
            r = acc / len(views)
            print(f"{cam_y:4.1f} m  {str(sun):22s} " + " ".join(f"{x:6.3f}" for x in r), flush=True)


if __name__ == "__main__":
    main()
