// The three.js example (examples/threejs/) in headless Chromium, WebGL2 on SwiftShader: a saagen
// GLSL ES snippet installed into MeshPhysicalMaterial compiles, renders, and changes the picture
// where the filter acts (small glossy spheres: high curvature per pixel at roughness 0.05), and
// nowhere else; clearcoat is filtered too; two configurations never share a program; the filter
// reads the geometric normal by default and the normal-mapped one with normal: 'shading' (the same
// picture without a normal map, another with one); with a bake (option bake) the compiled shader
// samples the normal map and the bake (the roughness maps) one MIP level coarser (saagen's advice,
// PREFILTER_LOD_BIAS), without one (either normal) and unfiltered at the implicit LOD.
//   node tests/webgl/threejs_test.mjs SAAGEN_CLI
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { launchChromium, openPage, serveDirectory } from './browser.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const cli = process.argv[2];
if (!cli) {
  console.error('usage: node tests/webgl/threejs_test.mjs PATH_TO_SAAGEN_CLI');
  process.exit(2);
}
if (!fs.existsSync(path.join(root, 'node_modules/three/package.json'))) {
  console.error(`${root}/package.json: node_modules is missing; run npm ci in ${root} (scripts/install-deps.sh does)`);
  process.exit(2);
}

const failures = [];
function check(condition, what) {
  console.log(`${condition ? 'ok  ' : 'FAIL'} ${what}`);
  if (!condition) failures.push(what);
}

const output = fs.mkdtempSync(path.join(os.tmpdir(), 'saagen-threejs-'));
execFileSync(cli, ['emit', '--target', 'gles', '--variant', 'deferred-sum', '--variant', 'deferred-avg', '--output', output]);
const snippet = fs.readFileSync(path.join(output, 'saa_deferred_sum.essl'), 'utf8');
const avgSnippet = fs.readFileSync(path.join(output, 'saa_deferred_avg.essl'), 'utf8');
fs.rmSync(output, { recursive: true, force: true });

