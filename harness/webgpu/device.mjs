// A WebGPU device for saagen's WGSL target: Dawn for Node (the npm package `webgpu`, pinned by
// package-lock.json) on SwiftShader's Vulkan ICD from Debian's chromium package.
//
// Usage:
//   import { openDevice } from './device.mjs';
//   const session = await openDevice();
//   ... session.device, session.flags.BufferUsage, session.takeUncapturedErrors() ...
//   session.close();            // destroys the device
//   process.exit(code);         // the only way out: see `instances` below
//
// openDevice() resolves to
//   { device,                    // GPUDevice
//     adapterInfo: { vendor, architecture, device, description },
//     features: [string],        // the device's enabled features (shader-f16 when offered)
//     limits: { name: number },  // the device limits the job runner relies on
//     flags: { BufferUsage, MapMode, TextureUsage, ShaderStage },
//     lostInfo(),                // null, or { reason, message } once the device is lost
//     takeUncapturedErrors(),    // messages of errors no error scope caught, since the last call
//     close() }                 // destroys the device (again harmlessly)
// and rejects with an Error whose message is one line when there is no usable adapter.
//
// Driver selection: the Vulkan loader reads VK_ICD_FILENAMES / VK_DRIVER_FILES when Dawn creates
// its Vulkan instance, which happens after this module has set them in process.env (Node's
// process.env writes through to the C environment), so no re-exec is needed. The manifest is
// /usr/lib/chromium/vk_swiftshader_icd.json unless SAAGEN_WEBGPU_ICD names another. Only that one
// driver is made visible: Dawn refuses lavapipe, and whatever the caller's environment listed
// (the C++ tests list lavapipe and SwiftShader together) would otherwise be enumerated too.
import fs from 'node:fs';

export const DEFAULT_ICD = '/usr/lib/chromium/vk_swiftshader_icd.json';

// The limits the job runner reads or raises; results.json reports them as `limits_used`.
const REPORTED_LIMITS = [
  'maxStorageBuffersInFragmentStage',
  'maxComputeWorkgroupsPerDimension',
  'maxComputeInvocationsPerWorkgroup',
  'maxStorageBufferBindingSize',
  'maxBufferSize',
  'maxTextureDimension2D',
  'maxTextureArrayLayers',
];

// Points the Vulkan loader at one ICD manifest; returns its path.
export function selectVulkanDriver(env = process.env) {
  const icd = env.SAAGEN_WEBGPU_ICD || DEFAULT_ICD;
  if (!fs.existsSync(icd)) {
    throw new Error(`no Vulkan ICD manifest at ${icd} (install Debian's chromium, or set SAAGEN_WEBGPU_ICD)`);
  }
  env.VK_ICD_FILENAMES = icd;
  env.VK_DRIVER_FILES = icd; // the loader's newer name; it wins over VK_ICD_FILENAMES when both are set
  delete env.VK_ADD_DRIVER_FILES; // would add drivers back next to the one chosen
  // Something in the driver stack probes for a Wayland display, and libwayland prints
  // "error: XDG_RUNTIME_DIR is invalid" to stderr when that variable is unset. Nothing here
  // presents to a window; an absolute display path that does not exist makes the probe fail
  // quietly, so the runner's stderr carries only the runner's own messages.
  if (!env.XDG_RUNTIME_DIR && !env.WAYLAND_DISPLAY) env.WAYLAND_DISPLAY = '/nonexistent/saagen-no-wayland';
  return icd;
}

// Raise the buffer-size limits to what the adapter allows: the defaults (128 MiB bindings,
// 256 MiB buffers) are enough for today's inputs, but asking costs nothing. The array-layer
// limit too: WebGPU's default is 256, and the glint dictionary has L * N / 4 layers (768 by default).
function requiredLimits(adapter) {
  return {
    maxStorageBufferBindingSize: adapter.limits.maxStorageBufferBindingSize,
    maxBufferSize: adapter.limits.maxBufferSize,
    maxTextureArrayLayers: adapter.limits.maxTextureArrayLayers,
  };
}

function describeAdapter(adapter) {
  const info = adapter.info;
  return { vendor: info.vendor, architecture: info.architecture, device: info.device, description: info.description };
}

function pickLimits(device) {
  return Object.fromEntries(REPORTED_LIMITS.map((name) => [name, device.limits[name]]));
}

// Every Dawn instance ever created, kept reachable until the process ends. Dawn for Node's event
// pump holds a plain pointer to its instance and may still be scheduled after the last device
// is destroyed; had the garbage collector freed the instance by then, the pump would run on
// freed memory (seen here as a segmentation fault or std::system_error at exit). A referenced
// instance also keeps Node's event loop alive, so a program using this module ends with
// process.exit() rather than by running out of work.
const instances = [];

export async function openDevice() {
  selectVulkanDriver();
  // Imported only now so that nothing of Dawn's is loaded before the environment is set.
  const { create, globals } = await import('webgpu');
  const gpu = create([]);
  instances.push(gpu);
  const adapter = await gpu.requestAdapter();
  if (!adapter) {
    throw new Error(`no WebGPU adapter on the Vulkan driver ${process.env.VK_ICD_FILENAMES}`);
  }
  const adapterInfo = describeAdapter(adapter);
  const requiredFeatures = adapter.features.has('shader-f16') ? ['shader-f16'] : [];
  const device = await adapter.requestDevice({ requiredFeatures, requiredLimits: requiredLimits(adapter) });

  let uncaptured = [];
  device.addEventListener('uncapturederror', (event) => uncaptured.push(event.error.message));
  let lost = null;
  let closing = false;
  device.lost.then((info) => { if (!closing) lost = { reason: info.reason, message: info.message }; });

  return {
    device,
    adapterInfo,
    features: [...device.features].sort(),
    limits: pickLimits(device),
    flags: {
      BufferUsage: globals.GPUBufferUsage,
      MapMode: globals.GPUMapMode,
      TextureUsage: globals.GPUTextureUsage,
      ShaderStage: globals.GPUShaderStage,
    },
    lostInfo: () => lost,
    takeUncapturedErrors() {
      const taken = uncaptured;
      uncaptured = [];
      return taken;
    },
    close() {
      closing = true;
      device.destroy();
    },
  };
}
