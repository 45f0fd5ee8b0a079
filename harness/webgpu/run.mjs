#!/usr/bin/env node
// saagen's WebGPU job runner: compiles WGSL modules with Tint and runs them on Dawn for Node (npm
// package `webgpu`) over SwiftShader's Vulkan ICD (device.mjs says how the driver is chosen).
// Used by the C++ test suite and by `saagen validate --target wgsl`.
//
//   node harness/webgpu/run.mjs DIR
//
// reads DIR/jobs.json, runs its jobs in order on one device, and writes DIR/results.json plus
// one DIR/<id>.out.f32 per compute or fragment job that succeeded. Exit status 0 whenever the
// runner itself worked, however many jobs failed; otherwise (no adapter, DIR not a directory,
// jobs.json unreadable or not an array, results.json unwritable) exit status 1 and one line on
// stderr. Nothing bounds a job's time (a shader that never ends hangs the runner): the caller
// puts its own time limit on the process. stdout is not part of the protocol: it ends with the
// runner's one-line summary, and Dawn prints its shader compilation logs (warnings) there too.
//
// jobs.json: an array of jobs. Fields of every job:
//   id     string matching [A-Za-z0-9_][A-Za-z0-9_.-]* (at most 200 characters), unique in the run
//   kind   "compile" | "compute" | "fragment"
//   code   the WGSL module's text
// kind "compile": createShaderModule + getCompilationInfo; then, if the module compiled, one
//   pipeline per entry of
//   entry_points  optional array of { stage: "compute" | "fragment", name }
//   with layout "auto" (a fragment entry gets the runner's vertex stage `vs` and one rgba8unorm
//   color target), each inside error scopes, so that what only pipeline creation checks (stage
//   restrictions, workgroup-size and resource limits, entry-point names) is reported.
// kind "compute": the module declares
//     @compute @workgroup_size(64) fn main(@builtin(global_invocation_id) id: vec3<u32>)
//     @group(0) @binding(0) var<storage, read> saagen_input: array<f32>;
//     @group(0) @binding(1) var<storage, read_write> saagen_output: array<f32>;
//   invocations    positive integer; ceil(invocations / 64) workgroups are dispatched along x
//                  only (id.y = id.z = 0), so at most 65535 * 64 = 4194240; the shader bounds
//                  its own index (the last workgroup may run past `invocations`)
//   output_floats  positive integer: the size of saagen_output, zeroed before the dispatch
//   input          optional file name, relative to DIR, of raw little-endian f32 bound as
//                  saagen_input; absent or empty binds 16 zero bytes (arrayLength = 4)
//   texture        optional: a 2D array texture with its MIP levels, which the module declares as
//                    @group(0) @binding(2) var <name>: texture_2d_array<f32>;
//                    @group(0) @binding(3) var <name>: sampler;
//                  (the glint dictionary's declaration in targets/wgsl.json), an object of
//     file           file name, relative to DIR: raw little-endian texels of `format`, level
//                    after level, each level layer after layer, each layer row after row; level
//                    m is max(1, width >> m) x max(1, height >> m) texels
//     format         "rgba16float" (filterable) | "rgba32float" | "r32float" (nearest filters only)
//     width, height, layers, levels   positive integers (levels at most a full MIP chain;
//                    layers at most the device's maxTextureArrayLayers, raised to the adapter's)
//     filter         "nearest" | "linear": the sampler's mag and min filters (default nearest)
//     mipmap_filter  "nearest" | "linear" (default nearest)
//     address_mode   "clamp-to-edge" | "repeat" | "mirror-repeat", on u, v and w (default
//                    clamp-to-edge)
// kind "fragment": the module declares
//     @fragment fn fs(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32>
//   (further inputs only if the runner's vertex stage, which outputs just the position, feeds
//   them: it does not) and the same two bindings, visible to the fragment stage (the device
//   must allow 2 storage buffers there, maxStorageBuffersInFragmentStage). Fields:
//   width, height  positive integers: the rgba8unorm target of the one full-screen triangle
//                  (position.xy at pixel centres: x + 0.5, y + 0.5, y down)
//   output_floats, input, texture  as for "compute"
//   Every pixel runs fs once; the color written is discarded. Helper invocations (derivatives)
//   write no storage.
// Both "compute" and "fragment" write DIR/<id>.out.f32 (output_floats raw little-endian f32)
// when the job succeeded, and remove a stale one when it did not.
//
// results.json:
//   { adapter: { vendor, architecture, device, description },
//     features: [string],          // the device's features; "shader-f16" when the adapter offers it
//     limits_used: { maxStorageBuffersInFragmentStage, maxComputeWorkgroupsPerDimension,
//                    maxComputeInvocationsPerWorkgroup, maxStorageBufferBindingSize,
//                    maxBufferSize, maxTextureDimension2D, maxTextureArrayLayers },
//     elapsed_ms: number,           // the whole run, device creation included
//     results: [ one per job, in order:
//       { id,                       // the job's id (null when it had no string id)
//         messages: [ { type: "error" | "warning" | "info", message, line, column } ],
//                                   // Tint's, line and column 1-based, 0 when without position
//         pipeline_errors: [string],// "compile" jobs only: "<stage> <name>: <Dawn's message>"
//         error: string,            // present only when the job failed: a field was wrong, the
//                                   // module did not compile, a pipeline was refused, a WebGPU
//                                   // call failed, an error escaped the scopes, the device was lost
//         ms: number } ] }          // the job's time
// A job that failed never stops the ones after it; a lost device is opened anew for them (if
// that fails, the runner exits with status 1 and writes no results.json).
import fs from 'node:fs';
import path from 'node:path';
import { openDevice } from './device.mjs';
import { JobRunner } from './runner.mjs';

