// Installs a saagen GLSL ES 3.00 snippet (`saagen emit --target gles`) into a three.js
// MeshStandardMaterial or MeshPhysicalMaterial: the material's roughness, and the clearcoat's,
// are filtered by the snippet's tangent-free fragment wrapper instead of three.js's own
// `geometryRoughness` term.
//
// Where: three.js computes `material.roughness` (and `material.clearcoatRoughness`) in the chunk
// lights_physical_fragment, after normal_fragment_begin/_maps have produced the view-space
// shading normal `normal` (and `clearcoatNormal`). The roughness map is read earlier
// (roughnessmap_fragment), before any normal exists, so the filter goes where three.js adds its
// geometric roughness: `material.roughness += geometryRoughness;` becomes a call of the snippet.
//
// Domains: three.js's roughness is perceptual (r, the glTF convention): its GGX takes
// alpha = r^2, so alpha^2 = r^4. The tangent-free wrappers take and return alpha^2; the result
// goes back as r = (alpha^2)^(1/4). Their normal argument may be in any frame that does not
// change across the quad's pixels faster than the normal itself: the kernels depend only on the
// lengths of the normal's screen derivatives, which a rotation keeps, so three.js's view-space
// normal serves (the camera's rotation is the same at the four pixels of a quad).
import * as THREE from 'three';

// The wrappers that need only alpha^2 and a normal (no tangent frame, no half vector).
export const TANGENT_FREE_WRAPPERS = [
  'deferred_sum_fragment',
  'deferred_avg_fragment',
  'deferred_max_tangent_free_fragment',
  'deferred_projected_space_fragment',
];

const ROUGHNESS_LINE = 'material.roughness += geometryRoughness;';
const CLEARCOAT_LINE = 'material.clearcoatRoughness += geometryRoughness;';

// A short, stable hash of the snippet's text, so that two snippets never share a program.
function fingerprint(text) {
  let hash = 0x811c9dc5;
  for (let index = 0; index < text.length; ++index) {
    hash ^= text.charCodeAt(index);
    hash = Math.imul(hash, 0x01000193) >>> 0;
  }
  return hash.toString(16).padStart(8, '0');
}

// The prefix the snippet was emitted with, from its marker line ("// saagen-marker: ... prefix=saa_").
function snippetPrefix(snippet) {
  const marker = /^\/\/ saagen-marker: target=(\S+) .*?prefix=(\S+)/m.exec(snippet);
  if (!marker) throw new Error('saagen-three: the snippet has no saagen marker line; pass the text of a file `saagen emit` wrote');
  if (marker[1] !== 'gles') throw new Error(`saagen-three: the snippet targets ${marker[1]}; emit it with \`saagen emit --target gles\``);
  return marker[2];
}

// GLSL: perceptual roughness in, the filtered perceptual roughness out.
function roughnessFilter(functionName) {
  return `
// saagen: three.js perceptual roughness r -> alpha^2 = r^4 -> ${functionName} -> r' = (alpha'^2)^(1/4)
highp float saagenFilterRoughness(highp float perceptual, highp vec3 viewNormal) {
  highp float alpha2 = perceptual * perceptual * perceptual * perceptual;
  return sqrt(sqrt(${functionName}(alpha2, viewNormal)));
}
`;
}

// Patches three.js's lights_physical_fragment chunk: the filter replaces the geometric-roughness
// term (filter = true), or the term is dropped (filter = false: the unfiltered reference render).
function lightsChunk(filter, clearcoat) {
  const chunk = THREE.ShaderChunk.lights_physical_fragment;
  for (const line of [ROUGHNESS_LINE, CLEARCOAT_LINE]) {
    if (!chunk.includes(line)) {
      throw new Error(`saagen-three: three.js r${THREE.REVISION} has no '${line}' in lights_physical_fragment; this module needs updating`);
    }
  }
  const base = filter ? 'material.roughness = saagenFilterRoughness(material.roughness, normal);' : '';
  const coat = filter && clearcoat ? 'material.clearcoatRoughness = saagenFilterRoughness(material.clearcoatRoughness, clearcoatNormal);' : '';
  return chunk.replace(ROUGHNESS_LINE, base).replace(CLEARCOAT_LINE, coat);
}

// Installs the snippet into `material`. Options:
//   snippet   the text of a `saagen emit --target gles` file (fp32 or fp16) with the wrapper
//   wrapper   the unprefixed wrapper name (one of TANGENT_FREE_WRAPPERS; default deferred_sum_fragment)
//   filter    false: no filter and no three.js geometric roughness (the unfiltered render)
//   clearcoat filter the clearcoat roughness too (default true; needs MeshPhysicalMaterial.clearcoat > 0)
// Returns the material.
export function installSaagen(material, { snippet = '', wrapper = 'deferred_sum_fragment', filter = true, clearcoat = true } = {}) {
  if (!TANGENT_FREE_WRAPPERS.includes(wrapper)) {
    throw new Error(`saagen-three: wrapper '${wrapper}' is not one of ${TANGENT_FREE_WRAPPERS.join(', ')}`);
  }
  let functionName = '';
  if (filter) {
    functionName = snippetPrefix(snippet) + wrapper;
    if (!snippet.includes(`${functionName}(`)) {
      throw new Error(`saagen-three: the snippet defines no ${functionName}; emit the variant that has it`);
    }
  }
  const key = filter ? `saagen|${functionName}|${clearcoat}|${fingerprint(snippet)}` : 'saagen|unfiltered';
  material.onBeforeCompile = (shader) => {
    const head = filter ? snippet + roughnessFilter(functionName) : '';
    shader.fragmentShader = head + shader.fragmentShader.replace('#include <lights_physical_fragment>', lightsChunk(filter, clearcoat));
  };
  // Two configurations (snippet, wrapper, clearcoat, on/off) never share a compiled program.
  material.customProgramCacheKey = () => key;
  material.needsUpdate = true;
  return material;
}
