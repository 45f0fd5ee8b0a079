// Runs the shaders that test_webgl wrote (DIR/cases.json) in WebGL2 in headless Chromium: each
// case is a fragment shader over a full-screen triangle into an RGBA32F target
// (EXT_color_buffer_float), with its inputs as an RGBA32F texture; the target is read back as
// floats after each pass (uniform saagen_pass) and written to DIR/<id>.out.f32.
//   node tests/webgl/run_functions.mjs DIR
// A case may also name a 2D array texture (the glint dictionary), bound to texture unit 1 as
// the sampler2DArray uniform `uniform`: the fields of the WebGPU runner's "texture"
// (harness/webgpu/run.mjs: file of raw texels level after level, layer after layer; format
// rgba16float or rgba32float; width, height, layers, levels; filter, mipmap_filter; address_mode).
import fs from 'node:fs';
import path from 'node:path';
import { launchChromium } from './browser.mjs';

const directory = process.argv[2];
if (!directory) {
  console.error('usage: node tests/webgl/run_functions.mjs DIR (written by test_webgl)');
  process.exit(2);
}
const cases = JSON.parse(fs.readFileSync(path.join(directory, 'cases.json'), 'utf8'));

// In the page: one WebGL2 context, one case at a time.
function runCase(entry, inputBase64, textureBase64) {
  const canvas = window.saagenCanvas ?? (window.saagenCanvas = document.createElement('canvas'));
  const gl = window.saagenGl ?? (window.saagenGl = canvas.getContext('webgl2'));
  if (!gl) return { error: 'no WebGL2 context' };
  if (!gl.getExtension('EXT_color_buffer_float')) return { error: 'no EXT_color_buffer_float' };
  const compile = (type, source) => {
    const shader = gl.createShader(type);
    gl.shaderSource(shader, source);
    gl.compileShader(shader);
    if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(shader));
    return shader;
  };
  const vertex = '#version 300 es\nvoid main() {\n  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));\n  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);\n}\n';
  let program;
  try {
    program = gl.createProgram();
    gl.attachShader(program, compile(gl.VERTEX_SHADER, vertex));
    gl.attachShader(program, compile(gl.FRAGMENT_SHADER, entry.shader));
    gl.linkProgram(program);
    if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(program));
  } catch (error) {
    return { error: `compile/link: ${error.message}` };
  }
  gl.useProgram(program);
  const input = gl.createTexture();
  gl.activeTexture(gl.TEXTURE0);
  gl.bindTexture(gl.TEXTURE_2D, input);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
  if (inputBase64) {
    const bytes = Uint8Array.from(atob(inputBase64), (c) => c.charCodeAt(0));
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, entry.input_width, entry.input_height, 0, gl.RGBA, gl.FLOAT, new Float32Array(bytes.buffer));
  } else {
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, 1, 1, 0, gl.RGBA, gl.FLOAT, new Float32Array(4));
  }
  gl.uniform1i(gl.getUniformLocation(program, 'saagen_input'), 0);
  let arrayTexture = null;
  if (entry.texture) {
    const t = entry.texture;
    const formats = { rgba16float: [gl.RGBA16F, gl.HALF_FLOAT, Uint16Array], rgba32float: [gl.RGBA32F, gl.FLOAT, Float32Array] };
    const wraps = { 'clamp-to-edge': gl.CLAMP_TO_EDGE, repeat: gl.REPEAT, 'mirror-repeat': gl.MIRRORED_REPEAT };
    const format = formats[t.format];
    if (!format) return { error: `texture format ${t.format} is not rgba16float or rgba32float` };
    const maxLayers = gl.getParameter(gl.MAX_ARRAY_TEXTURE_LAYERS);
    if (t.layers > maxLayers) return { error: `texture layers ${t.layers} exceed MAX_ARRAY_TEXTURE_LAYERS ${maxLayers}` };
    const [internalFormat, type, View] = format;
    const bytes = Uint8Array.from(atob(textureBase64), (c) => c.charCodeAt(0));
    arrayTexture = gl.createTexture();
    gl.activeTexture(gl.TEXTURE1);
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, arrayTexture);
    gl.texStorage3D(gl.TEXTURE_2D_ARRAY, t.levels, internalFormat, t.width, t.height, t.layers);
    let offset = 0;
    for (let level = 0; level < t.levels; ++level) {
      const width = Math.max(1, t.width >> level);
      const height = Math.max(1, t.height >> level);
      const count = width * height * t.layers * 4;
      gl.texSubImage3D(gl.TEXTURE_2D_ARRAY, level, 0, 0, 0, width, height, t.layers, gl.RGBA, type, new View(bytes.buffer, offset, count));
      offset += count * View.BYTES_PER_ELEMENT;
    }
    if (offset !== bytes.length) return { error: `texture ${t.file} is ${bytes.length} bytes, its levels take ${offset}` };
    const linear = t.filter === 'linear';
    const minFilter = t.mipmap_filter === 'linear' ? (linear ? gl.LINEAR_MIPMAP_LINEAR : gl.NEAREST_MIPMAP_LINEAR)
                                                   : (linear ? gl.LINEAR_MIPMAP_NEAREST : gl.NEAREST_MIPMAP_NEAREST);
    gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MIN_FILTER, minFilter);
    gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MAG_FILTER, linear ? gl.LINEAR : gl.NEAREST);
    for (const wrap of [gl.TEXTURE_WRAP_S, gl.TEXTURE_WRAP_T, gl.TEXTURE_WRAP_R]) {
      gl.texParameteri(gl.TEXTURE_2D_ARRAY, wrap, wraps[t.address_mode ?? 'clamp-to-edge']);
    }
    gl.uniform1i(gl.getUniformLocation(program, t.uniform), 1);
    gl.activeTexture(gl.TEXTURE0);
  }
  const target = gl.createTexture();
  gl.bindTexture(gl.TEXTURE_2D, target);
  gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, entry.width, entry.height, 0, gl.RGBA, gl.FLOAT, null);
  gl.bindTexture(gl.TEXTURE_2D, input);
  const framebuffer = gl.createFramebuffer();
  gl.bindFramebuffer(gl.FRAMEBUFFER, framebuffer);
  gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, target, 0);
  if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE) return { error: 'RGBA32F target incomplete' };
  gl.viewport(0, 0, entry.width, entry.height);
  const passLocation = gl.getUniformLocation(program, 'saagen_pass');
  const pixels = entry.width * entry.height * 4;
  const result = new Float32Array(pixels * entry.passes);
  for (let pass = 0; pass < entry.passes; ++pass) {
    gl.uniform1i(passLocation, pass);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    gl.readPixels(0, 0, entry.width, entry.height, gl.RGBA, gl.FLOAT, result.subarray(pass * pixels, (pass + 1) * pixels));
  }
  const glError = gl.getError();
  gl.deleteFramebuffer(framebuffer);
  gl.deleteTexture(target);
  gl.deleteTexture(input);
  if (arrayTexture) gl.deleteTexture(arrayTexture);
  gl.deleteProgram(program);
  if (glError !== gl.NO_ERROR) return { error: `GL error ${glError}` };
  const bytes = new Uint8Array(result.buffer);
  let binary = '';
  for (let i = 0; i < bytes.length; i += 0x8000) binary += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
  return { output: btoa(binary) };
}

