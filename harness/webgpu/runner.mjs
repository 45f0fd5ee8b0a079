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
// Texture formats a job's `texture` may have: bytes per texel, and how the shader samples it
// (a 32-bit float format filters only with the float32-filterable feature, which is not asked for).
const TEXTURE_FORMATS = {
  rgba16float: { bytesPerTexel: 8, sampleType: 'float' },
  rgba32float: { bytesPerTexel: 16, sampleType: 'unfilterable-float' },
  r32float: { bytesPerTexel: 4, sampleType: 'unfilterable-float' },
};
const FILTER_MODES = new Set(['nearest', 'linear']);
const ADDRESS_MODES = new Set(['clamp-to-edge', 'repeat', 'mirror-repeat']);
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

function oneOf(field, value, allowed) {
  if (!allowed.has(value)) throw new JobError(`job field texture.${field} must be one of ${[...allowed].join(', ')}`);
  return value;
}

// The job's texture description (run.mjs: "texture"), checked; null when the job has none.
function textureSpec(job) {
  const texture = job.texture;
  if (texture === undefined || texture === null) return null;
  if (typeof texture !== 'object' || Array.isArray(texture)) throw new JobError('job field texture must be an object');
  if (typeof texture.file !== 'string' || texture.file === '') throw new JobError('job field texture.file must be a file name');
  const format = oneOf('format', texture.format, new Set(Object.keys(TEXTURE_FORMATS)));
  const size = {};
  for (const field of ['width', 'height', 'layers', 'levels']) {
    const value = texture[field];
    if (!Number.isSafeInteger(value) || value < 1) throw new JobError(`job field texture.${field} must be a positive integer`);
    size[field] = value;
  }
  const fullChain = Math.floor(Math.log2(Math.max(size.width, size.height))) + 1;
  if (size.levels > fullChain) throw new JobError(`texture.levels ${size.levels} exceeds the ${fullChain} of a full MIP chain`);
  const filter = oneOf('filter', texture.filter ?? 'nearest', FILTER_MODES);
  const mipmapFilter = oneOf('mipmap_filter', texture.mipmap_filter ?? 'nearest', FILTER_MODES);
  const addressMode = oneOf('address_mode', texture.address_mode ?? 'clamp-to-edge', ADDRESS_MODES);
  const { sampleType } = TEXTURE_FORMATS[format];
  const filtering = filter === 'linear' || mipmapFilter === 'linear';
  if (filtering && sampleType !== 'float') throw new JobError(`texture format ${format} cannot be sampled with linear filters`);
  return { file: texture.file, format, ...size, filter, mipmapFilter, addressMode, sampleType, filtering };
}

