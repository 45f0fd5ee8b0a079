#!/usr/bin/env python3
"""Writes measure/src/video_vdp_tables.cpp: the published data of ColorVideoVDP (Mantiuk,
Hanji, Ashraf, Asano, Chapiro, ACM TOG 43(4), 2024) that saagen's C++ model
(measure/include/saagen/measure/video_vdp.hpp) reads, taken from a checkout of
https://github.com/gfxdisp/ColorVideoVDP (MIT): the calibrated parameters
(pycvvdp/vvdp_data/cvvdp_parameters.json), the castleCSF lookup table of the parameter file's
`csf` variant (csf_lut_<csf>.json), the display model `standard_fhd` (display_models.json) and
its colour space (color_spaces.json). Numbers only: every value is written as the shortest
decimal that reads back as the file's double.

    python3 scripts/video_vdp_tables.py --cvvdp /path/to/ColorVideoVDP [--check]

--check compares with the committed file instead of writing it (exit 1 when they differ). The
output is formatted with clang-format when it is installed (the repository's format_check).
Standard library only; the checkout is read, never imported.
"""

import argparse
import json
import os
import re
import shutil
import subprocess
import sys

OUTPUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "measure", "src",
                      "video_vdp_tables.cpp")

# The parameter file's keys the model reads, in the order of VideoVdpParameters (video_vdp_tables.hpp).
SCALARS = ["mask_p", "mask_c", "pu_dilate", "beta", "beta_t", "beta_tch", "beta_sch", "sensitivity_correction",
           "jod_a", "jod_exp", "ch_chrom_w", "ch_trans_w", "d_max", "image_int"]
VECTORS = [("mask_q", 4), ("sigma_tf", 4), ("beta_tf", 4), ("xcm_weights", 16), ("baseband_weight", 4)]
# What the C++ model implements; any other value in the parameter file is refused.
EXPECTED = {"masking_model": "mult-mutual", "local_adapt": "gpyr", "contrast": "weber_g1", "csf": "weber_fixed_size",
            "xchannel_masking": "on", "dclamp_type": "soft", "Bloch_int": "off"}
CSF_FIELDS = ["o0_c1", "o0_c2", "o0_c3", "o5_c1"]  # sustained achromatic, RG, YV; transient achromatic


def number(x):
    text = repr(float(x))
    return text if ("e" in text or "." in text or "inf" in text or "nan" in text) else text + ".0"


def array(values):
    return "{" + ", ".join(number(v) for v in values) + "}"


def identity(path):
    version = "unknown"
    with open(os.path.join(path, "pyproject.toml")) as f:
        m = re.search(r'^version\s*=\s*"([^"]+)"', f.read(), re.M)
        if m:
            version = m.group(1)
    try:
        commit = subprocess.run(["git", "-C", path, "rev-parse", "HEAD"], capture_output=True, text=True,
                                timeout=10).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        commit = ""
    return version, commit or "unknown"


