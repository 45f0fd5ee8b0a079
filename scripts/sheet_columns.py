#!/usr/bin/env python3
"""Cut chosen columns out of a `saagen report` sheet (sheet_SCENE_alphaA.png) into a smaller PNG,
for the docs' before/after images. Standard library only (zlib), so it runs wherever the report does.

    python3 scripts/sheet_columns.py SHEET.png OUT.png CONFIGURATION ...

A sheet is a label band, then one column per configuration after the ground truth, each tile the
report's display size wide with a 2-pixel gutter (report/src/report.cpp, grid_png). The column order
is the trade's order of configurations, given by --order FILE (one per line; `saagen bench --json`'s
cases for one scene and alpha list them in that order). The ground truth column is always kept first.
"""
import argparse
import pathlib
import struct
import sys
import zlib

GUTTER = 2  # report/src/report.cpp: grid_png's gutter between tiles


def read_png_rgb(path):
    data = pathlib.Path(path).read_bytes()
    if data[:8] != b'\x89PNG\r\n\x1a\n':
        sys.exit(f"{path}: not a PNG")
    position, idat, width = 8, b'', None
    while position < len(data):
        length, kind = struct.unpack('>I4s', data[position:position + 8])
        body = data[position + 8:position + 8 + length]
        if kind == b'IHDR':
            width, height, depth, colour = struct.unpack('>IIBB', body[:10])
            if (depth, colour) != (8, 2):
                sys.exit(f"{path}: expected 8-bit RGB, as the report writes")
        elif kind == b'IDAT':
            idat += body
        position += 12 + length
    return width, height, unfilter(zlib.decompress(idat), width, height, 3)


def unfilter(raw, width, height, channels):
    """PNG's five row filters (ISO/IEC 15948, 9.2), undone row by row."""
    stride, rows, previous = width * channels, [], bytearray(width * channels)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            left = line[x - channels] if x >= channels else 0
            up, up_left = previous[x], previous[x - channels] if x >= channels else 0
            if kind == 1:
                line[x] = (line[x] + left) & 255
            elif kind == 2:
                line[x] = (line[x] + up) & 255
            elif kind == 3:
                line[x] = (line[x] + (left + up) // 2) & 255
            elif kind == 4:
                estimate = left + up - up_left
                pa, pb, pc = abs(estimate - left), abs(estimate - up), abs(estimate - up_left)
                predictor = left if pa <= pb and pa <= pc else up if pb <= pc else up_left
                line[x] = (line[x] + predictor) & 255
        rows.append(line)
        previous = line
    return rows


def write_png_rgb(path, width, rows):
    raw = b''.join(b'\x00' + bytes(row) for row in rows)
    chunk = lambda kind, body: struct.pack('>I', len(body)) + kind + body + struct.pack('>I', zlib.crc32(kind + body))
    png = b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', width, len(rows), 8, 2, 0, 0, 0))
    png += chunk(b'IDAT', zlib.compress(raw, 9)) + chunk(b'IEND', b'')
    pathlib.Path(path).write_bytes(png)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('sheet')
    parser.add_argument('output')
    parser.add_argument('configurations', nargs='+')
    parser.add_argument('--order', required=True, help='file: the sheet\'s configurations, one per line, in column order')
    args = parser.parse_args()
    order = [line.strip() for line in open(args.order) if line.strip()]
    width, height, rows = read_png_rgb(args.sheet)
    columns = 1 + len(order)
    tile = (width - (columns - 1) * GUTTER) // columns
    if columns * tile + (columns - 1) * GUTTER != width:
        sys.exit(f"{args.sheet}: {width} px is not {columns} columns of equal tiles; is --order this sheet's?")
    missing = [c for c in args.configurations if c not in order]
    if missing:
        sys.exit(f"{args.order}: no column {missing[0]}")
    keep = [0] + [1 + order.index(c) for c in args.configurations]
    out_rows = []
    for row in rows:
        out = bytearray()
        for index, column in enumerate(keep):
            start = column * (tile + GUTTER) * 3
            out += row[start:start + tile * 3]
            if index + 1 < len(keep):
                out += row[start + tile * 3:start + (tile + GUTTER) * 3] if column + 1 < columns else bytes([96] * GUTTER * 3)
        out_rows.append(out)
    write_png_rgb(args.output, len(out_rows[0]) // 3, out_rows)


if __name__ == '__main__':
    main()