const { server, origin } = await serveDirectory(root);
const { browser, close } = await launchChromium();
try {
  const { page, errors } = await openPage(browser, `${origin}/tests/webgl/threejs.html`);
  await page.waitForFunction('window.saagenReady === true', { timeout: 20000 });
  const result = await page.evaluate((snippet, avgSnippet) => {
    const { createRenderer, renderScene, SIZE } = window.saagenScene;
    const fresh = (mode, options = {}) => {
      const canvas = document.createElement('canvas');
      const renderer = createRenderer(canvas);
      const pixels = renderScene(renderer, mode, { snippet, ...options });
      const log = [];
      const fragments = [];
      for (const program of renderer.info.programs ?? []) {
        const gl = renderer.getContext();
        const info = gl.getProgramInfoLog(program.program);
        if (info) log.push(info);
        for (const shader of gl.getAttachedShaders(program.program)) {
          if (gl.getShaderParameter(shader, gl.SHADER_TYPE) === gl.FRAGMENT_SHADER) fragments.push(gl.getShaderSource(shader));
        }
      }
      // Release the WebGL context now: Chromium keeps at most 16 live and loses the oldest (the
      // shared renderer) when a 17th is created, which then renders a restored, different picture.
      renderer.dispose();
      renderer.forceContextLoss();
      return { pixels, log, fragments };
    };
    // Luminance of the sRGB bytes, 0..1.
    const luminance = (p, i) => (0.2126 * p[i] + 0.7152 * p[i + 1] + 0.0722 * p[i + 2]) / 255;
    const stats = (pixels) => {
      let peak = 0, lit = 0, sum = 0;
      for (let i = 0; i < pixels.length; i += 4) {
        const y = luminance(pixels, i);
        peak = Math.max(peak, y); sum += y; if (y > 0) ++lit;
      }
      let bright = 0;
      for (let i = 0; i < pixels.length; i += 4) if (luminance(pixels, i) >= 0.5 * peak) ++bright;
      return { peak, lit, bright, mean: sum / (pixels.length / 4) };
    };
    const compare = (a, b) => {
      let differing = 0, outside = 0;
      for (let i = 0; i < a.length; i += 4) {
        const d = Math.max(Math.abs(a[i] - b[i]), Math.abs(a[i + 1] - b[i + 1]), Math.abs(a[i + 2] - b[i + 2]));
        const covered = a[i] + a[i + 1] + a[i + 2] + b[i] + b[i + 1] + b[i + 2] > 0;
        if (d > 2) { ++differing; if (!covered) ++outside; }
      }
      return { differing, outside };
    };
    const three = fresh('three'), unfiltered = fresh('unfiltered'), saagen = fresh('saagen');
    const noClearcoatFilter = (() => {
      const canvas = document.createElement('canvas');
      const renderer = createRenderer(canvas);
      return renderScene(renderer, 'saagen', { snippet, clearcoatFilter: false });
    })();
    const avg = fresh('saagen', { snippet: avgSnippet, wrapper: 'deferred_avg_fragment' });
    // One renderer, configurations in turn: a shared program would repeat the first picture.
    const shared = createRenderer(document.createElement('canvas'));
    const sequence = ['unfiltered', 'saagen', 'three'].map((mode) => renderScene(shared, mode, { snippet }));
    const sharedAvg = renderScene(shared, 'saagen', { snippet: avgSnippet, wrapper: 'deferred_avg_fragment' });
    const programs = shared.info.programs.length;
    // Which normal: without a normal map the geometric and shading normals are the same vector;
    // with one, only the shading normal carries the map's detail into the kernel.
    const shading = fresh('saagen', { normal: 'shading' });
    const mappedUnfiltered = fresh('unfiltered', { normalMap: true });
    const mappedGeometric = fresh('saagen', { normalMap: true });
    const mappedShading = fresh('saagen', { normalMap: true, normal: 'shading' });
    const mappedBaked = fresh('saagen', { normalMap: true, bake: true });
    const sharedMapped = createRenderer(document.createElement('canvas'));
    const mappedSequence = ['geometric', 'shading'].map((normal) => renderScene(sharedMapped, 'saagen', { snippet, normalMap: true, normal }));
    const equal = (a, b) => compare(a, b).differing === 0;
    // The texture reads of the compiled fragment shaders (the fresh renderer's one program).
    const reads = ['normalMap, vNormalMapUv', 'roughnessMap, vRoughnessMapUv', 'clearcoatNormalMap, vClearcoatNormalMapUv',
                   'clearcoatRoughnessMap, vClearcoatRoughnessMapUv'];
    const biasOf = (run) => reads.map((read) => {
      const text = run.fragments.join('\n');
      if (text.includes(`texture2D( ${read}, ${window.saagenLodBias.toFixed(1)} )`)) return window.saagenLodBias;
      return text.includes(`texture2D( ${read} )`) ? 0 : null;
    });
    return {
      size: SIZE,
      stats: { three: stats(three.pixels), unfiltered: stats(unfiltered.pixels), saagen: stats(saagen.pixels), avg: stats(avg.pixels) },
      saagenVsUnfiltered: compare(saagen.pixels, unfiltered.pixels),
      saagenVsThree: compare(saagen.pixels, three.pixels),
      clearcoat: compare(saagen.pixels, noClearcoatFilter),
      sequenceMatchesFresh: [equal(sequence[0], unfiltered.pixels), equal(sequence[1], saagen.pixels), equal(sequence[2], three.pixels),
                             equal(sharedAvg, avg.pixels)],
      programs,
      avgVsSum: compare(avg.pixels, saagen.pixels),
      shadingVsGeometric: compare(shading.pixels, saagen.pixels),
      mapped: {
        geometricVsUnfiltered: compare(mappedGeometric.pixels, mappedUnfiltered.pixels),
        shadingVsGeometric: compare(mappedShading.pixels, mappedGeometric.pixels),
        geometricVsNoMap: compare(mappedGeometric.pixels, saagen.pixels),
        shadingVsNoMap: compare(mappedShading.pixels, shading.pixels),
        sequenceMatchesFresh: [equal(mappedSequence[0], mappedGeometric.pixels), equal(mappedSequence[1], mappedShading.pixels)],
      },
      lodBias: { value: window.saagenLodBias, baked: biasOf(mappedBaked), geometric: biasOf(mappedGeometric), shading: biasOf(mappedShading),
                 unfiltered: biasOf(mappedUnfiltered), programs: mappedBaked.fragments.length },
    };
  }, snippet, avgSnippet);
  console.log(JSON.stringify(result.stats));
  const { stats } = result;
  check(errors.length === 0, `no console errors or exceptions (${errors.slice(0, 3).join(' | ')})`);
  // Every sphere pixel is lit by the ambient term (a few grazing ones round to black without the
  // filter's wider lobe).
  check(stats.unfiltered.lit > 5000 && stats.saagen.lit >= stats.unfiltered.lit && stats.saagen.lit === stats.three.lit,
        `the spheres render (${stats.saagen.lit} lit pixels; unfiltered ${stats.unfiltered.lit}, three.js ${stats.three.lit})`);
  check(result.saagenVsUnfiltered.differing > 200,
        `the filter changes the picture where it acts: ${result.saagenVsUnfiltered.differing} pixels differ by > 2/255 from the unfiltered render`);
  check(result.saagenVsUnfiltered.outside === 0, `and nowhere outside the spheres (${result.saagenVsUnfiltered.outside})`);
  // Raising roughness spreads a highlight (the peak saturates at 1 in both): the bright area, at
  // least half the peak, grows, and so does the mean (a wider lobe is not lost between pixels).
  check(stats.saagen.bright > 2 * stats.unfiltered.bright && stats.saagen.mean > stats.unfiltered.mean,
        `highlights widen: ${stats.saagen.bright} vs ${stats.unfiltered.bright} bright pixels, mean ${stats.saagen.mean.toFixed(5)} vs ${stats.unfiltered.mean.toFixed(5)}`);
  check(result.clearcoat.differing > 50, `the clearcoat roughness is filtered too (${result.clearcoat.differing} pixels change without it)`);
  check(result.avgVsSum.differing > 0, `another variant gives another picture (${result.avgVsSum.differing} pixels)`);
  check(result.sequenceMatchesFresh.every(Boolean) && result.programs >= 4,
        `one renderer, four configurations: ${result.programs} programs, each picture as from a fresh renderer (${result.sequenceMatchesFresh})`);
  check(result.shadingVsGeometric.differing === 0,
        `without a normal map, normal: 'shading' gives the default (geometric) picture (${result.shadingVsGeometric.differing} pixels differ)`);
  const { mapped } = result;
  // The map shades either way; with the shading normal its detail also widens the filter.
  check(mapped.shadingVsNoMap.differing > 200 && mapped.geometricVsNoMap.differing > 0,
        `the normal map changes the picture (normal: 'shading': ${mapped.shadingVsNoMap.differing} pixels; the geometric normal: ${mapped.geometricVsNoMap.differing})`);
  check(mapped.geometricVsUnfiltered.differing > 200 && mapped.geometricVsUnfiltered.outside === 0,
        `with a normal map, the geometric-normal filter acts on the spheres (${mapped.geometricVsUnfiltered.differing} pixels) and nowhere else (${mapped.geometricVsUnfiltered.outside})`);
  check(mapped.shadingVsGeometric.differing > 200 && mapped.shadingVsGeometric.outside === 0,
        `with a normal map, normal: 'shading' reads the mapped normal: ${mapped.shadingVsGeometric.differing} pixels differ from the geometric-normal picture`);
  check(mapped.sequenceMatchesFresh.every(Boolean),
        `one renderer keeps the geometric and shading configurations apart (${mapped.sequenceMatchesFresh})`);
  const { lodBias } = result;
  check(lodBias.value === 1 && lodBias.programs >= 1 && lodBias.baked.every((bias) => bias === lodBias.value),
        `with a bake the compiled shader samples the normal maps and the roughness maps with the LOD bias +${lodBias.value} (${lodBias.baked})`);
  check([lodBias.geometric, lodBias.shading, lodBias.unfiltered].every((reads) => reads.every((bias) => bias === 0)),
        `without a bake (geometric, shading) and unfiltered they are sampled at the implicit LOD (${lodBias.geometric}; ${lodBias.shading}; ${lodBias.unfiltered})`);
  console.log(`three.js: saagen vs three.js as shipped: ${result.saagenVsThree.differing} pixels differ`);
} finally {
  await close();
  server.close();
}
if (failures.length > 0) {
  console.error(`${failures.length} check(s) failed`);
  process.exit(1);
}
