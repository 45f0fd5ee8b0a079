// The GPU side of the WebGPU job runner: one JobRunner per device runs the jobs of jobs.json one
// at a time (the protocol is described in run.mjs, which owns the command line and the files).
//
// Usage:
//   const runner = new JobRunner(session, dir);   // session from device.mjs's openDevice()
//   const result = await runner.run(job);         // never throws; failures land in result.error
//
// Everything a job asks of the device runs inside validation / out-of-memory / internal error
// scopes, so its errors are reported as that job's and nothing reaches Dawn's uncaptured-error
// path (which also prints to the console). Buffers, the render target, bind group layouts and
// recently compiled modules with their pipelines are kept between jobs: hundreds of jobs reuse a
// handful of allocations, and a module that several jobs share is compiled once.
import fs from 'node:fs';
import path from 'node:path';

export const WORKGROUP_SIZE = 64;
const TARGET_FORMAT = 'rgba8unorm';
// Bound in place of a missing input, so the module's binding 0 always has a buffer behind it.
const ZERO_INPUT_BYTES = 16;
const MODULE_CACHE_SIZE = 8;
const ERROR_SCOPES = ['validation', 'out-of-memory', 'internal'];
const JOB_KINDS = new Set(['compile', 'compute', 'fragment']);
const ENTRY_STAGES = new Set(['compute', 'fragment']);
// File-name safe: no separators, no leading dot (no hidden files, no "..").
const ID_PATTERN = /^[A-Za-z0-9_][A-Za-z0-9_.-]{0,199}$/;

// The runner's own vertex stage: one triangle that covers the whole target, corners from the
// vertex index alone ((-1,-1), (3,-1), (-1,3) in clip space), so no vertex buffers are needed.
export const VERTEX_WGSL = `
@vertex
fn vs(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
  let corner = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
  return vec4<f32>(corner * 2.0 - 1.0, 0.0, 1.0);
}
`;

// A failure that is the job's (bad field, compile error, pipeline error): reported as it is.
class JobError extends Error {}

function messageOf(error) {
  return String(error?.message ?? error).trim();
}

// Runs `work` inside one error scope of each kind and returns its value together with the
// messages of the errors the scopes caught. Scopes are popped even when `work` throws, so the
// device's scope stack is balanced for the next job.
async function withErrorScopes(device, work) {
  for (const filter of ERROR_SCOPES) device.pushErrorScope(filter);
  let value;
  let thrown = null;
  try {
    value = await work();
  } catch (error) {
    thrown = error;
  }
  const errors = [];
  for (let i = 0; i < ERROR_SCOPES.length; ++i) {
    const error = await device.popErrorScope().catch((failure) => failure);
    if (error) errors.push(messageOf(error));
  }
  if (thrown) throw thrown;
  return { value, errors };
}

function positiveInteger(job, field) {
  const value = job[field];
  if (!Number.isSafeInteger(value) || value < 1) throw new JobError(`job field ${field} must be a positive integer`);
  return value;
}

// GPUCompilationMessage → the protocol's { type, message, line, column } (1-based; 0 = no position).
function toMessage(message) {
  return { type: message.type, message: message.message, line: message.lineNum, column: message.linePos };
}

function compileFailure(messages) {
  const errors = messages.filter((message) => message.type === 'error');
  if (errors.length === 0) return null;
  const first = errors[0];
  const more = errors.length > 1 ? ` (and ${errors.length - 1} more)` : '';
  return `WGSL compilation failed at ${first.line}:${first.column}: ${first.message}${more}`;
}

function checkEntryPoints(entryPoints) {
  if (entryPoints === undefined) return [];
  const valid = Array.isArray(entryPoints) && entryPoints.every(
    (entry) => ENTRY_STAGES.has(entry?.stage) && typeof entry.name === 'string' && entry.name !== '');
  if (!valid) throw new JobError('job field entry_points must be an array of { stage: "compute"|"fragment", name }');
  return entryPoints;
}

function checkJob(job) {
  if (job === null || typeof job !== 'object' || Array.isArray(job)) throw new JobError('a job must be an object');
  if (typeof job.id !== 'string' || !ID_PATTERN.test(job.id)) {
    throw new JobError('job field id must be a file-name safe string ([A-Za-z0-9_.-], not starting with a dot)');
  }
  if (!JOB_KINDS.has(job.kind)) throw new JobError('job field kind must be "compile", "compute" or "fragment"');
  if (typeof job.code !== 'string' || job.code === '') throw new JobError('job field code must be a non-empty WGSL string');
}

