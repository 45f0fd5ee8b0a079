#!/usr/bin/env python3
"""A glTF 2.0 UV sphere carrying a tangent-space normal map, for `saagen bench --scene` on normal
maps nobody here authored (docs/PREFILTER.md, "Real normal maps").

    python3 scripts/normal_map_sphere.py MAP OUT_DIR [--tile U V]

MAP is a PNG, or one of the npm package @pmndrs/assets's `normals/NNNN.webp.js` modules (CC0; a
WebP data URI), which is decoded with `dwebp` (Debian package `webp`, libwebp's tool) into
OUT_DIR/NAME.png. Writes OUT_DIR/NAME.gltf: a unit sphere of 128 x 64 segments with positions,
normals and UVs (u around, v pole to pole, the map repeated --tile times, default 2 x 1), one
material with the map as normalTexture, REPEAT and trilinear sampling, no tangents (saagen
generates MikkTSpace-frame tangents, as the glTF specification asks) and no roughness texture
(the trade sweeps its own alphas). Nothing is copied into the repository."""
import argparse
import base64
import json
import math
import os
import struct
import subprocess
import sys

RINGS, SEGMENTS = 64, 128


def decoded_png(map_path, out_dir):
    name = os.path.basename(map_path).split('.')[0]
    if map_path.endswith('.png'):
        return name, os.path.relpath(map_path, out_dir)
    text = open(map_path).read()
    if 'data:image/webp;base64,' not in text:
        sys.exit(f'{map_path}: neither a PNG nor a module holding a WebP data URI')
    webp = os.path.join(out_dir, name + '.webp')
    with open(webp, 'wb') as f:
        f.write(base64.b64decode(text.split('base64,', 1)[1].split("'", 1)[0]))
    png = os.path.join(out_dir, name + '.png')
    subprocess.run(['dwebp', '-quiet', webp, '-o', png], check=True)
    os.remove(webp)
    return name, name + '.png'


def sphere(tile_u, tile_v):
    positions, uvs, indices = [], [], []
    for i in range(RINGS + 1):
        theta = math.pi * i / RINGS
        for j in range(SEGMENTS + 1):
            phi = 2.0 * math.pi * j / SEGMENTS
            positions += (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            uvs += (tile_u * j / SEGMENTS, tile_v * i / RINGS)
    for i in range(RINGS):
        for j in range(SEGMENTS):
            a, b = i * (SEGMENTS + 1) + j, (i + 1) * (SEGMENTS + 1) + j
            if i != 0:
                indices += (a, b, a + 1)
            if i != RINGS - 1:
                indices += (a + 1, b, b + 1)
    return positions, uvs, indices


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('map')
    parser.add_argument('out_dir')
    parser.add_argument('--tile', nargs=2, type=float, default=[2.0, 1.0])
    args = parser.parse_args()
    os.makedirs(args.out_dir, exist_ok=True)
    name, image_uri = decoded_png(args.map, args.out_dir)
    positions, uvs, indices = sphere(*args.tile)
    count = len(positions) // 3
    vertex_bytes = struct.pack(f'<{len(positions)}f', *positions) * 2 + struct.pack(f'<{len(uvs)}f', *uvs)  # normals = positions
    index_bytes = struct.pack(f'<{len(indices)}I', *indices)
    data = vertex_bytes + index_bytes
    views = [(0, count * 12, 34962), (count * 12, count * 12, 34962), (count * 24, count * 8, 34962),
             (len(vertex_bytes), len(index_bytes), 34963)]
    gltf = {
        'asset': {'version': '2.0', 'generator': 'saagen scripts/normal_map_sphere.py'},
        'scene': 0, 'scenes': [{'nodes': [0]}], 'nodes': [{'mesh': 0, 'name': name}],
        'meshes': [{'primitives': [{'attributes': {'POSITION': 0, 'NORMAL': 1, 'TEXCOORD_0': 2}, 'indices': 3, 'material': 0}]}],
        'materials': [{'name': name, 'pbrMetallicRoughness': {'roughnessFactor': 1.0, 'metallicFactor': 1.0},
                       'normalTexture': {'index': 0}}],
        'textures': [{'source': 0, 'sampler': 0}],
        'samplers': [{'magFilter': 9729, 'minFilter': 9987, 'wrapS': 10497, 'wrapT': 10497}],
        'images': [{'uri': image_uri}],
        'buffers': [{'byteLength': len(data), 'uri': 'data:application/octet-stream;base64,' + base64.b64encode(data).decode()}],
        'bufferViews': [{'buffer': 0, 'byteOffset': o, 'byteLength': n, 'target': t} for o, n, t in views],
        'accessors': [
            {'bufferView': 0, 'componentType': 5126, 'count': count, 'type': 'VEC3', 'min': [-1, -1, -1], 'max': [1, 1, 1]},
            {'bufferView': 1, 'componentType': 5126, 'count': count, 'type': 'VEC3'},
            {'bufferView': 2, 'componentType': 5126, 'count': count, 'type': 'VEC2'},
            {'bufferView': 3, 'componentType': 5125, 'count': len(indices), 'type': 'SCALAR'},
        ],
    }
    out = os.path.join(args.out_dir, name + '.gltf')
    with open(out, 'w') as f:
        json.dump(gltf, f)
    print(f'wrote {out} ({len(indices) // 3} triangles, normal map {image_uri})')


if __name__ == '__main__':
    main()
