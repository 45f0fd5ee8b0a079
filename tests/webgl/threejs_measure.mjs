// Whether following saagen beats no SAA in three.js, measured with saagen's own verdict metrics:
// the example scene (examples/threejs/scene.js, scene.saagen.toml) rendered in headless Chromium
// (WebGL2 on SwiftShader) as a short animation, its clips written in the format `saagen bench
// --frames` writes, then ranked by `saagen score` (image error, video error, lag, with 95 %
// intervals; each result against no SAA and against three.js's default).
//
// Per material of the plan (`saagen plan scene.saagen.toml --json`), the clips are:
//   ground truth, two seeds: the unfiltered material (installPlan with variant "none"), each
//     pixel the box-filtered mean of SCALE x SCALE x JITTERS samples: the scene rendered at SCALE
//     times the resolution, JITTERS times with a stratified random sub-pixel offset
//     (camera.setViewOffset), each seed its own offsets;
//   at one sample per pixel (pixel centres): "none" (installPlan with variant "none": three.js's
//     geometryRoughness term removed), "three-default" (three.js's material as shipped, with its
//     own geometryRoughness) and "saagen:VARIANT[+PREFILTER]" (installPlan with the plan's entry
//     and the manifest's gles bundle);
//   the sanity results: "sanity:other-seed" (the second seed, which score reads as such) and
//     "sanity:frozen" (its first frame held).
// The animation: the camera translates PAN pixels per frame (right, up), a fraction of a pixel.
//
// Display values: every render goes to a float render target (linear radiance, no tone mapping,
// no output encoding: three.js applies neither to a render target), the samples are averaged in
// linear radiance, and the pixel's Rec. 709 luminance is mapped as saagen's clips are: Reinhard
// x / (1 + x), then the sRGB encoding, rounded to 8 bits (report/frames.hpp). Not three.js's
// canvas output: the example renders without tone mapping, where every highlight clips at 1,
// and the verdict's metrics are defined on these display values; every clip gets the same mapping.
//
// The example scene has no baked roughness map: a plan with a bake would be measured without it
// (the filter and the bake's LOD bias); the example's plans have none.
//
//   node tests/webgl/threejs_measure.mjs SAAGEN_CLI OUT_DIR [--size N] [--frames N] [--scale N]
//        [--jitters N] [--pan X,Y] [--materials a,b] [--trade-table T.json] [--score-only]
// prints `saagen score`'s table and the per-material summary table (Markdown). The defaults: 128 x
// 128 pixels, 24 frames, 1024 samples per pixel in the ground truth (4 x 4 x 64), a pan of
// (0.37, 0.21) pixels per frame: about 6 minutes on 2 cores. --score-only scores OUT_DIR's clips
// again without rendering them.
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import zlib from 'node:zlib';
import { fileURLToPath } from 'node:url';
import { launchChromium, openPage, serveDirectory } from './browser.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');

export const DEFAULTS = { size: 128, frames: 24, scale: 4, jitters: 64, pan: [0.37, 0.21], materials: null, scoreOnly: false };
const SEEDS = [1, 2];
const ROUGHNESS = 0.05;  // scene.js's default

// --- PNG (8-bit greyscale), written with node's zlib (RFC 2083: signature, IHDR, IDAT, IEND).