export class JobRunner {
  constructor(session, dir) {
    this.session = session;
    this.device = session.device;
    this.limits = session.limits;
    this.flags = session.flags;
    this.dir = dir;
    this.modules = new Map(); // code → { module, messages, error, pipelines }
    this.buffers = {};        // role → GPUBuffer, grown as jobs need
    this.target = null;       // { width, height, texture, view }
    this.layouts = {};        // stage → { bindGroupLayout, pipelineLayout }
    this.vertexModule = null;
  }

  // Runs one job; the result is { id, messages, pipeline_errors?, error?, ms }.
  async run(job) {
    const started = performance.now();
    const result = { id: typeof job?.id === 'string' ? job.id : null, messages: [] };
    try {
      checkJob(job);
      this.clearOutput(job.id);
      await this[job.kind](job, result);
    } catch (error) {
      result.error = messageOf(error);
    }
    this.noteDeviceTrouble(result);
    if (result.error !== undefined && result.id !== null && ID_PATTERN.test(result.id)) this.clearOutput(result.id);
    result.ms = Math.round((performance.now() - started) * 10) / 10;
    return result;
  }

  // Errors that escaped every scope, or a lost device, spoil the job that was running.
  noteDeviceTrouble(result) {
    const problems = this.session.takeUncapturedErrors().map((message) => `uncaptured error: ${message}`);
    const lost = this.session.lostInfo();
    if (lost) problems.push(`device lost (${lost.reason}): ${lost.message}`);
    if (problems.length === 0) return;
    result.error = [result.error, ...problems].filter(Boolean).join('\n');
  }

  // --- job kinds -------------------------------------------------------------------------------

  async compile(job, result) {
    const entryPoints = checkEntryPoints(job.entry_points);
    result.pipeline_errors = [];
    const compiled = await this.compiledModule(job.code, result);
    for (const entry of entryPoints) {
      const errors = await this.tryAutoPipeline(compiled.module, entry);
      result.pipeline_errors.push(...errors.map((message) => `${entry.stage} ${entry.name}: ${message}`));
    }
    if (result.pipeline_errors.length > 0) {
      throw new JobError(`pipeline creation failed: ${result.pipeline_errors[0]}`);
    }
  }

  async compute(job, result) {
    const invocations = positiveInteger(job, 'invocations');
    const outputBytes = this.outputBytes(job);
    const groups = Math.ceil(invocations / WORKGROUP_SIZE);
    const maxGroups = this.limits.maxComputeWorkgroupsPerDimension;
    if (groups > maxGroups) {
      throw new JobError(`invocations ${invocations} exceeds ${maxGroups * WORKGROUP_SIZE}: ` +
                         `the runner dispatches one row of ${WORKGROUP_SIZE}-wide workgroups along x`);
    }
    const input = this.readInput(job);
    const compiled = await this.compiledModule(job.code, result);
    const pipeline = await this.cachedPipeline(compiled, 'compute', () => this.device.createComputePipeline({
      layout: this.layout('compute').pipelineLayout, compute: { module: compiled.module, entryPoint: 'main' } }));
    const bytes = await this.execute(input, outputBytes, 'compute', (encoder, bindGroup) => {
      const pass = encoder.beginComputePass();
      pass.setPipeline(pipeline);
      pass.setBindGroup(0, bindGroup);
      pass.dispatchWorkgroups(groups);
      pass.end();
    });
    this.writeOutput(job.id, bytes);
  }

  async fragment(job, result) {
    const width = this.textureSide(job, 'width');
    const height = this.textureSide(job, 'height');
    const outputBytes = this.outputBytes(job);
    const input = this.readInput(job);
    const layout = this.layout('fragment'); // first, so a device without fragment storage fails early
    const compiled = await this.compiledModule(job.code, result);
    const pipeline = await this.cachedPipeline(compiled, 'fragment', () => this.device.createRenderPipeline(
      this.renderPipelineDescriptor(layout.pipelineLayout, compiled.module, 'fs')));
    const bytes = await this.execute(input, outputBytes, 'fragment', (encoder, bindGroup) => {
      const view = this.renderTarget(width, height); // here, inside execute's error scopes
      const pass = encoder.beginRenderPass({
        colorAttachments: [{ view, loadOp: 'clear', clearValue: [0, 0, 0, 0], storeOp: 'store' }] });
      pass.setPipeline(pipeline);
      pass.setBindGroup(0, bindGroup);
      pass.draw(3);
      pass.end();
    });
    this.writeOutput(job.id, bytes);
  }

