// Runs the shaders that test_webgl wrote (DIR/cases.json) in WebGL2 in headless Chromium: each
// case is a fragment shader over a full-screen triangle into an RGBA32F target
// (EXT_color_buffer_float), with its inputs as an RGBA32F texture; the target is read back as
// floats after each pass (uniform saagen_pass) and written to DIR/<id>.out.f32.
//   node tests/webgl/run_functions.mjs DIR
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
function runCase(entry, inputBase64) {
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
    const result = await page.evaluate(runCase, entry, input);
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
