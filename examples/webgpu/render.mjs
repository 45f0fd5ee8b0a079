// A WebGPU consumer of a saagen WGSL bundle (Node.js, the npm package `webgpu`: Dawn with Tint).
// It renders a grid of small glossy beads -- anisotropic GGX, alpha = (0.05, 0.1) -- at one sample
// per pixel without and with the bundle's filter, and a 16-sample supersampled image of the
// unfiltered shading as the ground truth, then reports the tonemapped RMSE of each against it.
//
//   saagen emit --manifest examples/webgpu/scene.saagen.toml -o out/webgpu
//   node examples/webgpu/render.mjs out/webgpu/saa_webgpu.wgsl out/webgpu
//
// On a machine without a GPU, point the Vulkan loader at SwiftShader (Debian's chromium ships it):
//   VK_ICD_FILENAMES=/usr/lib/chromium/vk_swiftshader_icd.json node examples/webgpu/render.mjs ...
//
// How the bundle is used, as any WebGPU engine would: WGSL has no includes, so the shader module
// is the bundle's text followed by this file's code (the bundle defines each function once, all
// prefixed saa_). The [fragment] wrapper takes dpdx/dpdy, so it is called from the fragment entry
// point in uniform control flow -- before any branch on a per-pixel value -- and its result is
// used or discarded afterwards with select().
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';
import { pathToFileURL } from 'node:url';

export const WIDTH = 256;
export const HEIGHT = 256;

// The example's own WGSL: an orthographic view of beads of radius 5.5 px on a 16 px grid, each with
// its analytic normal and a tangent frame, lit by one directional light.
const sceneCode = /* wgsl */ `
const LIGHT_RADIANCE: f32 = 4.0;
const ALPHA2: vec2<f32> = vec2<f32>(0.0025, 0.01);

struct Surface {
    hit: bool,
    n: vec3<f32>,
    t: vec3<f32>,
    b: vec3<f32>,
};

fn bead_at(p: vec2<f32>) -> Surface {
    let cell = p - (floor(p / 16.0) * 16.0 + vec2<f32>(8.0, 8.0));
    let q = cell / 5.5;
    let r2 = dot(q, q);
    // Outside the bead the field continues radially, so that every 2x2 quad sees a smooth field.
    let qc = q * min(1.0, sqrt(0.95 / max(r2, 1e-8)));
    let n = normalize(vec3<f32>(qc.x, -qc.y, sqrt(max(1.0 - dot(qc, qc), 0.0))));
    let t = normalize(vec3<f32>(n.z, 0.0, -n.x));
    return Surface(r2 < 1.0, n, t, cross(n, t));
}

fn to_tangent(v: vec3<f32>, s: Surface) -> vec3<f32> {
    return vec3<f32>(dot(v, s.t), dot(v, s.b), dot(v, s.n));
}

fn radiance(s: Surface, a: vec3<f32>) -> f32 {
    let light = normalize(vec3<f32>(0.35, 0.45, 0.82));
    let i = to_tangent(light, s);
    let o = to_tangent(vec3<f32>(0.0, 0.0, 1.0), s);
    let brdf = saa_ggx_brdf_filtered_matrix(i, o, a, ALPHA2);
    return select(0.0, LIGHT_RADIANCE * brdf * max(i.z, 0.0), s.hit);
}

// The light's half vector in world space (the view is along +z).
fn half_vector() -> vec3<f32> {
    let light = normalize(vec3<f32>(0.35, 0.45, 0.82));
    return normalize(light + vec3<f32>(0.0, 0.0, 1.0));
}

struct Out {
    @location(0) value: vec4<f32>,
};

// One sample per pixel; filtered when MODE is 1.
override MODE: u32 = 0u;

@fragment
fn shade(@builtin(position) position: vec4<f32>) -> Out {
    let s = bead_at(position.xy);
    // Uniform control flow: the wrapper (dpdx/dpdy inside) runs for every pixel of the quad.
    // The half vector in world space with the frame it is filtered in (the transported wrapper, as
    // saagen plans it: the frame's turn about the normal between pixels is not read as curvature).
    let filtered = saa_forward_aniso_projected_transported_fragment(ALPHA2, half_vector(), s.n, s.t, s.b);
    let unfiltered = vec3<f32>(ALPHA2.x, 0.0, ALPHA2.y);
    let a = select(unfiltered, filtered, MODE == 1u);
    return Out(vec4<f32>(radiance(s, a), 0.0, 0.0, 1.0));
}

// The ground truth: the unfiltered shading averaged over a 4 x 4 grid of sub-pixel samples.
@fragment
fn reference(@builtin(position) position: vec4<f32>) -> Out {
    var sum: f32 = 0.0;
    for (var k: i32 = 0; k < 16; k++) {
        let offset = (vec2<f32>(f32(k % 4), f32(k / 4)) + 0.5) / 4.0 - 0.5;
        sum += radiance(bead_at(position.xy + offset), vec3<f32>(ALPHA2.x, 0.0, ALPHA2.y));
    }
    return Out(vec4<f32>(sum / 16.0, 0.0, 0.0, 1.0));
}

@vertex
fn full_screen(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    let p = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(p * 2.0 - 1.0, 0.0, 1.0);
}
`;

export async function openDevice() {
  const { create, globals } = await import('webgpu');
  Object.assign(globalThis, globals);
  const gpu = create([]);
  const adapter = await gpu.requestAdapter();
  if (!adapter) throw new Error('no WebGPU adapter (on a machine without a GPU set VK_ICD_FILENAMES to SwiftShader\'s ICD)');
  const device = await adapter.requestDevice();
  return { gpu, device };
}

