#!/usr/bin/env node
// Self-test of the WebGPU job runner (run.mjs) on this machine's Dawn for Node + SwiftShader.
//
//   node harness/webgpu/selftest.mjs                       # checks; exit status 1 if any failed
//   node harness/webgpu/selftest.mjs --bench N [--pad-kb K]  # timing of N compute jobs
//
// The checks write a temporary DIR with jobs.json and inputs, run `node run.mjs DIR` as a child
// process, exactly as the C++ side does, and compare results.json and the output files with
// what the shaders must produce:
//   - a compute job: output[i] = input[i] * 2 + 1 (and 1 everywhere when no input is given),
//   - a fragment job: output[y * w + x] = position.x + 1000 * position.y at pixel centres,
//   - compile jobs: a type error reported with its line, a derivative in non-uniform control
//     flow reported as an error, a module whose pipelines compile cleanly, and a workgroup size
//     that only pipeline creation refuses,
//   - a compute job that samples a 2-layer rgba16float texture with 3 MIP levels (linear filters,
//     mirror-repeat) at texel centres, between texels, between levels and across the mirrored
//     edge, where the filtered values are exact; and a texture whose file has the wrong size,
//   - a job that the runner must refuse (too many invocations), followed by one that must run,
//   - a DIR that does not exist: exit status 1 and one line on stderr.
// It prints one line per check, the adapter and whether it offers shader-f16, and closes with
// "webgpu selftest: N passed, M failed".
//
// --bench N writes N compute jobs of 16384 invocations with N distinct modules (so none is
// compiled only once for all), all reading one 64 KiB input, and prints the runner's wall time;
// --pad-kb K makes every module about K KB longer with a chain of helper functions that main
// calls, so the size of real emitted modules can be imitated.
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const RUNNER = path.join(path.dirname(fileURLToPath(import.meta.url)), 'run.mjs');

const BINDINGS = `@group(0) @binding(0) var<storage, read> saagen_input: array<f32>;
@group(0) @binding(1) var<storage, read_write> saagen_output: array<f32>;
`;

// output[i] = input[i] * 2 + 1, reading 0 past the end of the input (as with no input at all).
function doublingModule(extraFunctions = '', extraCall = 'x') {
  return `${BINDINGS}${extraFunctions}
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
  let i = id.x;
  if (i >= arrayLength(&saagen_output)) { return; }
  var x = 0.0;
  if (i < arrayLength(&saagen_input)) { x = saagen_input[i]; }
  saagen_output[i] = ${extraCall} * 2.0 + 1.0;
}
`;
}

function positionModule(width) {
  return `${BINDINGS}
@fragment
fn fs(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
  let index = u32(position.y) * ${width}u + u32(position.x);
  saagen_output[index] = position.x + 1000.0 * position.y;
  return vec4<f32>(0.0, 0.0, 0.0, 1.0);
}
`;
}

// The type error sits on line 3 of this module.
const TYPE_ERROR_MODULE = `fn helper() -> f32 {
  let a = 1.0;
  let b: f32 = 2u;
  return a + b;
}
`;

const NON_UNIFORM_DERIVATIVE_MODULE = `@fragment
fn fs(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
  var slope = 0.0;
  if (position.x > 8.0) {
    slope = dpdx(position.y);
  }
  return vec4<f32>(slope);
}
`;

const TOO_WIDE_WORKGROUP_MODULE = `@compute @workgroup_size(1024)
fn main() {}
`;

// The texture check: texel (layer l, level m, x) holds TEXEL_VALUE(l, m, x) + channel / 4, values
// that half precision holds exactly, so that filtered results can be compared for equality.
const TEXTURE = { width: 4, height: 1, layers: 2, levels: 3 };
const texelValue = (layer, level, x, channel) => 100 * layer + 10 * level + x + channel / 4;

// IEEE half bits of a value that half precision represents exactly (normal, positive, or 0).
function halfBits(value) {
  if (value === 0) return 0;
  const exponent = Math.floor(Math.log2(value));
  const mantissa = (value / 2 ** exponent - 1) * 1024;
  if (!Number.isInteger(mantissa)) throw new Error(`${value} is not a half`);
  return ((exponent + 15) << 10) | mantissa;
}

function textureBytes() {
  const halves = [];
  for (let level = 0; level < TEXTURE.levels; ++level) {
    for (let layer = 0; layer < TEXTURE.layers; ++layer) {
      for (let x = 0; x < Math.max(1, TEXTURE.width >> level); ++x) {
        for (let channel = 0; channel < 4; ++channel) halves.push(halfBits(texelValue(layer, level, x, channel)));
      }
    }
  }
  return Buffer.from(new Uint16Array(halves).buffer);
}