def generate(path):
    data = os.path.join(path, "pycvvdp", "vvdp_data")
    with open(os.path.join(data, "cvvdp_parameters.json")) as f:
        parameters = json.load(f)
    for key, value in EXPECTED.items():
        if parameters.get(key) != value:
            sys.exit(f"video_vdp_tables: {key} = {parameters.get(key)!r} in cvvdp_parameters.json; the C++ model "
                     f"implements {value!r}")
    with open(os.path.join(data, f"csf_lut_{parameters['csf']}.json")) as f:
        csf = json.load(f)
    with open(os.path.join(data, "display_models.json")) as f:
        display = json.load(f)["standard_fhd"]
    with open(os.path.join(data, "color_spaces.json")) as f:
        colour = json.load(f)[display.get("colorspace", "sRGB")]
    version, commit = identity(path)

    if list(csf["omega"]) != [0, 5]:
        sys.exit(f"video_vdp_tables: the CSF table's temporal frequencies are {csf['omega']}, expected [0, 5]")
    n_l, n_rho = len(csf["L_bkg"]), len(csf["rho"])

    out = []
    w = out.append
    w("// ColorVideoVDP's published data, as numbers: written by scripts/video_vdp_tables.py (do not edit;")
    w("// rerun it) from ColorVideoVDP " + version + " (github.com/gfxdisp/ColorVideoVDP, MIT, commit")
    w("// " + commit + "), pycvvdp/vvdp_data/: cvvdp_parameters.json (version " + str(parameters["version"]) + "),")
    w("// csf_lut_" + parameters["csf"] + ".json, display_models.json (standard_fhd) and color_spaces.json (" +
      display.get("colorspace", "sRGB") + ").")
    w('#include "video_vdp_tables.hpp"')
    w("")
    w("namespace saagen::measure::video_vdp_data {")
    w("")
    w("// cvvdp_parameters.json, by key.")
    w("const VideoVdpParameters kParameters = {")
    for key in SCALARS:
        w(f"    {number(parameters[key])},  // {key}")
    for key, n in VECTORS:
        values = parameters[key]
        if len(values) != n:
            sys.exit(f"video_vdp_tables: {key} has {len(values)} values, expected {n}")
        w(f"    {array(values)},  // {key}")
    w("};")
    w("")
    w("// display_models.json, standard_fhd: " + display["name"])
    w("const DisplayData kStandardFhd = {")
    w(f"    {display['resolution'][0]}, {display['resolution'][1]},  // resolution")
    w(f"    {number(display['viewing_distance_meters'])},  // viewing_distance_meters")
    w(f"    {number(display['diagonal_size_inches'])},  // diagonal_size_inches")
    w(f"    {number(display['max_luminance'])},  // max_luminance")
    w(f"    {number(display['contrast'])},  // contrast")
    w(f"    {number(display.get('E_ambient', 0))},  // E_ambient")
    w(f"    {number(display.get('k_refl', 0.005))},  // k_refl (the file's default 0.005 when absent)")
    w("};")
    w("")
    w("// color_spaces.json: RGB2X, RGB2Y, RGB2Z (linear RGB to CIE XYZ); EOTF " + colour["EOTF"] + ".")
    w(f"const double kRgbToXyz[3][3] = {{{array(colour['RGB2X'])}, {array(colour['RGB2Y'])}, {array(colour['RGB2Z'])}}};")
    w("")
    w(f"// csf_lut_{parameters['csf']}.json: the background luminances L_bkg [cd/m^2] ({n_l}) and spatial")
    w(f"// frequencies rho [cycles/degree] ({n_rho}) of the table, and log10 of the sensitivity at each,")
    w("// [L_bkg][rho], for the sustained achromatic, red-green and yellow-violet channels (omega = 0 Hz:")
    w("// o0_c1, o0_c2, o0_c3) and the transient achromatic channel (omega = 5 Hz: o5_c1).")
    w(f"const double kCsfLuminance[{n_l}] = {array(csf['L_bkg'])};")
    w(f"const double kCsfRho[{n_rho}] = {array(csf['rho'])};")
    w(f"const double kCsfLogSensitivity[4][{n_l}][{n_rho}] = {{")
    for field in CSF_FIELDS:
        table = csf[field]
        if len(table) != n_l or any(len(row) != n_rho for row in table):
            sys.exit(f"video_vdp_tables: {field} is not {n_l} x {n_rho}")
        w(f"    // {field}")
        w("    {" + ", ".join(array(row) for row in table) + "},")
    w("};")
    w("")
    w("}  // namespace saagen::measure::video_vdp_data")
    text = "\n".join(out) + "\n"
    clang_format = shutil.which("clang-format")
    if clang_format:
        text = subprocess.run([clang_format, "--assume-filename=" + OUTPUT], input=text, capture_output=True, text=True,
                              check=True, cwd=os.path.dirname(OUTPUT)).stdout
    return text


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cvvdp", required=True, help="a ColorVideoVDP checkout (has pycvvdp/vvdp_data/)")
    parser.add_argument("--check", action="store_true", help="compare with the committed file; do not write")
    args = parser.parse_args()
    if not os.path.isdir(os.path.join(args.cvvdp, "pycvvdp", "vvdp_data")):
        sys.exit(f"video_vdp_tables: --cvvdp {args.cvvdp}: no pycvvdp/vvdp_data/ there")
    text = generate(args.cvvdp)
    if args.check:
        with open(OUTPUT) as f:
            same = f.read() == text
        print(f"video_vdp_tables: {os.path.relpath(OUTPUT)} {'matches' if same else 'DIFFERS from'} the checkout")
        sys.exit(0 if same else 1)
    with open(OUTPUT, "w") as f:
        f.write(text)
    print(f"video_vdp_tables: wrote {os.path.relpath(OUTPUT)}")


if __name__ == "__main__":
    main()