  // --- modules and pipelines ---------------------------------------------------------------------

  // The module for `code`, compiled once while it stays among the recent ones. Fills
  // result.messages, and throws when the module did not compile.
  async compiledModule(code, result) {
    let compiled = this.modules.get(code);
    if (!compiled) {
      compiled = await this.compileModule(code);
      if (this.modules.size >= MODULE_CACHE_SIZE) this.modules.delete(this.modules.keys().next().value);
      this.modules.set(code, compiled);
    }
    result.messages = compiled.messages;
    if (compiled.error) throw new JobError(compiled.error);
    return compiled;
  }

  async compileModule(code) {
    const { value: module, errors } = await withErrorScopes(this.device, async () => this.device.createShaderModule({ code }));
    const messages = (await module.getCompilationInfo()).messages.map(toMessage);
    // The scope repeats a compile error that the messages already carry; it is shown alone
    // only when the messages say nothing (a failure outside the WGSL front end).
    const error = compileFailure(messages) ?? (errors.length > 0 ? `shader module creation failed: ${errors.join('\n')}` : null);
    return { module, messages, error, pipelines: new Map() };
  }

  async cachedPipeline(compiled, key, create) {
    const cached = compiled.pipelines.get(key);
    if (cached) return cached;
    const { value: pipeline, errors } = await withErrorScopes(this.device, async () => create());
    if (errors.length > 0) throw new JobError(`pipeline creation failed: ${errors.join('\n')}`);
    compiled.pipelines.set(key, pipeline);
    return pipeline;
  }

  // A compile job's pipeline for one entry point, with layout "auto": only its errors matter
  // (stage restrictions, resource limits, missing entry points), so nothing is kept.
  async tryAutoPipeline(module, entry) {
    const create = entry.stage === 'compute'
      ? () => this.device.createComputePipeline({ layout: 'auto', compute: { module, entryPoint: entry.name } })
      : () => this.device.createRenderPipeline(this.renderPipelineDescriptor('auto', module, entry.name));
    const { errors } = await withErrorScopes(this.device, async () => create());
    return errors;
  }

  renderPipelineDescriptor(layout, module, entryPoint) {
    this.vertexModule ??= this.device.createShaderModule({ code: VERTEX_WGSL });
    return {
      layout,
      vertex: { module: this.vertexModule, entryPoint: 'vs' },
      fragment: { module, entryPoint, targets: [{ format: TARGET_FORMAT }] },
      primitive: { topology: 'triangle-list' },
    };
  }

  // Binding 0: saagen_input (read-only storage), binding 1: saagen_output (read-write storage),
  // visible to the one stage that runs the job's code. Explicit rather than "auto" so that a
  // module that never reads its input still gets the same bind group.
  layout(stage) {
    if (this.layouts[stage]) return this.layouts[stage];
    if (stage === 'fragment' && !(this.limits.maxStorageBuffersInFragmentStage >= 2)) {
      throw new JobError(`fragment jobs need 2 storage buffers in the fragment stage; this device allows ` +
                         `maxStorageBuffersInFragmentStage = ${this.limits.maxStorageBuffersInFragmentStage}`);
    }
    const visibility = stage === 'compute' ? this.flags.ShaderStage.COMPUTE : this.flags.ShaderStage.FRAGMENT;
    const bindGroupLayout = this.device.createBindGroupLayout({ entries: [
      { binding: 0, visibility, buffer: { type: 'read-only-storage' } },
      { binding: 1, visibility, buffer: { type: 'storage' } },
    ] });
    const pipelineLayout = this.device.createPipelineLayout({ bindGroupLayouts: [bindGroupLayout] });
    this.layouts[stage] = { bindGroupLayout, pipelineLayout };
    return this.layouts[stage];
  }

  // --- buffers, target, files --------------------------------------------------------------------

  outputBytes(job) {
    const bytes = positiveInteger(job, 'output_floats') * 4;
    this.checkBindingSize(bytes, `output_floats ${job.output_floats}`);
    return bytes;
  }

  checkBindingSize(bytes, what) {
    const limit = this.limits.maxStorageBufferBindingSize;
    if (bytes > limit) throw new JobError(`${what} exceeds the storage binding limit of ${limit} bytes`);
  }