// Queries (u, layer, lod) and the exact result of channel 0 (channel c adds c / 4).
const TEXTURE_QUERIES = [
  ...[0, 1].flatMap((layer) => [0, 1, 2].flatMap((level) => Array.from({ length: TEXTURE.width >> level }, (_, x) => (
    { u: (x + 0.5) / (TEXTURE.width >> level), layer, lod: level, expected: texelValue(layer, level, x, 0) })))),
  { u: 0.5, layer: 1, lod: 0, expected: (texelValue(1, 0, 1, 0) + texelValue(1, 0, 2, 0)) / 2 },  // between texels 1 and 2
  { u: 0.125, layer: 0, lod: 0.5, expected: (texelValue(0, 0, 0, 0) + texelValue(0, 1, 0, 0)) / 2 },  // level 1 mirrors texel 0
  { u: -0.125, layer: 1, lod: 0, expected: texelValue(1, 0, 0, 0) },  // mirror-repeat: -u
  { u: 1.375, layer: 0, lod: 0, expected: texelValue(0, 0, 2, 0) },   // mirror-repeat: 2 - u
];

const TEXTURE_MODULE = `${BINDINGS}@group(0) @binding(2) var saagen_texture: texture_2d_array<f32>;
@group(0) @binding(3) var saagen_sampler: sampler;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
  let i = id.x;
  if (4u * i >= arrayLength(&saagen_output)) { return; }
  let q = vec3<f32>(saagen_input[3u * i], saagen_input[3u * i + 1u], saagen_input[3u * i + 2u]);
  let t = textureSampleLevel(saagen_texture, saagen_sampler, vec2<f32>(q.x, 0.5), i32(q.y), q.z);
  for (var c = 0u; c < 4u; c++) { saagen_output[4u * i + c] = t[c]; }
}
`;

function textureJob(id, file) {
  return { id, kind: 'compute', code: TEXTURE_MODULE, input: 'texture_queries.f32', invocations: TEXTURE_QUERIES.length,
           output_floats: 4 * TEXTURE_QUERIES.length,
           texture: { file, format: 'rgba16float', ...TEXTURE, filter: 'linear', mipmap_filter: 'linear',
                      address_mode: 'mirror-repeat' } };
}

function writeFloats(file, values) {
  fs.writeFileSync(file, Buffer.from(new Float32Array(values).buffer));
}

function readFloats(file) {
  const bytes = fs.readFileSync(file);
  return new Float32Array(bytes.buffer, bytes.byteOffset, bytes.length / 4);
}

function runRunner(dir) {
  const started = performance.now();
  const child = spawnSync(process.execPath, [RUNNER, dir], { encoding: 'utf8' });
  return { status: child.status, signal: child.signal, stdout: child.stdout, stderr: child.stderr,
           seconds: (performance.now() - started) / 1000 };
}

// The index of the first element where `actual` differs from expected(i), or -1.
function firstMismatch(actual, count, expected) {
  if (actual.length !== count) return 0;
  for (let i = 0; i < count; ++i) if (actual[i] !== expected(i)) return i;
  return -1;
}

// --- the checks ---------------------------------------------------------------------------------

const COMPUTE_COUNT = 16384 + 37; // not a multiple of 64: the last workgroup runs past the end
const FRAGMENT_WIDTH = 37;
const FRAGMENT_HEIGHT = 23;

function inputValue(i) {
  return i * 0.25 - 1000;
}

