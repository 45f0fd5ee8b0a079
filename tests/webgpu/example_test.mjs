// The WebGPU example (examples/webgpu/) on Dawn for Node, SwiftShader's Vulkan: the manifest's WGSL
// bundle, emitted by the CLI, passes `saagen validate` (Tint) and, with the example's scene
// appended, compiles without a message; the filtered image is closer to the 16-sample ground truth
// than the unfiltered one (tonemapped RMSE); the filter changes only the beads, never the
// background; and the images are not empty.
//   node tests/webgpu/example_test.mjs SAAGEN_CLI
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { selectVulkanDriver } from '../../harness/webgpu/device.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const cli = process.argv[2];
if (!cli) {
  console.error('usage: node tests/webgpu/example_test.mjs PATH_TO_SAAGEN_CLI');
  process.exit(2);
}
selectVulkanDriver();
const { run, WIDTH } = await import('../../examples/webgpu/render.mjs');

const failures = [];
function check(condition, what) {
  console.log(`${condition ? 'ok  ' : 'FAIL'} ${what}`);
  if (!condition) failures.push(what);
}

const output = fs.mkdtempSync(path.join(os.tmpdir(), 'saagen-webgpu-example-'));
try {
  execFileSync(cli, ['emit', '--manifest', path.join(root, 'examples/webgpu/scene.saagen.toml'), '--output', output], { stdio: 'pipe' });
  const validation = execFileSync(cli, ['validate', output], { encoding: 'utf8' });
  check(/1 file\(s\) validated, 0 failed/.test(validation), `saagen validate (Tint) accepts the bundle: ${validation.trim().split('\n')[0]}`);
  const bundle = fs.readFileSync(path.join(output, 'saa_webgpu.wgsl'), 'utf8');
  const result = await run(bundle);  // throws on any Tint error or warning
  check(true, 'the bundle with the example scene appended compiles without a message');
  const { unfiltered, filtered, truth, rmse } = result;
  console.log(`     tonemapped RMSE vs the 16-sample ground truth: unfiltered ${rmse.unfiltered.toFixed(5)}, filtered ${rmse.filtered.toFixed(5)}`);
  check(rmse.filtered < rmse.unfiltered, 'the filtered image is closer to the ground truth than the unfiltered one');
  const lit = (image) => image.filter((v) => v > 0.01).length;
  check(lit(unfiltered) > 0 && lit(truth) > 0, `the images are lit (${lit(unfiltered)} and ${lit(truth)} pixels above 0.01)`);
  // Background pixels (bead centres on a 16 px grid, radius 5.5 px; 6.5 px leaves the rim's quads out).
  let background = 0;
  let changed = 0;
  for (let k = 0; k < unfiltered.length; ++k) {
    const x = (k % WIDTH) + 0.5;
    const y = Math.floor(k / WIDTH) + 0.5;
    const dx = x - (Math.floor(x / 16) * 16 + 8);
    const dy = y - (Math.floor(y / 16) * 16 + 8);
    if (dx * dx + dy * dy > 6.5 * 6.5) {
      ++background;
      if (filtered[k] !== unfiltered[k]) ++changed;
    }
  }
  check(changed === 0, `the filter leaves the ${background} background pixels unchanged (${changed} changed)`);
} finally {
  fs.rmSync(output, { recursive: true, force: true });
}
if (failures.length > 0) {
  console.error(`${failures.length} check(s) failed`);
  process.exit(1);
}
process.exit(0);