  textureSide(job, field) {
    const side = positiveInteger(job, field);
    if (side > this.limits.maxTextureDimension2D) {
      throw new JobError(`${field} ${side} exceeds maxTextureDimension2D ${this.limits.maxTextureDimension2D}`);
    }
    return side;
  }

  // The job's input file (raw little-endian f32), or null when it names none or an empty one.
  readInput(job) {
    if (job.input === undefined || job.input === null) return null;
    if (typeof job.input !== 'string' || job.input === '') throw new JobError('job field input must be a file name');
    let bytes;
    try {
      bytes = fs.readFileSync(path.resolve(this.dir, job.input));
    } catch (error) {
      throw new JobError(`cannot read input ${job.input}: ${error.code ?? messageOf(error)}`);
    }
    if (bytes.length % 4 !== 0) throw new JobError(`input ${job.input} is ${bytes.length} bytes, not a whole number of f32`);
    this.checkBindingSize(bytes.length, `input ${job.input}`);
    return bytes.length === 0 ? null : bytes;
  }

  // A buffer for `role` of at least `bytes`, reused while large enough; grown by doubling so a
  // run whose sizes creep up reallocates only a few times.
  buffer(role, bytes, usage) {
    const current = this.buffers[role];
    if (current && current.size >= bytes) return current;
    const size = Math.max(256, bytes, current ? current.size * 2 : 0);
    current?.destroy();
    this.buffers[role] = this.device.createBuffer({ size: Math.ceil(size / 4) * 4, usage });
    return this.buffers[role];
  }

  inputBinding(input) {
    const usage = this.flags.BufferUsage;
    if (input === null) {
      this.zeroInput ??= this.device.createBuffer({ size: ZERO_INPUT_BYTES, usage: usage.STORAGE });
      return { buffer: this.zeroInput, size: ZERO_INPUT_BYTES };
    }
    const buffer = this.buffer('input', input.length, usage.STORAGE | usage.COPY_DST);
    this.device.queue.writeBuffer(buffer, 0, input);
    return { buffer, size: input.length };
  }

  renderTarget(width, height) {
    if (this.target?.width === width && this.target?.height === height) return this.target.view;
    this.target?.texture.destroy();
    const texture = this.device.createTexture({
      size: [width, height], format: TARGET_FORMAT, usage: this.flags.TextureUsage.RENDER_ATTACHMENT });
    this.target = { width, height, texture, view: texture.createView() };
    return this.target.view;
  }

  // Binds input and a cleared output, lets `encode` record the pass, copies the output to a
  // mappable buffer and returns its bytes. Every binding is sized exactly, so arrayLength() in
  // the shader sees the job's sizes rather than the pooled buffers'.
  async execute(input, outputBytes, stage, encode) {
    const { value: bytes, errors } = await withErrorScopes(this.device, async () => {
      const usage = this.flags.BufferUsage;
      const source = this.inputBinding(input);
      const output = this.buffer('output', outputBytes, usage.STORAGE | usage.COPY_SRC | usage.COPY_DST);
      const readback = this.buffer('readback', outputBytes, usage.MAP_READ | usage.COPY_DST);
      const bindGroup = this.device.createBindGroup({ layout: this.layout(stage).bindGroupLayout, entries: [
        { binding: 0, resource: { buffer: source.buffer, size: source.size } },
        { binding: 1, resource: { buffer: output, size: outputBytes } },
      ] });
      const encoder = this.device.createCommandEncoder();
      encoder.clearBuffer(output, 0, outputBytes);
      encode(encoder, bindGroup);
      encoder.copyBufferToBuffer(output, 0, readback, 0, outputBytes);
      this.device.queue.submit([encoder.finish()]);
      await readback.mapAsync(this.flags.MapMode.READ, 0, outputBytes);
      const copy = new Uint8Array(readback.getMappedRange(0, outputBytes)).slice();
      readback.unmap();
      return copy;
    });
    if (errors.length > 0) throw new JobError(errors.join('\n'));
    return bytes;
  }

  outputPath(id) {
    return path.join(this.dir, `${id}.out.f32`);
  }

  // Removes a previous run's output first, so a failed job never leaves a stale file behind.
  clearOutput(id) {
    fs.rmSync(this.outputPath(id), { force: true });
  }

  writeOutput(id, bytes) {
    fs.writeFileSync(this.outputPath(id), bytes);
  }
}
