// The example's scene: small glossy spheres (high curvature per pixel at low roughness, where
// specular highlights alias) with a clearcoat, lit by a directional light, rendered with three.js
// in WebGL2 in three forms: three.js as shipped, unfiltered, and filtered by a saagen snippet.
import * as THREE from 'three';
import { installSaagen } from './saagen-three.js';

export const SIZE = 256;

// Renders one frame of the scene in `mode` ('three': three.js as shipped, with its own geometric
// roughness; 'unfiltered': without it; 'saagen': the snippet's filter) and returns the RGBA8 pixels
// (bottom row first, as gl.readPixels returns them). clearcoatFilter: false leaves the clearcoat
// roughness unfiltered.
export function renderScene(renderer, mode, { snippet = '', wrapper = 'deferred_sum_fragment', roughness = 0.05, clearcoatFilter = true } = {}) {
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0x000000);
  const camera = new THREE.PerspectiveCamera(40, 1, 0.1, 100);
  camera.position.set(0, 0, 12);
  const light = new THREE.DirectionalLight(0xffffff, 3.0);
  light.position.set(1, 1.5, 2);
  scene.add(light);
  scene.add(new THREE.AmbientLight(0xffffff, 0.5));  // the spheres' diffuse, so every sphere pixel is lit

  const material = new THREE.MeshPhysicalMaterial({ color: 0x303030, metalness: 0.0, roughness, clearcoat: 1.0, clearcoatRoughness: roughness });
  if (mode !== 'three') installSaagen(material, { snippet, wrapper, filter: mode === 'saagen', clearcoat: clearcoatFilter });
  // A grid of spheres 12 to 40 pixels across: per-pixel normal changes of 0.05 to 0.2.
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