function checkJobs(dir) {
  writeFloats(path.join(dir, 'ramp.f32'), Array.from({ length: COMPUTE_COUNT }, (_, i) => inputValue(i)));
  writeFloats(path.join(dir, 'texture_queries.f32'), TEXTURE_QUERIES.flatMap((q) => [q.u, q.layer, q.lod]));
  fs.writeFileSync(path.join(dir, 'texture.rgba16float'), textureBytes());
  fs.writeFileSync(path.join(dir, 'texture_short.rgba16float'), textureBytes().subarray(8));
  return [
    { id: 'type_error', kind: 'compile', code: TYPE_ERROR_MODULE },
    { id: 'non_uniform_dpdx', kind: 'compile', code: NON_UNIFORM_DERIVATIVE_MODULE,
      entry_points: [{ stage: 'fragment', name: 'fs' }] },
    { id: 'clean_pipelines', kind: 'compile', code: doublingModule() + positionModule(4).replace(BINDINGS, ''),
      entry_points: [{ stage: 'compute', name: 'main' }, { stage: 'fragment', name: 'fs' }] },
    { id: 'too_wide_workgroup', kind: 'compile', code: TOO_WIDE_WORKGROUP_MODULE,
      entry_points: [{ stage: 'compute', name: 'main' }] },
    { id: 'too_many_invocations', kind: 'compute', code: doublingModule(), output_floats: 4, invocations: 65535 * 64 + 1 },
    { id: 'doubling', kind: 'compute', code: doublingModule(), input: 'ramp.f32',
      output_floats: COMPUTE_COUNT, invocations: COMPUTE_COUNT },
    { id: 'doubling_no_input', kind: 'compute', code: doublingModule(), output_floats: 100, invocations: 100 },
    { id: 'positions', kind: 'fragment', code: positionModule(FRAGMENT_WIDTH), width: FRAGMENT_WIDTH,
      height: FRAGMENT_HEIGHT, output_floats: FRAGMENT_WIDTH * FRAGMENT_HEIGHT },
    textureJob('texture', 'texture.rgba16float'),
    textureJob('texture_short', 'texture_short.rgba16float'),
  ];
}

// Each check returns null when it holds, or what went wrong.
function resultChecks(dir, byId) {
  const errorsOf = (result) => result.messages.filter((message) => message.type === 'error');
  return {
    'type error reported with its line': () => {
      const result = byId.type_error;
      const error = errorsOf(result)[0];
      if (!result.error || !error) return `no error: ${JSON.stringify(result)}`;
      return error.line === 3 && error.column > 0 ? null : `reported at ${error.line}:${error.column}, expected line 3`;
    },
    'non-uniform dpdx reported as an error': () => {
      const result = byId.non_uniform_dpdx;
      const error = errorsOf(result).find((message) => /uniform/.test(message.message));
      return result.error && error?.line === 5 ? null : `not reported as an error on line 5: ${JSON.stringify(result.messages)}`;
    },
    'clean module: no messages, both pipelines created': () => {
      const result = byId.clean_pipelines;
      return !result.error && result.messages.length === 0 && result.pipeline_errors.length === 0 ? null : JSON.stringify(result);
    },
    'workgroup too wide: a pipeline error, not a compile error': () => {
      const result = byId.too_wide_workgroup;
      return result.error && errorsOf(result).length === 0 && result.pipeline_errors.length === 1 ? null : JSON.stringify(result);
    },
    'too many invocations refused': () => {
      const result = byId.too_many_invocations;
      return result.error?.includes('invocations') ? null : JSON.stringify(result);
    },
    'compute: output = input * 2 + 1': () => outputCheck(dir, byId.doubling, COMPUTE_COUNT, (i) => inputValue(i) * 2 + 1),
    'compute without input: output = 1': () => outputCheck(dir, byId.doubling_no_input, 100, () => 1),
    'texture: 2D array, MIP levels, linear filters, mirror-repeat': () => outputCheck(dir, byId.texture,
      4 * TEXTURE_QUERIES.length, (i) => TEXTURE_QUERIES[Math.floor(i / 4)].expected + (i % 4) / 4),
    'texture of the wrong size refused': () => {
      const result = byId.texture_short;
      return result.error?.includes('bytes') ? null : JSON.stringify(result);
    },
    'fragment: output = position.x + 1000 * position.y': () => outputCheck(dir, byId.positions, FRAGMENT_WIDTH * FRAGMENT_HEIGHT,
      (i) => ((i % FRAGMENT_WIDTH) + 0.5) + 1000 * (Math.floor(i / FRAGMENT_WIDTH) + 0.5)),
  };
}

function outputCheck(dir, result, count, expected) {
  if (result.error) return result.error;
  const values = readFloats(path.join(dir, `${result.id}.out.f32`));
  const at = firstMismatch(values, count, expected);
  return at < 0 ? null : `output[${at}] = ${values[at]}, expected ${expected(at)} (${values.length} floats)`;
}

function runnerChecks(dir, run) {
  return {
    'runner exit status 0, results for every job': () => (run.status === 0 && run.report?.results.length === checkJobs(dir).length
      ? null : `status ${run.status} ${run.signal ?? ''}: ${run.stderr}`),
    'runner stderr empty': () => (run.stderr === '' ? null : run.stderr),
    'missing DIR: exit status 1, one line on stderr': () => {
      const missing = runRunner(path.join(dir, 'missing'));
      const oneLine = /^run\.mjs: .*\n$/.test(missing.stderr);
      return missing.status === 1 && oneLine ? null : `status ${missing.status}: ${missing.stderr}`;
    },
  };
}