// Compiles the bundle + the scene into one module; throws with Tint's messages on any error or warning.
export async function compileModule(device, bundleText) {
  const code = `${bundleText}\n${sceneCode}`;
  const module = device.createShaderModule({ code });
  const info = await module.getCompilationInfo();
  const problems = info.messages.filter((message) => message.type !== 'info');
  if (problems.length > 0) {
    throw new Error(problems.map((m) => `${m.type} at module line ${m.lineNum}:${m.linePos}: ${m.message}`).join('\n'));
  }
  return module;
}

// Renders one entry point into an r32float target and reads it back.
export async function render(device, module, entryPoint, constants = {}) {
  const format = 'r32float';
  const pipeline = device.createRenderPipeline({
    layout: 'auto',
    vertex: { module, entryPoint: 'full_screen' },
    fragment: { module, entryPoint, targets: [{ format }], constants },
    primitive: { topology: 'triangle-list' },
  });
  const texture = device.createTexture({ size: [WIDTH, HEIGHT], format, usage: GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.COPY_SRC });
  const bytesPerRow = WIDTH * 4;
  const readback = device.createBuffer({ size: bytesPerRow * HEIGHT, usage: GPUBufferUsage.COPY_DST | GPUBufferUsage.MAP_READ });
  const encoder = device.createCommandEncoder();
  const pass = encoder.beginRenderPass({
    colorAttachments: [{ view: texture.createView(), loadOp: 'clear', storeOp: 'store', clearValue: [0, 0, 0, 0] }],
  });
  pass.setPipeline(pipeline);
  pass.draw(3);
  pass.end();
  encoder.copyTextureToBuffer({ texture }, { buffer: readback, bytesPerRow }, [WIDTH, HEIGHT]);
  device.queue.submit([encoder.finish()]);
  await readback.mapAsync(GPUMapMode.READ);
  const pixels = new Float32Array(readback.getMappedRange().slice(0));
  readback.unmap();
  texture.destroy();
  readback.destroy();
  return pixels;
}

const tonemap = (x) => x / (1 + x); // Reinhard: display-referred values in [0, 1)

export function tonemappedRmse(image, truth) {
  let sum = 0;
  for (let k = 0; k < image.length; ++k) sum += (tonemap(image[k]) - tonemap(truth[k])) ** 2;
  return Math.sqrt(sum / image.length);
}

// An 8-bit greyscale PNG of the tonemapped image (zlib from Node; one filter byte per row).
export function writePng(file, image) {
  const raw = Buffer.alloc((WIDTH + 1) * HEIGHT);
  for (let y = 0; y < HEIGHT; ++y) {
    for (let x = 0; x < WIDTH; ++x) raw[y * (WIDTH + 1) + 1 + x] = Math.round(255 * Math.pow(tonemap(image[y * WIDTH + x]), 1 / 2.2));
  }
  const chunk = (type, data) => {
    const length = Buffer.alloc(4);
    length.writeUInt32BE(data.length);
    const body = Buffer.concat([Buffer.from(type, 'ascii'), data]);
    const crc = Buffer.alloc(4);
    crc.writeUInt32BE(zlib.crc32(body));
    return Buffer.concat([length, body, crc]);
  };
  const header = Buffer.alloc(13);
  header.writeUInt32BE(WIDTH, 0);
  header.writeUInt32BE(HEIGHT, 4);
  header.set([8, 0, 0, 0, 0], 8); // 8-bit greyscale, no interlace
  const signature = Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);
  fs.writeFileSync(file, Buffer.concat([signature, chunk('IHDR', header), chunk('IDAT', zlib.deflateSync(raw)), chunk('IEND', Buffer.alloc(0))]));
}

// Renders the three images; returns them with the RMSE figures.
export async function run(bundleText) {
  const { gpu, device } = await openDevice();
  try {
    const module = await compileModule(device, bundleText);
    const unfiltered = await render(device, module, 'shade', { MODE: 0 });
    const filtered = await render(device, module, 'shade', { MODE: 1 });
    const truth = await render(device, module, 'reference');
    return {
      unfiltered,
      filtered,
      truth,
      rmse: { unfiltered: tonemappedRmse(unfiltered, truth), filtered: tonemappedRmse(filtered, truth) },
    };
  } finally {
    device.destroy();
    void gpu;
  }
}

if (import.meta.url === pathToFileURL(process.argv[1]).href) {
  const [bundle, outputDirectory] = process.argv.slice(2);
  if (!bundle) {
    console.error('usage: node examples/webgpu/render.mjs BUNDLE.wgsl [OUTPUT_DIR] (emit the bundle with saagen emit --manifest examples/webgpu/scene.saagen.toml)');
    process.exit(2);
  }
  const result = await run(fs.readFileSync(bundle, 'utf8'));
  console.log(`tonemapped RMSE against the 16-sample ground truth: unfiltered ${result.rmse.unfiltered.toFixed(5)}, saagen-filtered ${result.rmse.filtered.toFixed(5)}`);
  if (outputDirectory) {
    for (const name of ['unfiltered', 'filtered', 'truth']) writePng(path.join(outputDirectory, `${name}.png`), result[name]);
    console.log(`wrote ${['unfiltered', 'filtered', 'truth'].map((name) => path.join(outputDirectory, `${name}.png`)).join(', ')}`);
  }
  process.exit(0);
}