// Bytes of each MIP level of `spec`: max(1, width >> m) x max(1, height >> m) texels per layer.
function levelExtents(spec) {
  const extents = [];
  for (let level = 0; level < spec.levels; ++level) {
    const width = Math.max(1, spec.width >> level);
    const height = Math.max(1, spec.height >> level);
    extents.push({ width, height, bytes: width * height * spec.layers * TEXTURE_FORMATS[spec.format].bytesPerTexel });
  }
  return extents;
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
    const texture = this.readTexture(job);
    const layout = this.layout('compute', texture?.spec);
    const compiled = await this.compiledModule(job.code, result);
    const pipeline = await this.cachedPipeline(compiled, layout.key, () => this.device.createComputePipeline({
      layout: layout.pipelineLayout, compute: { module: compiled.module, entryPoint: 'main' } }));
    const bytes = await this.execute({ input, texture, outputBytes, layout }, (encoder, bindGroup) => {
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
    const texture = this.readTexture(job);
    const layout = this.layout('fragment', texture?.spec); // first, so a device without fragment storage fails early
    const compiled = await this.compiledModule(job.code, result);
    const pipeline = await this.cachedPipeline(compiled, layout.key, () => this.device.createRenderPipeline(
      this.renderPipelineDescriptor(layout.pipelineLayout, compiled.module, 'fs')));
    const bytes = await this.execute({ input, texture, outputBytes, layout }, (encoder, bindGroup) => {
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
  // visible to the one stage that runs the job's code; with a texture, binding 2: the
  // texture_2d_array<f32> and binding 3: its sampler (`texture`: the job's textureSpec). Explicit
  // rather than "auto" so that a module that never reads its input still gets the same bind group.
  layout(stage, texture = null) {
    const key = texture ? `${stage} ${texture.sampleType}` : stage;
    if (this.layouts[key]) return this.layouts[key];
    if (stage === 'fragment' && !(this.limits.maxStorageBuffersInFragmentStage >= 2)) {
      throw new JobError(`fragment jobs need 2 storage buffers in the fragment stage; this device allows ` +
                         `maxStorageBuffersInFragmentStage = ${this.limits.maxStorageBuffersInFragmentStage}`);
    }
    const visibility = stage === 'compute' ? this.flags.ShaderStage.COMPUTE : this.flags.ShaderStage.FRAGMENT;
    const entries = [
      { binding: 0, visibility, buffer: { type: 'read-only-storage' } },
      { binding: 1, visibility, buffer: { type: 'storage' } },
    ];
    if (texture) {
      entries.push({ binding: 2, visibility, texture: { sampleType: texture.sampleType, viewDimension: '2d-array' } });
      entries.push({ binding: 3, visibility, sampler: { type: texture.sampleType === 'float' ? 'filtering' : 'non-filtering' } });
    }
    const bindGroupLayout = this.device.createBindGroupLayout({ entries });
    const pipelineLayout = this.device.createPipelineLayout({ bindGroupLayouts: [bindGroupLayout] });
    this.layouts[key] = { key, bindGroupLayout, pipelineLayout };
    return this.layouts[key];
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

  // The job's texture: its checked description and its file's bytes (raw little-endian texels of
  // the format, level after level, each level layer after layer, rows top to bottom), or null.
  readTexture(job) {
    const spec = textureSpec(job);
    if (!spec) return null;
    if (spec.width > this.limits.maxTextureDimension2D || spec.height > this.limits.maxTextureDimension2D) {
      throw new JobError(`texture ${spec.width} x ${spec.height} exceeds maxTextureDimension2D ${this.limits.maxTextureDimension2D}`);
    }
    if (spec.layers > this.limits.maxTextureArrayLayers) {
      throw new JobError(`texture.layers ${spec.layers} exceeds this device's maxTextureArrayLayers ${this.limits.maxTextureArrayLayers}`);
    }
    let bytes;
    try {
      bytes = fs.readFileSync(path.resolve(this.dir, spec.file));
    } catch (error) {
      throw new JobError(`cannot read texture ${spec.file}: ${error.code ?? messageOf(error)}`);
    }
    const extents = levelExtents(spec);
    const expected = extents.reduce((sum, extent) => sum + extent.bytes, 0);
    if (bytes.length !== expected) {
      throw new JobError(`texture ${spec.file} is ${bytes.length} bytes; ${spec.levels} levels of ${spec.width} x ${spec.height} x ` +
                         `${spec.layers} ${spec.format} take ${expected}`);
    }
    return { spec, extents, bytes };
  }

  // The texture's view and sampler for bindings 2 and 3, uploaded level by level; the texture
  // is destroyed by the caller once the job's commands have run.
  textureBinding(texture) {
    const { spec, extents, bytes } = texture;
    const handle = this.device.createTexture({
      size: [spec.width, spec.height, spec.layers], format: spec.format, mipLevelCount: spec.levels,
      usage: this.flags.TextureUsage.TEXTURE_BINDING | this.flags.TextureUsage.COPY_DST });
    let offset = 0;
    extents.forEach((extent, level) => {
      const rowBytes = extent.width * TEXTURE_FORMATS[spec.format].bytesPerTexel;
      this.device.queue.writeTexture({ texture: handle, mipLevel: level }, bytes.subarray(offset, offset + extent.bytes),
                                     { bytesPerRow: rowBytes, rowsPerImage: extent.height }, [extent.width, extent.height, spec.layers]);
      offset += extent.bytes;
    });
    const sampler = this.device.createSampler({
      magFilter: spec.filter, minFilter: spec.filter, mipmapFilter: spec.mipmapFilter,
      addressModeU: spec.addressMode, addressModeV: spec.addressMode, addressModeW: spec.addressMode });
    return { handle, view: handle.createView({ dimension: '2d-array' }), sampler };
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

  // Binds input, a cleared output and the job's texture, lets `encode` record the pass, copies
  // the output to a mappable buffer and returns its bytes. Every binding is sized exactly, so
  // arrayLength() in the shader sees the job's sizes rather than the pooled buffers'.
  async execute({ input, texture, outputBytes, layout }, encode) {
    let uploaded = null;
    let scoped;
    try {
      scoped = await withErrorScopes(this.device, async () => {
        const usage = this.flags.BufferUsage;
        const source = this.inputBinding(input);
        const output = this.buffer('output', outputBytes, usage.STORAGE | usage.COPY_SRC | usage.COPY_DST);
        const readback = this.buffer('readback', outputBytes, usage.MAP_READ | usage.COPY_DST);
        const entries = [
          { binding: 0, resource: { buffer: source.buffer, size: source.size } },
          { binding: 1, resource: { buffer: output, size: outputBytes } },
        ];
        if (texture) {
          uploaded = this.textureBinding(texture);
          entries.push({ binding: 2, resource: uploaded.view }, { binding: 3, resource: uploaded.sampler });
        }
        const bindGroup = this.device.createBindGroup({ layout: layout.bindGroupLayout, entries });
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
    } finally {
      uploaded?.handle.destroy();
    }
    if (scoped.errors.length > 0) throw new JobError(scoped.errors.join('\n'));
    return scoped.value;
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