class UsageError extends Error {}

function readJobs(dir) {
  if (!dir) throw new UsageError('usage: node harness/webgpu/run.mjs DIR (DIR holds jobs.json)');
  if (!fs.statSync(dir, { throwIfNoEntry: false })?.isDirectory()) throw new UsageError(`${dir} is not a directory`);
  const file = path.join(dir, 'jobs.json');
  let jobs;
  try {
    jobs = JSON.parse(fs.readFileSync(file, 'utf8'));
  } catch (error) {
    throw new UsageError(`cannot read ${file}: ${error.code ?? error.message}`);
  }
  if (!Array.isArray(jobs)) throw new UsageError(`${file} is not an array of jobs`);
  return jobs;
}

function header(session) {
  return { adapter: session.adapterInfo, features: session.features, limits_used: session.limits };
}

// A second job with an id already seen would overwrite the first one's output file.
function duplicateResult(job) {
  return { id: job.id, messages: [], error: `duplicate job id ${job.id}`, ms: 0 };
}

// Runs every job; a lost device is replaced so that the jobs after the one that lost it still
// run. Returns the results and the session open at the end (for the caller to close).
async function runJobs(session, dir, jobs) {
  let runner = new JobRunner(session, dir);
  const seen = new Set();
  const results = [];
  for (const job of jobs) {
    if (typeof job?.id === 'string' && seen.has(job.id)) {
      results.push(duplicateResult(job));
      continue;
    }
    seen.add(job?.id);
    results.push(await runner.run(job));
    if (session.lostInfo()) {
      session.close();
      session = await openDevice();
      runner = new JobRunner(session, dir);
    }
  }
  return { results, session };
}

// Written whole under a temporary name and renamed, so a reader never sees half a file.
function writeResults(dir, report) {
  const file = path.join(dir, 'results.json');
  const partial = `${file}.partial`;
  fs.writeFileSync(partial, `${JSON.stringify(report, null, 1)}\n`);
  fs.renameSync(partial, file);
}

function summary(results, elapsedMs) {
  const failed = results.filter((result) => result.error !== undefined).length;
  return `webgpu run: ${results.length} jobs, ${failed} failed, ${(elapsedMs / 1000).toFixed(2)} s`;
}

async function main(argv) {
  const started = performance.now();
  const dir = argv[0];
  const jobs = readJobs(dir);
  let session = await openDevice();
  try {
    const report = header(session);
    const run = await runJobs(session, dir, jobs);
    session = run.session;
    report.elapsed_ms = Math.round(performance.now() - started);
    report.results = run.results;
    writeResults(dir, report);
    console.log(summary(run.results, report.elapsed_ms));
  } finally {
    session.close();
  }
}

// process.exit() rather than a natural end: device.mjs keeps Dawn's instances alive until then.
main(process.argv.slice(2)).then(() => process.exit(0), (error) => {
  const message = String(error?.message ?? error).split('\n')[0];
  process.stderr.write(`run.mjs: ${message}\n`);
  process.exit(1);
});
