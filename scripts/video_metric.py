#!/usr/bin/env python3
"""ColorVideoVDP (Mantiuk et al. 2024) on the animation clips `saagen bench --frames DIR` writes,
and its agreement (Kendall tau) with saagen's own criteria.

    python3 scripts/video_metric.py --cvvdp /work/cvvdp --frames DIR [--table T.json]
        [--filter REGEX] [--columns a,b] [--display standard_fhd] [--fps 30] --out R.json

--cvvdp is a checkout of https://github.com/gfxdisp/ColorVideoVDP (its `pycvvdp/` folder and the
JSON parameter files in it; nothing is downloaded at run time). The metric is third-party code and
is not part of saagen: this script only imports it from that path. Its Python dependencies beyond
numpy and torch are torchvision, scipy and tqdm (Debian: python3-torch python3-torchvision
python3-scipy python3-tqdm). Its video-file I/O modules import ffmpeg-python and imageio, which
this script never uses (it decodes the PNG frames itself and passes tensors to the metric): when
they are not installed they are replaced by modules that raise on use. Torch 1.13 (Debian
bookworm) cannot index with int32 tensors, which one interpolation helper of the metric returns;
the helper is wrapped so that its indices are int64 (the same values).

Each clip of DIR/index.json (saagen bench --frames; docs/COLORVIDEOVDP.md) is compared with its
reference, every frame's grey value put in R, G and B, display-encoded (the PNGs hold the display
values: Reinhard, then the sRGB encoding), one image pixel per display pixel. The JOD of each clip
row (10: no visible difference, higher is better) goes to --out. With --table (the bench's --json),
each row is matched to the table's case of the same scene, alpha, Fresnel mode and configuration,
and for each (scene, alpha) the Kendall tau-b between JOD and each criterion column (lower is
better) is printed: tau = 1 when the column orders the configurations exactly as ColorVideoVDP
does.
"""

import argparse
import json
import math
import os
import re
import struct
import subprocess
import sys
import time
import types
import zlib

_REEXEC_ENV = "SAAGEN_VIDEO_METRIC_REEXEC"


def fail(message):
    print(f"video_metric: {message}", file=sys.stderr)
    sys.exit(2)


# ---------------------------------------------------------------------------------------------
# PNG (stdlib): 8- or 16-bit greyscale, grey+alpha, RGB or RGBA, not interlaced.

def _paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    if pa <= pb and pa <= pc:
        return a
    return b if pb <= pc else c