function report(checks) {
  let passed = 0;
  let failed = 0;
  for (const [name, check] of Object.entries(checks)) {
    let problem;
    try {
      problem = check();
    } catch (error) {
      problem = String(error?.stack ?? error);
    }
    if (problem === null) ++passed; else ++failed;
    console.log(problem === null ? `ok   ${name}` : `FAIL ${name}: ${problem}`);
  }
  return { passed, failed };
}

function selfTest() {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'saagen-webgpu-'));
  fs.writeFileSync(path.join(dir, 'jobs.json'), JSON.stringify(checkJobs(dir)));
  const run = runRunner(dir);
  run.report = run.status === 0 ? JSON.parse(fs.readFileSync(path.join(dir, 'results.json'), 'utf8')) : null;
  const byId = Object.fromEntries((run.report?.results ?? []).map((result) => [result.id, result]));
  const checks = { ...runnerChecks(dir, run), ...(run.report ? resultChecks(dir, byId) : {}) };
  const { passed, failed } = report(checks);
  if (run.report) {
    const { adapter, features } = run.report;
    console.log(`adapter: ${adapter.vendor} / ${adapter.architecture} / ${adapter.device} / ${adapter.description}`);
    console.log(`shader-f16: ${features.includes('shader-f16') ? 'offered' : 'not offered'}; runner ${run.seconds.toFixed(2)} s`);
  }
  console.log(`webgpu selftest: ${passed} passed, ${failed} failed`);
  if (failed === 0) fs.rmSync(dir, { recursive: true, force: true }); else console.log(`kept ${dir}`);
  return failed === 0 ? 0 : 1;
}

// --- the benchmark ------------------------------------------------------------------------------

// About `kb` KB of helper functions, each calling the previous one, and the call that starts
// the chain: every function stays live, as in an emitted module.
function padding(kb, seed) {
  const functions = [];
  let length = 0;
  for (let k = 0; length < kb * 1024; ++k) {
    const body = k === 0 ? 'x' : `pad_${k - 1}(x)`;
    const text = `fn pad_${k}(x: f32) -> f32 {\n  let scaled = ${body} * 1.0000001 + ${seed}.0e-30;\n` +
                 '  return max(scaled, -3.0e38);\n}\n';
    functions.push(text);
    length += text.length;
  }
  return { text: functions.join(''), call: functions.length > 0 ? `pad_${functions.length - 1}(x)` : 'x' };
}

function bench(count, padKb) {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'saagen-webgpu-bench-'));
  const invocations = 16384;
  writeFloats(path.join(dir, 'input.f32'), Array.from({ length: invocations }, (_, i) => i));
  const jobs = Array.from({ length: count }, (_, n) => {
    const pad = padding(padKb, n);
    // The job number in a comment makes every module distinct even without padding.
    return { id: `job${n}`, kind: 'compute', code: `// job ${n}\n${doublingModule(pad.text, pad.call)}`,
             input: 'input.f32', output_floats: invocations, invocations };
  });
  fs.writeFileSync(path.join(dir, 'jobs.json'), JSON.stringify(jobs));
  const run = runRunner(dir);
  if (run.status !== 0) {
    console.log(`bench: runner failed (${run.status}): ${run.stderr}`);
    return 1;
  }
  const results = JSON.parse(fs.readFileSync(path.join(dir, 'results.json'), 'utf8'));
  const failed = results.results.filter((result) => result.error);
  const moduleKb = (jobs[0].code.length / 1024).toFixed(1);
  const ownSeconds = (results.elapsed_ms / 1000).toFixed(2);
  console.log(`bench: ${count} compute jobs x ${invocations} invocations, modules of ${moduleKb} KB: ` +
              `${run.seconds.toFixed(2)} s wall (runner's own: ${ownSeconds} s), ${failed.length} failed`);
  if (failed.length > 0) console.log(`first failure: ${failed[0].error}`);
  fs.rmSync(dir, { recursive: true, force: true });
  return failed.length === 0 ? 0 : 1;
}

function main(argv) {
  const benchAt = argv.indexOf('--bench');
  if (benchAt < 0) return selfTest();
  const padAt = argv.indexOf('--pad-kb');
  return bench(Number(argv[benchAt + 1] ?? 200), padAt < 0 ? 0 : Number(argv[padAt + 1]));
}

process.exitCode = main(process.argv.slice(2));
