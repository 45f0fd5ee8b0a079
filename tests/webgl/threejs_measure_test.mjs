// A tiny run of threejs_measure.mjs (48 x 48 pixels, 8 frames, 400 samples per pixel in the
// ground truth): the three.js example's clips, rendered in headless Chromium, are scored by
// `saagen score`. Checks: every material of the plan has its rows (no SAA, three.js's default,
// the plan's, the sanity results), each compared with both baselines; the sanity results rank as
// they must (the ground truth's other seed below every one-sample-per-pixel clip in the image
// error, a frozen clip above it in both errors); the plan's "none" is no SAA exactly (a difference
// of 0); a filter the plan installs changes the clip.
//   node tests/webgl/threejs_measure_test.mjs SAAGEN_CLI
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { renderClips, score } from './threejs_measure.mjs';

const cli = process.argv[2];
if (!cli) {
  console.error('usage: node tests/webgl/threejs_measure_test.mjs PATH_TO_SAAGEN_CLI');
  process.exit(2);
}

const failures = [];
function check(condition, what) {
  console.log(`${condition ? 'ok  ' : 'FAIL'} ${what}`);
  if (!condition) failures.push(what);
}

const out = fs.mkdtempSync(path.join(os.tmpdir(), 'saagen-threejs-measure-test-'));
try {
  const index = await renderClips(cli, out, { size: 48, frames: 8, scale: 4, jitters: 25, pan: [0.37, 0.21], materials: null });
  const { json } = score(cli, out);
  check(json.groups.length === index.groups.length && json.groups.length === 7, `every material of the plan scored (${json.groups.length})`);
  for (const group of json.groups) {
    const result = (name) => group.results.find((r) => r.configuration === name);
    const plan = group.results.find((r) => r.configuration.startsWith('saagen:'));
    const names = group.results.map((r) => r.configuration);
    check(result('none') && result('three-default') && plan && result('sanity:other-seed') && result('sanity:frozen'),
          `${group.name}: its rows (${names.join(', ')})`);
    if (!plan) continue;
    const compared = (name, baseline) => group.comparisons.find((c) => c.configuration === name && c.baseline === baseline);
    check(compared(plan.configuration, 'none') && compared(plan.configuration, 'three-default') && compared('three-default', 'none'),
          `${group.name}: ${plan.configuration} compared with no SAA and three.js's default`);
    const other = result('sanity:other-seed'), frozen = result('sanity:frozen');
    const oneSample = group.results.filter((r) => !r.sanity);
    check(oneSample.every((r) => other.image_error.mean < r.image_error.mean),
          `${group.name}: another seed of the ground truth has the lowest image error (${other.image_error.mean.toFixed(4)} < ${oneSample.map((r) => r.image_error.mean.toFixed(4)).join(', ')})`);
    check(frozen.image_error.mean > other.image_error.mean && frozen.video_error.mean > other.video_error.mean,
          `${group.name}: a frozen clip is worse than another seed (image ${frozen.image_error.mean.toFixed(4)} > ${other.image_error.mean.toFixed(4)}, video ${frozen.video_error.mean.toFixed(3)} > ${other.video_error.mean.toFixed(3)})`);
    const againstNone = compared(plan.configuration, 'none');
    if (plan.configuration === 'saagen:none') {
      check(againstNone.image_error.mean === 0 && againstNone.video_error.mean === 0 && againstNone.outcome === 'ties',
            `${group.name}: the plan's "none" is no SAA exactly (${againstNone.outcome})`);
    } else {
      check(againstNone.image_error.mean !== 0, `${group.name}: ${plan.configuration} changes the clip (image error ${againstNone.image_error.mean >= 0 ? '+' : ''}${againstNone.image_error.mean.toFixed(4)} against no SAA)`);
    }
  }
} finally {
  fs.rmSync(out, { recursive: true, force: true });
}
if (failures.length > 0) {
  console.error(`${failures.length} check(s) failed`);
  process.exit(1);
}