def read_png(path):
    """(height, width, channels, bit depth, rows): rows a bytes object of the unfiltered
    scanlines."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path}: not a PNG")
    pos, idat, header = 8, [], None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        kind = data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
    if header is None:
        raise ValueError(f"{path}: no IHDR")
    width, height, depth, colour, _, _, interlace = header
    channels = {0: 1, 4: 2, 2: 3, 6: 4}.get(colour)
    if channels is None or depth not in (8, 16) or interlace != 0:
        raise ValueError(f"{path}: unsupported PNG (colour type {colour}, depth {depth}, "
                         f"interlace {interlace})")
    raw = zlib.decompress(b"".join(idat))
    bpp = channels * depth // 8
    stride = width * bpp
    if len(raw) != height * (stride + 1):
        raise ValueError(f"{path}: {len(raw)} bytes of scanlines, expected {height * (stride + 1)}")
    out = bytearray(height * stride)
    previous = bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        if kind == 1:
            for i in range(bpp, stride):
                line[i] = (line[i] + line[i - bpp]) & 255
        elif kind == 2:
            for i in range(stride):
                line[i] = (line[i] + previous[i]) & 255
        elif kind == 3:
            for i in range(stride):
                left = line[i - bpp] if i >= bpp else 0
                line[i] = (line[i] + ((left + previous[i]) >> 1)) & 255
        elif kind == 4:
            for i in range(stride):
                left = line[i - bpp] if i >= bpp else 0
                upper_left = previous[i - bpp] if i >= bpp else 0
                line[i] = (line[i] + _paeth(left, previous[i], upper_left)) & 255
        elif kind != 0:
            raise ValueError(f"{path}: unknown PNG filter {kind}")
        out[y * stride:(y + 1) * stride] = line
        previous = line
    return height, width, channels, depth, bytes(out)


def load_grey_frame(path, np):
    """One frame as a (height, width) float32 array of display values in [0, 1]."""
    height, width, channels, depth, rows = read_png(path)
    dtype = np.uint8 if depth == 8 else np.dtype(">u2")
    a = np.frombuffer(rows, dtype=dtype).reshape(height, width, channels).astype(np.float32)
    a /= 255.0 if depth == 8 else 65535.0
    if channels in (1, 2):
        return a[:, :, 0]
    # Colour frames: the format is greyscale; take the Rec. 709 luma of the encoded values.
    return 0.2126 * a[:, :, 0] + 0.7152 * a[:, :, 1] + 0.0722 * a[:, :, 2]


def load_clip(frames_dir, rel, clip, np):
    """A clip as a (frames, height, width) float32 array: one PNG with the frames stacked top to
    bottom (what saagen bench --frames writes), or a folder of frame-NN.png."""
    path = os.path.join(frames_dir, rel)
    count, height = clip.get("frames"), clip.get("height")
    if os.path.isfile(path):
        stacked = load_grey_frame(path, np)
        if not count:
            if not height:
                raise ValueError(f"{path}: the index gives neither the frame count nor the height")
            count = stacked.shape[0] // height
        if stacked.shape[0] % count:
            raise ValueError(f"{path}: {stacked.shape[0]} rows do not hold {count} frames")
        frame_height = stacked.shape[0] // count
        if height and frame_height != height:
            raise ValueError(f"{path}: frames of {frame_height} rows, the index says {height}")
        if clip.get("width") and stacked.shape[1] != clip["width"]:
            raise ValueError(f"{path}: {stacked.shape[1]} columns, the index says {clip['width']}")
        return stacked.reshape(count, frame_height, stacked.shape[1])
    if not os.path.isdir(path):
        raise FileNotFoundError(f"{path}: no such clip (file or folder)")
    names = [n for n in os.listdir(path) if re.fullmatch(r"frame-\d+\.png", n)]
    if count and len(names) != count:
        raise ValueError(f"{path}: {len(names)} frames, the index says {count}")
    names.sort(key=lambda n: int(n[6:-4]))
    return np.stack([load_grey_frame(os.path.join(path, n), np) for n in names])


def index_clips(index):
    """The index's clips, one per (scene, material), as {scene, alpha, fresnel, width, height,
    frames, reference, rows: [{configuration, path}], criterion}. Reads saagen's layout
    ("groups", each with "clips" of {configuration, file}) and the earlier draft's ("clips", each
    with "rows" of {configuration, dir})."""
    groups = index.get("groups")
    if groups is None:
        groups = index.get("clips", [])
    out = []
    for group in groups:
        rows = group.get("clips") if "groups" in index else group.get("rows")
        clip = {k: group.get(k) for k in ("scene", "alpha", "width", "height", "frames", "reference")}
        clip["fresnel"] = bool(group.get("fresnel", False))
        clip["criterion"] = group.get("criterion")
        clip["rows"] = [{"configuration": r["configuration"], "path": r.get("file") or r.get("dir"),
                         "criterion": r.get("criterion")} for r in rows or []]
        if clip["reference"] is None:
            raise ValueError(f"index: {clip['scene']} alpha {clip['alpha']}: no reference clip")
        out.append(clip)
    return out


# ---------------------------------------------------------------------------------------------
# ColorVideoVDP from a checkout, without its video-file I/O.

def _raising_module(name):
    module = types.ModuleType(name)

    def missing(attribute):
        raise ImportError(f"{name}.{attribute}: not installed (video_metric.py does not use it)")

    module.__getattr__ = missing
    return module


def _importable(name):
    import importlib.util
    try:
        return importlib.util.find_spec(name) is not None
    except (ImportError, ValueError):
        return False


def load_cvvdp(path, torch):
    package_dir = os.path.join(path, "pycvvdp")
    if not os.path.isfile(os.path.join(package_dir, "cvvdp_metric.py")):
        fail(f"--cvvdp {path}: no pycvvdp/cvvdp_metric.py there (a ColorVideoVDP checkout is needed)")
    # The file I/O layer (video_writer, video_source_file) imports these; never used here.
    if not _importable("ffmpeg"):
        sys.modules["ffmpeg"] = _raising_module("ffmpeg")
    if not _importable("imageio") or not _importable("imageio.v2"):
        imageio = sys.modules.get("imageio") or _raising_module("imageio")
        imageio.v2 = _raising_module("imageio.v2")
        sys.modules["imageio"] = imageio
        sys.modules["imageio.v2"] = imageio.v2
    if not _importable("tqdm"):  # a progress bar only
        tqdm = types.ModuleType("tqdm")
        tqdm.tqdm = lambda iterable, *a, **k: iterable
        sys.modules["tqdm"] = tqdm
    # The package's __init__ imports every metric and the file readers; load the package object
    # without it and import the one module needed.
    package = types.ModuleType("pycvvdp")
    package.__path__ = [package_dir]
    sys.modules["pycvvdp"] = package
    try:
        import pycvvdp.cvvdp_metric as cvvdp_metric
    except ImportError as e:
        fail(f"cannot import ColorVideoVDP from {path}: {e} (Debian: apt-get install python3-torch "
             f"python3-torchvision python3-scipy python3-tqdm)")
    # torch < 2.0 cannot index with int32 tensors; get_interpolants_quick returns int32 indices.
    for name in ("interp", "pycvvdp.interp"):
        module = sys.modules.get(name)
        if module is None or getattr(module, "_saagen_int64", False):
            continue
        original = module.get_interpolants_quick

        def quick(x_q, x, _original=original):
            low, high, fraction = _original(x_q, x)
            return low.long(), high.long(), fraction

        module.get_interpolants_quick = quick
        module._saagen_int64 = True
    return cvvdp_metric


def cvvdp_identity(path):
    version, commit = "unknown", "unknown"
    try:
        with open(os.path.join(path, "pyproject.toml")) as f:
            m = re.search(r'^version\s*=\s*"([^"]+)"', f.read(), re.M)
            if m:
                version = m.group(1)
    except OSError:
        pass
    try:
        commit = subprocess.run(["git", "-C", path, "rev-parse", "HEAD"], capture_output=True,
                                text=True, timeout=10).stdout.strip() or "unknown"
    except (OSError, subprocess.SubprocessError):
        pass
    return version, commit


# ---------------------------------------------------------------------------------------------
# Kendall tau-b.

def kendall_tau(x, y):
    """Kendall tau-b of two equal-length sequences; None when undefined (n < 2 or a constant)."""
    n = len(x)
    concordant = discordant = ties_x = ties_y = 0
    for i in range(n):
        for j in range(i + 1, n):
            dx = (x[i] > x[j]) - (x[i] < x[j])
            dy = (y[i] > y[j]) - (y[i] < y[j])
            if dx == 0 and dy == 0:
                continue
            if dx == 0:
                ties_x += 1
            elif dy == 0:
                ties_y += 1
            elif dx == dy:
                concordant += 1
            else:
                discordant += 1
    denominator = math.sqrt((concordant + discordant + ties_x) * (concordant + discordant + ties_y))
    if denominator == 0:
        return None
    return (concordant - discordant) / denominator


# ---------------------------------------------------------------------------------------------

def alpha_key(alpha):
    return f"{float(alpha):.6g}"


def row_label(clip, row):
    return f"{clip['scene']}/a{alpha_key(clip['alpha'])}/{row['configuration']}"


def clip_key(scene, alpha, fresnel):
    return (scene, alpha_key(alpha), bool(fresnel))


def index_criteria(clip):
    """Per-configuration criterion numbers an index clip may carry: {"criterion": {configuration:
    {column: value}}} or {"criterion": {column: {configuration: value}}}, or "criterion" on a row."""
    out = {}
    names = {row["configuration"] for row in clip.get("rows", [])}
    names.add("none")
    block = clip.get("criterion") or {}
    for key, value in block.items():
        if not isinstance(value, dict):
            continue
        if key in names:
            for column, number in value.items():
                if isinstance(number, (int, float)):
                    out.setdefault(key, {})[column] = float(number)
        else:
            for configuration, number in value.items():
                if isinstance(number, (int, float)):
                    out.setdefault(configuration, {})[key] = float(number)
    for row in clip.get("rows", []):
        for column, number in (row.get("criterion") or {}).items():
            if isinstance(number, (int, float)):
                out.setdefault(row["configuration"], {})[column] = float(number)
    return out


def _number(value):
    """A criterion value: a number, or the mean of an interval {"mean", "low", "high"}."""
    if isinstance(value, dict):
        value = value.get("mean")
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return float(value)
    return None


def table_criteria(table_path):
    """{(scene, alpha, fresnel): {configuration: {column: value}}} from the bench's --json: its
    "cases" (configurations) and its "sanity" rows (as "sanity:NAME")."""
    with open(table_path) as f:
        table = json.load(f)
    cases = table.get("cases")
    if not isinstance(cases, list):
        fail(f"{table_path}: no \"cases\" list (the bench's --json table is needed)")
    out = {}
    for case in cases:
        key = clip_key(case["scene"], case["alpha"], case.get("fresnel", False))
        values = {k: _number(v) for k, v in case.items() if k != "alpha"}
        out.setdefault(key, {})[case["configuration"]] = {
            k: v for k, v in values.items() if v is not None}
    for row in table.get("sanity") or []:
        key = clip_key(row["scene"], row["alpha"], row.get("fresnel", False))
        values = {k: _number(v) for k, v in row.items() if k != "alpha"}
        out.setdefault(key, {})["sanity:" + row["result"]] = {
            k: v for k, v in values.items() if v is not None}
    return out


DEFAULT_COLUMNS = ("flicker_error", "image_error", "tde", "flip_ldr", "flip_ldr_animation")


def agreement(results, criteria, columns, rows_of_kind):
    """{(scene, alpha, fresnel): {column: (tau, n)}} over the rows that have both a JOD and the
    column."""
    out = {}
    for key, rows in results.items():
        table = criteria.get(key, {})
        per_column = {}
        for column in columns:
            pairs = [(r["jod"], table[r["configuration"]][column]) for r in rows
                     if rows_of_kind(r["configuration"]) and r.get("jod") is not None
                     and column in table.get(r["configuration"], {})]
            if len(pairs) >= 2:
                # JOD: higher is better; the criteria: lower is better.
                tau = kendall_tau([p[0] for p in pairs], [-p[1] for p in pairs])
                per_column[column] = (tau, len(pairs))
        out[key] = per_column
    return out


def is_sanity(configuration):
    return configuration.startswith("sanity:")


def sanity_verdict(jod):
    """The sanity suite's rules (report/sanity.hpp) read with JOD, without intervals: nothing above
    another seed; none of 1-spp no SAA, blurred, frozen and no-highlight above the quarter-sample
    ground truth; frozen and no-highlight below it; delayed below its own frames on time (another
    seed)."""
    other, quarter = jod.get("sanity:other-seed"), jod.get("sanity:quarter-samples")
    broken = []
    if other is not None:
        broken += [f"{c.replace('sanity:', '')} above other-seed" for c, v in jod.items()
                   if c != "sanity:other-seed" and v > other]
    if quarter is not None:
        broken += [f"{c} above quarter-samples" for c in ("none", "blurred", "frozen", "no-highlight")
                   if jod.get(c if c == "none" else "sanity:" + c, -math.inf) > quarter
                   and not (other is not None and jod.get(c if c == "none" else "sanity:" + c) > other)]
    if other is None and quarter is None:
        return ""
    return "  [" + ("as expected" if not broken else "; ".join(broken)) + "]"


def print_report(results, criteria, columns, out=sys.stdout):
    keys = sorted(results, key=lambda k: (k[0], float(k[1]), k[2]))
    if criteria is not None and columns:
        for title, kind in (("configurations (the table's rows)", lambda c: not is_sanity(c)),
                            ("configurations and sanity rows (where the criterion covers them)",
                             lambda c: True)):
            taus = agreement(results, criteria, columns, kind)
            if title.startswith("configurations and") and all(
                    not any(is_sanity(c) for c in criteria.get(k, {})) for k in keys):
                continue
            print(f"\nKendall tau-b, JOD (higher better) vs column (lower better), {title}:", file=out)
            width = max(len(c) for c in columns)
            width = max(width, 9)
            print(f"{'scene':<22} {'alpha':>7} {'n':>4} " + " ".join(f"{c:>{width}}" for c in columns),
                  file=out)
            summary = {c: [] for c in columns}
            for key in keys:
                per = taus.get(key, {})
                if not per:
                    continue
                n = max(v[1] for v in per.values())
                cells = []
                for c in columns:
                    tau = per.get(c, (None, 0))[0]
                    cells.append(f"{'-' if tau is None else f'{tau:+.3f}':>{width}}")
                    if tau is not None:
                        summary[c].append(tau)
                scene = key[0] + (" (F)" if key[2] else "")
                print(f"{scene:<22} {key[1]:>7} {n:>4} " + " ".join(cells), file=out)
            print(f"{'min':<35} " + " ".join(
                f"{(f'{min(summary[c]):+.3f}' if summary[c] else '-'):>{width}}" for c in columns),
                file=out)
            print(f"{'cases with tau >= 0.8':<35} " + " ".join(
                f"{sum(t >= 0.8 for t in summary[c])} of {len(summary[c])}".rjust(width)
                for c in columns), file=out)
    print("\nSanity ranking by JOD (higher is closer to the reference):", file=out)
    for key in keys:
        rows = [r for r in results[key] if r.get("jod") is not None
                and (is_sanity(r["configuration"]) or r["configuration"] == "none")]
        if not rows:
            continue
        rows.sort(key=lambda r: -r["jod"])
        scene = key[0] + (" (F)" if key[2] else "")
        print(f"{scene:<22} {key[1]:>7}  " + "  ".join(
            f"{r['configuration'].replace('sanity:', '')} {r['jod']:.2f}" for r in rows)
            + sanity_verdict({r["configuration"]: r["jod"] for r in rows}), file=out)


def group_results(rows):
    out = {}
    for r in rows:
        out.setdefault(clip_key(r["scene"], r["alpha"], r["fresnel"]), []).append(r)
    return out


# ---------------------------------------------------------------------------------------------
# --self-test: the parts that need neither the metric nor numpy (run by ctest).

def _write_png(path, width, height, colour, depth, pixels, filters):
    """A PNG of `pixels` (bytes of the unfiltered scanlines), row y filtered with
    filters[y % len(filters)] (0-4), to test read_png on every filter."""
    channels = {0: 1, 4: 2, 2: 3, 6: 4}[colour]
    bpp = channels * depth // 8
    stride = width * bpp
    raw, previous = bytearray(), bytes(stride)
    for y in range(height):
        line = pixels[y * stride:(y + 1) * stride]
        kind = filters[y % len(filters)]
        encoded = bytearray(stride)
        for i in range(stride):
            left = line[i - bpp] if i >= bpp else 0
            upper_left = previous[i - bpp] if i >= bpp else 0
            predictor = (0, left, previous[i], (left + previous[i]) >> 1,
                         _paeth(left, previous[i], upper_left))[kind]
            encoded[i] = (line[i] - predictor) & 255
        raw.append(kind)
        raw += encoded
        previous = line

    def chunk(kind, body):
        return (struct.pack(">I", len(body)) + kind + body
                + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n"
                + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, depth, colour, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(bytes(raw))) + chunk(b"IEND", b""))


def self_test():
    import random
    import tempfile
    failures = []

    def check(condition, what):
        if not condition:
            failures.append(what)

    rng = random.Random(35)
    with tempfile.TemporaryDirectory() as folder:
        for colour, depth in ((0, 8), (0, 16), (2, 8), (6, 8)):
            channels = {0: 1, 2: 3, 6: 4}[colour]
            width, height = 13, 11
            pixels = bytes(rng.randrange(256) for _ in range(width * height * channels * depth // 8))
            for filters in ((0,), (1,), (2,), (3,), (4,), (0, 1, 2, 3, 4)):
                path = os.path.join(folder, "t.png")
                _write_png(path, width, height, colour, depth, pixels, filters)
                got = read_png(path)
                check(got == (height, width, channels, depth, pixels),
                      f"read_png: colour type {colour}, depth {depth}, filters {filters}")
    check(kendall_tau([1, 2, 3], [1, 2, 3]) == 1.0, "kendall_tau: identical order")
    check(kendall_tau([1, 2, 3], [3, 2, 1]) == -1.0, "kendall_tau: reversed order")
    # tau-b with ties (scipy.stats.kendalltau: 0.6666666666666666, 0.16051447078102563)
    check(abs(kendall_tau([1, 2, 2, 3, 4], [2, 1, 3, 3, 5]) - 2 / 3) < 1e-12, "kendall_tau: ties")
    check(abs(kendall_tau([3, 1, 4, 1, 5, 9, 2, 6], [2, 7, 1, 8, 2, 8, 1, 8])
              - 0.16051447078102563) < 1e-12, "kendall_tau: ties in both")
    check(kendall_tau([1, 1], [1, 2]) is None, "kendall_tau: constant sequence")
    rows = [{"configuration": "none"}, {"configuration": "sanity:frozen"}]
    by_row = index_criteria({"rows": rows, "criterion": {"none": {"tde": 1.0},
                                                          "sanity:frozen": {"tde": 2.0}}})
    by_column = index_criteria({"rows": rows, "criterion": {"tde": {"none": 1.0,
                                                                    "sanity:frozen": 2.0}}})
    check(by_row == by_column == {"none": {"tde": 1.0}, "sanity:frozen": {"tde": 2.0}},
          "index_criteria: per row and per column")
    for failure in failures:
        print(f"video_metric self-test: FAILED {failure}")
    print(f"video_metric self-test: {'failed' if failures else 'passed'}")
    return 1 if failures else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    if "--self-test" in sys.argv[1:]:
        sys.exit(self_test())
    parser.add_argument("--self-test", action="store_true",
                        help="test the PNG reader and Kendall tau (stdlib only) and exit")
    parser.add_argument("--cvvdp", help="ColorVideoVDP checkout (has pycvvdp/); required unless "
                        "--report-only")
    parser.add_argument("--frames", required=True, help="the folder saagen bench --frames wrote")
    parser.add_argument("--out", required=True, help="JSON with the JOD of every clip row")
    parser.add_argument("--table", help="the bench's --json table: print Kendall tau per scene, alpha")
    parser.add_argument("--columns", help="comma-separated criterion columns of --table "
                        f"(default: those of {','.join(DEFAULT_COLUMNS)} present)")
    parser.add_argument("--filter", help="regex; only rows whose 'scene/aALPHA/configuration' "
                        "matches (re.search), e.g. '/a(0.0025|0.3)/(none|engine-.*|.*/tail|sanity:.*)$'")
    parser.add_argument("--display", help="ColorVideoVDP display model (default: the index's "
                        "'display' when it names one, else standard_fhd)")
    parser.add_argument("--fps", type=float, help="frames per second (default: the index's 'fps', "
                        "else 30)")
    parser.add_argument("--reference-clip", metavar="NAME",
                        help="compare with this clip of each group instead of the ground truth "
                        "(e.g. sanity:other-seed; the ground truth becomes a row)")
    parser.add_argument("--ceiling", metavar="R2.json",
                        help="an --out of a run with --reference-clip: its JOD enters the tau table "
                        "as the column 'ceiling' (how far ColorVideoVDP agrees with itself when "
                        "only the ground truth's noise changes)")
    parser.add_argument("--resume", action="store_true",
                        help="keep the rows already in --out (same display and fps) and skip them")
    parser.add_argument("--batch", type=int, default=16,
                        help="rows of one clip per metric call (default 16)")
    parser.add_argument("--threads", type=int, default=1, help="torch threads (default 1)")
    parser.add_argument("--report-only", action="store_true",
                        help="do not run the metric: print the report of --out against --table")
    args = parser.parse_args()

    if not args.report_only and not args.cvvdp:
        fail("--cvvdp DIR is required: a ColorVideoVDP checkout (see docs/COLORVIDEOVDP.md)")
    if args.report_only:
        pass
    elif not os.path.isdir(args.cvvdp):
        fail(f"--cvvdp {args.cvvdp}: no such folder (a ColorVideoVDP checkout is needed)")
    elif not os.path.isdir(os.path.join(args.cvvdp, "pycvvdp")):
        fail(f"--cvvdp {args.cvvdp}: no pycvvdp/ folder there (a ColorVideoVDP checkout is needed)")
    index_path = os.path.join(args.frames, "index.json")
    if not os.path.isfile(index_path):
        fail(f"--frames {args.frames}: no index.json (written by saagen bench --frames DIR)")
    with open(index_path) as f:
        index = json.load(f)
    if index.get("version") != 1:
        fail(f"{index_path}: version {index.get('version')!r}, this script reads version 1")
    try:
        clips = index_clips(index)
    except (KeyError, TypeError, ValueError) as e:
        fail(f"{index_path}: not the layout saagen bench --frames writes ({e!r})")
    pattern = re.compile(args.filter) if args.filter else None

    criteria = None
    if args.table:
        criteria = table_criteria(args.table)
        for clip in clips:
            extra = index_criteria(clip)
            if extra:
                target = criteria.setdefault(clip_key(clip["scene"], clip["alpha"],
                                                     clip.get("fresnel", False)), {})
                for configuration, values in extra.items():
                    target.setdefault(configuration, {}).update(values)
    if args.ceiling:
        if criteria is None:
            fail("--ceiling needs --table")
        with open(args.ceiling) as f:
            for r in json.load(f)["rows"]:
                criteria.setdefault(clip_key(r["scene"], r["alpha"], r["fresnel"]), {}).setdefault(
                    r["configuration"], {})["ceiling"] = -float(r["jod"])  # lower is better
    if args.columns:
        columns = [c for c in args.columns.split(",") if c]
    elif criteria is not None:
        present = {c for per in criteria.values() for values in per.values() for c in values}
        columns = [c for c in DEFAULT_COLUMNS if c in present] + (["ceiling"] if args.ceiling else [])
    else:
        columns = []

    if args.report_only:
        with open(args.out) as f:
            previous = json.load(f)
        rows = [r for r in previous["rows"] if not pattern or pattern.search(
            f"{r['scene']}/a{alpha_key(r['alpha'])}/{r['configuration']}")]
        print_report(group_results(rows), criteria, columns)
        return

    try:
        import numpy as np
        import torch
    except ImportError as e:
        system = "/usr/bin/python3"
        if (os.environ.get(_REEXEC_ENV) is None and os.path.exists(system)
                and os.path.realpath(sys.executable) != os.path.realpath(system)):
            # Debian's python3-torch installs for the system interpreter; another python3 may
            # come first on PATH.
            os.environ[_REEXEC_ENV] = "1"
            os.execv(system, [system] + sys.argv)
        fail(f"{e} under {sys.executable} (Debian: apt-get install python3-torch "
             f"python3-torchvision python3-scipy python3-tqdm)")
    torch.set_num_threads(max(1, args.threads))
    cvvdp_metric = load_cvvdp(args.cvvdp, torch)
    version, commit = cvvdp_identity(args.cvvdp)

    display = args.display
    if display is None:
        with open(os.path.join(args.cvvdp, "pycvvdp", "vvdp_data", "display_models.json")) as f:
            known = json.load(f)
        display = index.get("display") if index.get("display") in known else "standard_fhd"
    fps = args.fps or float(index.get("fps") or 30.0)

    done = {}
    if args.resume and os.path.isfile(args.out):
        with open(args.out) as f:
            previous = json.load(f)
        if (previous.get("display") == display and previous.get("fps") == fps
                and previous.get("reference_clip") == (args.reference_clip or "ground-truth")):
            for r in previous.get("rows", []):
                done[(r["scene"], alpha_key(r["alpha"]), bool(r["fresnel"]), r["configuration"],
                      r["clip"])] = r

    import logging
    logging.getLogger().setLevel(logging.ERROR)
    metric = cvvdp_metric.cvvdp(display_name=display, device=torch.device("cpu"), quiet=True)

    result = {"metric": "ColorVideoVDP", "cvvdp_version": version, "cvvdp_commit": commit,
              "torch": torch.__version__, "display": display, "fps": fps,
              "frames": os.path.abspath(args.frames), "filter": args.filter,
              "reference_clip": args.reference_clip or "ground-truth", "rows": []}

    def save():
        tmp = args.out + ".tmp"
        with open(tmp, "w") as f:
            json.dump(result, f, indent=1)
        os.replace(tmp, args.out)

    todo = []
    for clip in clips:
        if args.reference_clip:
            # Another clip of the group as the reference (e.g. the ground truth with another seed):
            # the ground truth becomes a row.
            swap = [r for r in clip["rows"] if r["configuration"] == args.reference_clip]
            if not swap:
                continue
            clip = dict(clip, reference=swap[0]["path"],
                        rows=[{"configuration": "ground-truth", "path": clip["reference"]}]
                        + [r for r in clip["rows"] if r["configuration"] != args.reference_clip])
        rows = [r for r in clip.get("rows", []) if not pattern or pattern.search(row_label(clip, r))]
        if rows:
            todo.append((clip, rows))
    total = sum(len(rows) for _, rows in todo)
    print(f"ColorVideoVDP {version} ({commit[:12]}), torch {torch.__version__}, display {display}, "
          f"{fps:g} fps: {total} rows in {len(todo)} clips", file=sys.stderr)
    started, count, computed_seconds, computed = time.time(), 0, 0.0, 0
    for clip, rows in todo:
        pending = []
        for row in rows:
            count += 1
            key = (clip["scene"], alpha_key(clip["alpha"]), bool(clip.get("fresnel", False)),
                   row["configuration"], row["path"])
            if key in done:
                result["rows"].append(done[key])
            else:
                pending.append(row)
        if not pending:
            continue
        reference = load_clip(args.frames, clip["reference"], clip, np)
        reference_rgb = torch.from_numpy(np.repeat(reference[None, :, None], 3, axis=2))
        for first in range(0, len(pending), max(1, args.batch)):
            chunk = pending[first:first + max(1, args.batch)]
            tests = []
            for row in chunk:
                test = load_clip(args.frames, row["path"], clip, np)
                if test.shape != reference.shape:
                    raise ValueError(f"{row['path']}: frames {test.shape}, reference {reference.shape}")
                tests.append(test)
            # One batch of rows against the same reference (the same JODs as one call per row,
            # about 1.7x faster on a CPU).
            test_rgb = torch.from_numpy(np.repeat(np.stack(tests)[:, :, None], 3, axis=2))
            t0 = time.time()
            with torch.no_grad():
                jods, _ = metric.predict(test_rgb,
                                         reference_rgb.expand(len(chunk), -1, -1, -1, -1).contiguous(),
                                         dim_order="BFCHW", frames_per_second=fps)
            seconds = time.time() - t0
            computed_seconds += seconds
            computed += len(chunk)
            for row, jod in zip(chunk, jods.reshape(-1).tolist()):
                result["rows"].append({
                    "scene": clip["scene"], "alpha": clip["alpha"],
                    "fresnel": bool(clip.get("fresnel", False)),
                    "configuration": row["configuration"], "clip": row["path"],
                    "jod": round(float(jod), 4), "seconds": round(seconds / len(chunk), 3)})
        save()
        print(f"  {count}/{total} rows, {computed_seconds / max(computed, 1):.2f} s per clip row",
              file=sys.stderr)
    save()
    print(f"{count} rows ({computed} computed, {computed_seconds / max(computed, 1):.2f} s per clip "
          f"row in the metric, {time.time() - started:.0f} s in all) -> {args.out}", file=sys.stderr)
    print_report(group_results(result["rows"]), criteria, columns)


if __name__ == "__main__":
    main()
