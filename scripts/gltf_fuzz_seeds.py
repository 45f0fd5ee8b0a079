#!/usr/bin/env python3
"""Packs glTF samples into seeds for the glTF fuzzer (fuzz/gltf_fuzzer.cpp), at run time.

    python3 scripts/gltf_fuzz_seeds.py SAMPLES_DIR OUT_DIR MAX_BYTES

Every .gltf and .glb under SAMPLES_DIR (Debian's assimp-testmodels: /usr/share/assimp/models/glTF2)
becomes one seed: the asset, then for each buffer or image URI that names a file beside it,
"\\0SAAGEN-FILE:NAME\\n" and the file's bytes, as long as the seed stays within MAX_BYTES (a file
that does not fit is left out: the asset then fails to load, which is a seed too). Assets over
MAX_BYTES themselves are skipped. A missing SAMPLES_DIR gives no seeds and a note.
"""
import json
import os
import re
import sys
import urllib.parse

SECTION = b"\0SAAGEN-FILE:"
PLAIN = re.compile(r"^[A-Za-z0-9_.-]{1,64}$")


def referenced(asset_path, data):
    """The plain file names the asset's buffers and images point at, in order."""
    if not asset_path.endswith(".gltf"):
        return []
    try:
        document = json.loads(data.decode("utf-8", errors="replace"))
    except ValueError:
        return []
    names = []
    for key in ("buffers", "images"):
        entries = document.get(key) if isinstance(document, dict) else None
        for entry in entries if isinstance(entries, list) else []:
            uri = entry.get("uri") if isinstance(entry, dict) else None
            if not isinstance(uri, str) or uri.startswith("data:"):
                continue
            name = urllib.parse.unquote(uri)
            if PLAIN.match(name) and name not in names:
                names.append(name)
    return names


def main():
    samples, out, limit = sys.argv[1], sys.argv[2], int(sys.argv[3])
    os.makedirs(out, exist_ok=True)
    if not os.path.isdir(samples):
        print(f"gltf_fuzz_seeds: {samples} not found (Debian: apt-get install assimp-testmodels); no packaged seeds")
        return
    count = 0
    for root, _, files in sorted(os.walk(samples)):
        for file in sorted(files):
            if not file.lower().endswith((".gltf", ".glb")):
                continue
            path = os.path.join(root, file)
            with open(path, "rb") as f:
                data = f.read()
            if len(data) > limit:
                continue
            seed = bytearray(data)
            for name in referenced(path.lower(), data):
                beside = os.path.join(root, name)
                if not os.path.isfile(beside):
                    continue
                with open(beside, "rb") as f:
                    content = f.read()
                section = SECTION + name.encode() + b"\n" + content
                if len(seed) + len(section) <= limit:
                    seed += section
            target = os.path.join(out, "seed-" + os.path.relpath(path, samples).replace(os.sep, "_"))
            if not os.path.exists(target) or open(target, "rb").read() != seed:
                with open(target, "wb") as f:
                    f.write(seed)
            count += 1
    print(f"gltf_fuzz_seeds: {count} seeds from {samples} in {out}")


if __name__ == "__main__":
    main()