const CRC_TABLE = Array.from({ length: 256 }, (_, n) => {
  let c = n;
  for (let k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
  return c >>> 0;
});

function crc32(bytes) {
  let c = 0xffffffff;
  for (const b of bytes) c = CRC_TABLE[(c ^ b) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

function pngChunk(type, data) {
  const head = Buffer.alloc(8);
  head.writeUInt32BE(data.length, 0);
  head.write(type, 4, 'ascii');
  const crc = Buffer.alloc(4);
  crc.writeUInt32BE(crc32(Buffer.concat([head.subarray(4), data])), 0);
  return Buffer.concat([head, data, crc]);
}

export function greyPng(width, height, pixels) {
  const header = Buffer.alloc(13);
  header.writeUInt32BE(width, 0);
  header.writeUInt32BE(height, 4);
  header[8] = 8;  // bit depth
  header[9] = 0;  // greyscale
  const rows = Buffer.alloc((width + 1) * height);
  for (let y = 0; y < height; ++y) {
    rows[y * (width + 1)] = 0;  // filter: none
    Buffer.from(pixels.buffer, pixels.byteOffset + y * width, width).copy(rows, y * (width + 1) + 1);
  }
  return Buffer.concat([Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]), pngChunk('IHDR', header),
                        pngChunk('IDAT', zlib.deflateSync(rows)), pngChunk('IEND', Buffer.alloc(0))]);
}

// --- Display values, as saagen's clips hold them (measure/image.hpp: display_value).

function srgbEncode(v) {
  const c = Math.min(Math.max(v, 0), 1);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * Math.pow(c, 1 / 2.4) - 0.055;
}

function displayBytes(luminance) {
  const bytes = new Uint8Array(luminance.length);
  for (let i = 0; i < luminance.length; ++i) {
    const l = Math.max(luminance[i], 0);
    bytes[i] = Math.round(255 * srgbEncode(l / (1 + l)));
  }
  return bytes;
}

// --- Sub-pixel offsets: a seeded generator (mulberry32) and JITTERS stratified offsets per frame.

function mulberry32(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

function stratifiedOffsets(random, count) {
  const side = Math.round(Math.sqrt(count));
  if (side * side !== count) throw new Error(`--jitters ${count}: must be a square (1, 4, 9, 16, ...)`);
  const offsets = [];
  for (let y = 0; y < side; ++y)
    for (let x = 0; x < side; ++x) offsets.push([(x + random()) / side - 0.5, (y + random()) / side - 0.5]);
  return offsets;
}

// --- The page side: one renderer; per scene key a scene built once; renders into a float target.

function pageSide() {
  const { THREE, buildScene } = window.saagenScene;
  const renderer = new THREE.WebGLRenderer({ canvas: document.createElement('canvas'), antialias: false });
  renderer.setPixelRatio(1);
  const scenes = new Map();
  const targets = new Map();
  const target = (side) => {
    if (!targets.has(side)) {
      targets.set(side, new THREE.WebGLRenderTarget(side, side, { type: THREE.FloatType, format: THREE.RGBAFormat,
        minFilter: THREE.NearestFilter, magFilter: THREE.NearestFilter, depthBuffer: true }));
    }
    return targets.get(side);
  };
  // The mean linear luminance per pixel (size x size, top row first) of `offsets.length` renders
  // at `scale` times the resolution, each shifted by an offset in [-0.5, 0.5)^2 of its pixels,
  // the camera moved by `shift` (world units, x and y).
  window.saagenMeasure = ({ key, mode, options, size, scale, offsets, shift }) => {
    if (!scenes.has(key)) scenes.set(key, buildScene(mode, options));
    const { scene, camera } = scenes.get(key);
    const side = size * scale;
    const rt = target(side);
    renderer.setSize(side, side, false);
    camera.position.set(shift[0], shift[1], 12);
    const sums = new Float64Array(size * size);
    const pixels = new Float32Array(side * side * 4);
    for (const [dx, dy] of offsets) {
      camera.setViewOffset(side, side, dx, dy, side, side);
      renderer.setRenderTarget(rt);
      renderer.render(scene, camera);
      renderer.readRenderTargetPixels(rt, 0, 0, side, side, pixels);
      for (let y = 0; y < side; ++y) {
        const row = size - 1 - Math.floor(y / scale);  // bottom row first in, top row first out
        for (let x = 0; x < side; ++x) {
          const i = 4 * (y * side + x);
          sums[row * size + Math.floor(x / scale)] += 0.2126 * pixels[i] + 0.7152 * pixels[i + 1] + 0.0722 * pixels[i + 2];
        }
      }
    }
    renderer.setRenderTarget(null);
    camera.clearViewOffset();
    const n = scale * scale * offsets.length;
    return Array.from(sums, (s) => s / n);
  };
  return renderer.capabilities.isWebGL2 && renderer.extensions.has('EXT_color_buffer_float');
}

// --- The measurement.

// The example manifest's plan and bundle; with `tradeTable` (a `saagen bench --json` table of
// content like the example's), planned and emitted with that table, as a user measuring their own
// content would.
function planAndSnippet(cli, tradeTable) {
  const manifest = path.join(root, 'examples/threejs/scene.saagen.toml');
  const table = tradeTable ? ['--trade-table', tradeTable] : [];
  const plan = JSON.parse(execFileSync(cli, ['plan', manifest, '--json', ...table], { encoding: 'utf8' }));
  const output = fs.mkdtempSync(path.join(os.tmpdir(), 'saagen-threejs-measure-'));
  execFileSync(cli, ['emit', '--manifest', manifest, '--output', output, ...table]);
  const snippet = fs.readFileSync(path.join(output, 'saa_threejs.essl'), 'utf8');
  fs.rmSync(output, { recursive: true, force: true });
  return { plan, snippet };
}

function planClipName(entry) {
  return `saagen:${entry.variant}${entry.prefilter && entry.prefilter !== 'none' ? `+${entry.prefilter}` : ''}`;
}

function fileName(clip) {
  return `${clip.replace(/[/:+]/g, '_')}.png`;
}

// Renders every clip and writes OUT_DIR/index.json and the PNGs; returns the index.
export async function renderClips(cli, outDir, settings) {
  const { size, frames, scale, jitters, pan } = settings;
  const { plan, snippet } = planAndSnippet(cli, settings.tradeTable);
  const entries = plan.materials.filter((m) => !settings.materials || settings.materials.includes(m.material));
  if (entries.length === 0) throw new Error(`--materials ${settings.materials}: the plan has none of them`);
  const worldPerPixel = (2 * 12 * Math.tan((20 * Math.PI) / 180)) / size;  // scene.js's camera: 40 degrees, 12 from the spheres
  const shift = (t) => [t * pan[0] * worldPerPixel, t * pan[1] * worldPerPixel];
  fs.mkdirSync(outDir, { recursive: true });
  const { server, origin } = await serveDirectory(root);
  const { browser, close } = await launchChromium();
  const written = new Map();  // clip file -> bytes already written (clips shared by materials)
  const groups = [];
  try {
    const { page, errors } = await openPage(browser, `${origin}/tests/webgl/threejs.html`);
    page.setDefaultTimeout(600000);
    await page.waitForFunction('window.saagenReady === true', { timeout: 20000 });
    if (!(await page.evaluate(pageSide))) throw new Error('WebGL2 with float render targets (EXT_color_buffer_float) is not available');
    // One clip: `frames` frames of the scene `key` (built with mode and options), each frame the
    // mean over `offsets(t)`, as display bytes.
    const clip = async (key, mode, options, clipScale, offsets) => {
      const bytes = new Uint8Array(size * size * frames);
      for (let t = 0; t < frames; ++t) {
        const luminance = await page.evaluate((args) => window.saagenMeasure(args),
                                              { key, mode, options, size, scale: clipScale, offsets: offsets(t), shift: shift(t) });
        bytes.set(displayBytes(luminance), t * size * size);
      }
      return bytes;
    };
    const writeClip = (file, bytes) => {
      if (!written.has(file)) {
        fs.mkdirSync(path.dirname(path.join(outDir, file)), { recursive: true });
        fs.writeFileSync(path.join(outDir, file), greyPng(size, size * frames, bytes));
        written.set(file, bytes);
      }
      return file;
    };
    for (const entry of entries) {
      const normalMap = entry.material.startsWith('bumpy');
      const content = normalMap ? 'normal-mapped' : 'smooth';  // the clips every material of a content shares
      const none = { variant: 'none', prefilter: 'none', feed: 'shading', functions: [] };
      const centre = () => [[0, 0]];
      const seeds = [];
      for (const seed of SEEDS) {
        const file = `${content}/ground-truth-seed${seed}.png`;
        if (!written.has(file)) {
          const random = mulberry32(seed);
          console.error(`rendering ${file} (${frames} frames, ${scale * scale * jitters} samples per pixel)`);
          writeClip(file, await clip(`${content}|none`, 'plan', { entry: none, normalMap, snippet }, scale, () => stratifiedOffsets(random, jitters)));
        }
        seeds.push(file);
      }
      const secondSeed = written.get(seeds[1]);
      const frozen = new Uint8Array(secondSeed.length);
      for (let t = 0; t < frames; ++t) frozen.set(secondSeed.subarray(0, size * size), t * size * size);
      const clips = [
        ['none', `${content}/none.png`, () => clip(`${content}|none`, 'plan', { entry: none, normalMap, snippet }, 1, centre)],
        ['three-default', `${content}/three-default.png`, () => clip(`${content}|three`, 'three', { normalMap }, 1, centre)],
        [planClipName(entry), `${entry.material}/${fileName(planClipName(entry))}`,
         () => clip(`${entry.material}|plan`, 'plan', { entry, normalMap, snippet }, 1, centre)],
        ['sanity:other-seed', seeds[1], null],
        ['sanity:frozen', `${content}/sanity_frozen.png`, async () => frozen],
      ];
      const listed = [];
      for (const [configuration, file, render] of clips) {
        if (render && !written.has(file)) {
          console.error(`rendering ${file}`);
          writeClip(file, await render());
        }
        listed.push({ configuration, file });
      }
      groups.push({ scene: 'threejs-example', material: entry.material, alpha: ROUGHNESS * ROUGHNESS, fresnel: true, width: size,
                    height: size, frames, reference: seeds[0], clips: listed });
    }
    if (errors.length > 0) throw new Error(`console errors: ${errors.slice(0, 3).join(' | ')}`);
  } finally {
    await close();
    server.close();
  }
  const index = {
    generator: 'tests/webgl/threejs_measure.mjs (the three.js example scene)',
    version: 1,
    fps: 30,
    display: '8-bit greyscale PNG, the clip\'s frames stacked top to bottom; display values: Reinhard x / (1 + x) of the linear luminance, then the sRGB encoding',
    settings: { size, frames, scale, jitters, pan, roughness: ROUGHNESS },
    groups,
  };
  fs.writeFileSync(path.join(outDir, 'index.json'), `${JSON.stringify(index, null, 1)}\n`);
  return index;
}

// `saagen score` on the clips: its text and its JSON.
export function score(cli, outDir) {
  const json = path.join(outDir, 'score.json');
  const text = execFileSync(cli, ['score', '--frames', outDir, '--baseline', 'none', '--baseline', 'three-default', '--json', json, '--force'],
                            { encoding: 'utf8' });
  return { text, json: JSON.parse(fs.readFileSync(json, 'utf8')) };
}

const interval = (i, digits) => `${i.mean.toFixed(digits)} [${i.low.toFixed(digits)}, ${i.high.toFixed(digits)}]`;

// Per material: each one-sample-per-pixel clip's image and video error, and its outcome against
// no SAA and three.js's default with the differences (image / video; * where the ground truth's
// noise limits the call: a tie whatever the interval).
export function summaryTable(scored) {
  const lines = ['| material | configuration | image error (LDR-FLIP) | video error (10 - JOD) | vs no SAA | vs three.js default |',
                 '|---|---|---|---|---|---|'];
  const signed = (d, digits) => `${d.mean >= 0 ? '+' : ''}${d.mean.toFixed(digits)}${d.ground_truth_limited ? '*' : ''}`;
  for (const group of scored.groups) {
    const material = group.material || group.name;
    for (const result of group.results) {
      if (result.sanity) continue;
      const against = (baseline) => {
        const c = group.comparisons.find((x) => x.configuration === result.configuration && x.baseline === baseline);
        return c ? `${c.outcome} (${signed(c.image_error, 4)} / ${signed(c.video_error, 3)})` : '-';
      };
      lines.push(`| ${material} | ${result.configuration} | ${interval(result.image_error, 4)} | ${interval(result.video_error, 3)} | ${against('none')} | ${against('three-default')} |`);
    }
  }
  return lines.join('\n');
}

function parseArguments(argv) {
  const [cli, outDir, ...rest] = argv;
  if (!cli || !outDir) {
    console.error('usage: node tests/webgl/threejs_measure.mjs SAAGEN_CLI OUT_DIR [--size N] [--frames N] [--scale N] [--jitters N] [--pan X,Y] [--materials a,b] [--trade-table T.json] [--score-only]');
    process.exit(2);
  }
  const settings = { ...DEFAULTS };
  for (let i = 0; i < rest.length; i += 2) {
    if (rest[i] === '--score-only') {
      settings.scoreOnly = true;
      --i;
      continue;
    }
    const [name, value] = [rest[i], rest[i + 1]];
    if (value === undefined) throw new Error(`${name}: needs a value`);
    if (name === '--pan') settings.pan = value.split(',').map(Number);
    else if (name === '--materials') settings.materials = value.split(',');
    else if (name === '--trade-table') settings.tradeTable = path.resolve(value);
    else if (['--size', '--frames', '--scale', '--jitters'].includes(name)) settings[name.slice(2)] = Number.parseInt(value, 10);
    else throw new Error(`${name}: not an option (--size, --frames, --scale, --jitters, --pan, --materials, --trade-table, --score-only)`);
  }
  return { cli, outDir, settings };
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
  const { cli, outDir, settings } = parseArguments(process.argv.slice(2));
  if (!settings.scoreOnly) {
    const started = Date.now();
    await renderClips(cli, outDir, settings);
    console.error(`rendered in ${((Date.now() - started) / 1000).toFixed(0)} s`);
  }
  const scored = score(cli, outDir);
  console.log(scored.text);
  console.log(summaryTable(scored.json));
}
