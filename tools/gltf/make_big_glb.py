#!/usr/bin/env python3
"""Writes a large .glb for the open-a-model benchmark (tools/gltf/bench_open.sh): a wavy grid of
N x N quads (2 N^2 triangles; N = 1000 gives 2 M) with positions, normals and UVs, and two 4K
textures (a base colour and a normal map, random noise made by oiiotool so they do not
compress: about 100 MB in all), embedded as buffer views. Two materials share the base colour
image (half the grid each), so the renderer's sharing of one image between materials shows.

usage: make_big_glb.py OUT.glb [N] [TEXTURE_SIZE]"""
import array, json, math, os, struct, subprocess, sys, tempfile

out = sys.argv[1]
n = int(sys.argv[2]) if len(sys.argv) > 2 else 1000
tex = int(sys.argv[3]) if len(sys.argv) > 3 else 4096

def noise_png(path, seed, normal=False):
    if normal:  # tangent-space normals tilted at most ~6 degrees: x, y noise around 0.5, z = 1
        pattern = ['--pattern', f'noise:type=uniform:min=0.45:max=0.55:seed={seed}', f'{tex}x{tex}', '2',
                   '--pattern', 'constant:color=1', f'{tex}x{tex}', '1', '--chappend']
    else:
        pattern = ['--pattern', f'noise:type=uniform:min=0.2:max=0.9:seed={seed}', f'{tex}x{tex}', '3']
    subprocess.run(['oiiotool', *pattern, '-d', 'uint8', '-o', path], check=True)
    return open(path, 'rb').read()

with tempfile.TemporaryDirectory() as tmp:
    base_png = noise_png(os.path.join(tmp, 'base.png'), 1)
    normal_png = noise_png(os.path.join(tmp, 'normal.png'), 2, normal=True)

verts = (n + 1) * (n + 1)
pos, nrm, uv = array.array('f'), array.array('f'), array.array('f')
for j in range(n + 1):
    z = j / n * 2 - 1
    for i in range(n + 1):
        x = i / n * 2 - 1
        y = 0.05 * math.sin(6 * x) * math.cos(6 * z)
        dx = 0.3 * math.cos(6 * x) * math.cos(6 * z)
        dz = -0.3 * math.sin(6 * x) * math.sin(6 * z)
        l = math.sqrt(dx * dx + 1 + dz * dz)
        pos.extend((x, y, z)); nrm.extend((-dx / l, 1 / l, -dz / l)); uv.extend((i / n, j / n))
idx = array.array('I')
for j in range(n):
    for i in range(n):
        a = j * (n + 1) + i
        idx.extend((a, a + n + 1, a + 1, a + 1, a + n + 1, a + n + 2))
half = len(idx) // 2

bin_ = bytearray()
views = []
def add(data):
    while len(bin_) % 4: bin_.append(0)
    views.append({'buffer': 0, 'byteOffset': len(bin_), 'byteLength': len(data)})
    bin_.extend(data)
    return len(views) - 1
vp, vn, vu = add(pos.tobytes()), add(nrm.tobytes()), add(uv.tobytes())
vi0, vi1 = add(idx[:half].tobytes()), add(idx[half:].tobytes())
vb, vnm = add(base_png), add(normal_png)
while len(bin_) % 4: bin_.append(0)

acc = [{'bufferView': vp, 'componentType': 5126, 'count': verts, 'type': 'VEC3', 'min': [-1, -0.05, -1], 'max': [1, 0.05, 1]},
       {'bufferView': vn, 'componentType': 5126, 'count': verts, 'type': 'VEC3'},
       {'bufferView': vu, 'componentType': 5126, 'count': verts, 'type': 'VEC2'},
       {'bufferView': vi0, 'componentType': 5125, 'count': half, 'type': 'SCALAR'},
       {'bufferView': vi1, 'componentType': 5125, 'count': len(idx) - half, 'type': 'SCALAR'}]
attrs = {'POSITION': 0, 'NORMAL': 1, 'TEXCOORD_0': 2}
doc = {'asset': {'version': '2.0', 'generator': 'shadelab tools/gltf/make_big_glb.py'},
       'scene': 0, 'scenes': [{'nodes': [0]}], 'nodes': [{'name': 'grid', 'mesh': 0}],
       'meshes': [{'name': 'grid', 'primitives': [{'attributes': attrs, 'indices': 3, 'material': 0},
                                                  {'attributes': attrs, 'indices': 4, 'material': 1}]}],
       'materials': [{'name': f'half{k}', 'pbrMetallicRoughness': {'baseColorTexture': {'index': 0}, 'metallicFactor': 0,
                                                                  'roughnessFactor': 0.4 + 0.3 * k},
                      'normalTexture': {'index': 1}} for k in range(2)],
       'textures': [{'source': 0}, {'source': 1}],
       'images': [{'bufferView': vb, 'mimeType': 'image/png'}, {'bufferView': vnm, 'mimeType': 'image/png'}],
       'buffers': [{'byteLength': len(bin_)}], 'bufferViews': views, 'accessors': acc}
js = json.dumps(doc).encode()
js += b' ' * (-len(js) % 4)
with open(out, 'wb') as f:
    f.write(b'glTF' + struct.pack('<II', 2, 12 + 8 + len(js) + 8 + len(bin_)))
    f.write(struct.pack('<I', len(js)) + b'JSON' + js)
    f.write(struct.pack('<I', len(bin_)) + b'BIN\0' + bin_)
print(f'{out}: {os.path.getsize(out) / 1e6:.1f} MB, {len(idx) // 3} triangles, {verts} vertices, 2 textures {tex}x{tex}')
