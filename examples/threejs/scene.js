// The example's scene: small glossy spheres (high curvature per pixel at low roughness, where
// specular highlights alias) with a clearcoat, lit by a directional light, rendered with three.js
// in WebGL2 in three forms: three.js as shipped, unfiltered, and filtered by a saagen snippet.
import * as THREE from 'three';
import { installPlan, installSaagen } from './saagen-three.js';

export const SIZE = 256;

// A tangent-space normal map of round bumps (8 x 8 per texture), with its MIP chain: the detail
// the geometric normal does not see and the normal-mapped one does.
export function bumpNormalMap(size = 64, bumps = 8, height = 0.6) {
  const data = new Uint8Array(size * size * 4);
  const period = size / bumps;
  for (let y = 0; y < size; ++y) {
    for (let x = 0; x < size; ++x) {
      // Slopes of h = height * cos(2 pi x / period) * cos(2 pi y / period), in texels.
      const u = 2 * Math.PI * (x + 0.5) / period, v = 2 * Math.PI * (y + 0.5) / period;
      const sx = -height * Math.sin(u) * Math.cos(v), sy = -height * Math.cos(u) * Math.sin(v);
      const length = Math.hypot(sx, sy, 1);
      const i = 4 * (y * size + x);
      data[i] = Math.round(127.5 * (1 - sx / length));
      data[i + 1] = Math.round(127.5 * (1 - sy / length));
      data[i + 2] = Math.round(127.5 * (1 + 1 / length));
      data[i + 3] = 255;
    }
  }
  const texture = new THREE.DataTexture(data, size, size, THREE.RGBAFormat);
  texture.wrapS = texture.wrapT = THREE.RepeatWrapping;
  texture.repeat.set(4, 2);
  texture.magFilter = THREE.LinearFilter;
  texture.minFilter = THREE.LinearMipmapLinearFilter;
  texture.generateMipmaps = true;
  texture.needsUpdate = true;
  return texture;
}

// The scene in `mode` ('three': three.js as shipped, with its own geometric roughness;
// 'unfiltered': without it; 'saagen': the snippet's filter; 'plan': what the plan's entry says,
// installPlan with the manifest's bundle as snippet): { scene, camera }. clearcoatFilter: false
// leaves the clearcoat roughness unfiltered; normal: the normal the filter reads ('geometric' or
// 'shading', see installSaagen); bake: sample the maps as a bake's (installSaagen); normalMap: true gives the spheres bumpNormalMap() (base layer
// and clearcoat).
export function buildScene(mode, { snippet = '', wrapper = 'deferred_sum_fragment', normal = 'geometric', bake = false, normalMap = false, roughness = 0.05, clearcoatFilter = true, entry = null } = {}) {
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0x000000);
  const camera = new THREE.PerspectiveCamera(40, 1, 0.1, 100);
  camera.position.set(0, 0, 12);
  const light = new THREE.DirectionalLight(0xffffff, 3.0);
  light.position.set(1, 1.5, 2);
  scene.add(light);
  scene.add(new THREE.AmbientLight(0xffffff, 0.5));  // the spheres' diffuse, so every sphere pixel is lit

  const material = new THREE.MeshPhysicalMaterial({ color: 0x303030, metalness: 0.0, roughness, clearcoat: 1.0, clearcoatRoughness: roughness });
  if (normalMap) {
    material.normalMap = bumpNormalMap();
    material.clearcoatNormalMap = material.normalMap;
  }
  if (mode === 'plan') installPlan(material, entry, { snippet });
  else if (mode !== 'three') installSaagen(material, { snippet, wrapper, normal, bake, filter: mode === 'saagen', clearcoat: clearcoatFilter });
  const geometry = new THREE.SphereGeometry(1, 64, 32);
  for (let row = 0; row < 3; ++row) {
    for (let column = 0; column < 3; ++column) {
      const sphere = new THREE.Mesh(geometry, material);
      const scale = 0.35 + 0.3 * (row * 3 + column) / 8;
      sphere.scale.setScalar(scale);
      sphere.position.set((column - 1) * 3, (row - 1) * 3, 0);
      scene.add(sphere);
    }
  }
  return { scene, camera };
}

// Renders one frame of the scene in `mode` (buildScene's modes and options) and returns the RGBA8
// pixels (bottom row first, as gl.readPixels returns them).
export function renderScene(renderer, mode, options = {}) {
  const { scene, camera } = buildScene(mode, options);
  renderer.render(scene, camera);
  const gl = renderer.getContext();
  const pixels = new Uint8Array(SIZE * SIZE * 4);
  gl.readPixels(0, 0, SIZE, SIZE, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
  // The material and its program stay alive with the renderer: a later configuration rendered
  // by the same renderer must get its own program, not this one (customProgramCacheKey).
  return pixels;
}

export function createRenderer(canvas) {
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: false, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  renderer.setSize(SIZE, SIZE, false);
  return renderer;
}