const started = Date.now();
const { browser, close } = await launchChromium();
let failures = 0;
try {
  const page = await browser.newPage();
  const info = await page.evaluate(() => {
    const gl = document.createElement('canvas').getContext('webgl2');
    const format = (kind) => { const f = gl.getShaderPrecisionFormat(gl.FRAGMENT_SHADER, gl[kind]); return `${f.rangeMin}/${f.rangeMax}/${f.precision}`; };
    return `${gl.getParameter(gl.VERSION)}; fragment highp ${format('HIGH_FLOAT')}, mediump ${format('MEDIUM_FLOAT')} (range/range/precision bits)`;
  });
  console.log(`[ webgl2   ] ${info}`);
  for (const entry of cases) {
    const input = entry.input ? fs.readFileSync(path.join(directory, entry.input)).toString('base64') : null;
    const texture = entry.texture ? fs.readFileSync(path.join(directory, entry.texture.file)).toString('base64') : null;
    const result = await page.evaluate(runCase, entry, input, texture);
    if (result.error) {
      ++failures;
      console.error(`[ webgl2   ] ${entry.id}: ${result.error}`);
      continue;
    }
    fs.writeFileSync(path.join(directory, `${entry.id}.out.f32`), Buffer.from(result.output, 'base64'));
  }
} finally {
  await close();
}
console.log(`[ webgl2   ] ${cases.length} shaders run, ${failures} failed, in ${((Date.now() - started) / 1000).toFixed(1)} s`);
