// Installs a saagen GLSL ES 3.00 snippet (`saagen emit --target gles`) into a three.js
// MeshStandardMaterial or MeshPhysicalMaterial: the material's roughness, and the clearcoat's,
// are filtered by the snippet's tangent-free fragment wrapper instead of three.js's own
// `geometryRoughness` term.
//
// Where: three.js computes `material.roughness` (and `material.clearcoatRoughness`) in the chunk
// lights_physical_fragment, after normal_fragment_begin/_maps have produced the view-space
// geometric normal `nonPerturbedNormal` (the interpolated vertex normal, or the face normal with
// flatShading, facing the viewer on double-sided materials) and the normal-mapped shading normal
// `normal` (and `clearcoatNormal`). The roughness map is read earlier (roughnessmap_fragment),
// before any normal exists, so the filter goes where three.js adds its geometric roughness:
// `material.roughness += geometryRoughness;` becomes a call of the snippet.
//
// Which normal (option `normal`): 'geometric' (the default) feeds `nonPerturbedNormal`, the normal
// three.js's own term reads: saagen's advice (generator/include/saagen/advice.hpp, quoted in
// examples/INTEGRATION.md), as HDRP, Filament and Unreal also do. The normal map's detail is the
// texture's to filter (a roughness map baked from it with `saagen texture prefilter --method hdrp
// --gltf`), not the kernel's, whose quad derivatives of a mapped normal alias into 2x2 blocks;
// deferred-sum, the default wrapper, on the geometric normal with that bake measured LDR-FLIP
// 0.0300 / TDE 0.00731 against 0.0411 / 0.00739 for no SAA on saagen's normal-mapped scenes; on
// authored maps it raises TDE over no SAA (CC0 @pmndrs maps; on ClearCoatTest LDR-FLIP too)
// (examples/INTEGRATION.md, "Real normal maps").
// 'shading' feeds the normal-mapped `normal` (and `clearcoatNormal`), which lowers LDR-FLIP less
// and raises TDE where the map is not baked. Advice.ExamplesAndDocsAgreeWithThePlanner checks
// these defaults against `saagen plan`.
// Without normal maps the two are the same vector and give the same picture.
//
// Domains: three.js's roughness is perceptual (r, the glTF convention): its GGX takes
// alpha = r^2, so alpha^2 = r^4. The tangent-free wrappers take and return alpha^2; the result
// goes back as r = (alpha^2)^(1/4). Their normal argument may be in any frame that does not
// change across the quad's pixels faster than the normal itself: the kernels depend only on the
// lengths of the normal's screen derivatives, which a rotation keeps, so three.js's view-space
// normals serve (the camera's rotation is the same at the four pixels of a quad).
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

// The normals the filter reads, per option: [base layer, clearcoat layer] (three.js's names in
// normal_fragment_begin, normal_fragment_maps and clearcoat_normal_fragment_*).
export const NORMALS = {
  geometric: ['nonPerturbedNormal', 'nonPerturbedNormal'],
  shading: ['normal', 'clearcoatNormal'],
};

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
// term (filter = true), reading the normals of NORMALS[normal], or the term is dropped
// (filter = false: the unfiltered reference render).
function lightsChunk(filter, clearcoat, normal) {
  const chunk = THREE.ShaderChunk.lights_physical_fragment;
  for (const line of [ROUGHNESS_LINE, CLEARCOAT_LINE]) {
    if (!chunk.includes(line)) {
      throw new Error(`saagen-three: three.js r${THREE.REVISION} has no '${line}' in lights_physical_fragment; this module needs updating`);
    }
  }
  if (filter && normal === 'geometric' && !chunk.includes('nonPerturbedNormal')) {
    throw new Error(`saagen-three: three.js r${THREE.REVISION} has no nonPerturbedNormal in lights_physical_fragment; this module needs updating`);
  }
  const [baseNormal, coatNormal] = NORMALS[normal];
  const base = filter ? `material.roughness = saagenFilterRoughness(material.roughness, ${baseNormal});` : '';
  const coat = filter && clearcoat ? `material.clearcoatRoughness = saagenFilterRoughness(material.clearcoatRoughness, ${coatNormal});` : '';
  return chunk.replace(ROUGHNESS_LINE, base).replace(CLEARCOAT_LINE, coat);
}

// Installs the snippet into `material`. Options:
//   snippet   the text of a `saagen emit --target gles` file (fp32 or fp16) with the wrapper
//   wrapper   the unprefixed wrapper name (one of TANGENT_FREE_WRAPPERS; default deferred_sum_fragment)
//   normal    which normal the filter reads: 'geometric' (default) the interpolated vertex normal
//             before the normal map (three.js's nonPerturbedNormal), with the map's detail
//             prefiltered into the roughness map; 'shading' the normal-mapped normal (and
//             clearcoatNormal), only for content without texture prefiltering
//   filter    false: no filter and no three.js geometric roughness (the unfiltered render)
//   clearcoat filter the clearcoat roughness too (default true; needs MeshPhysicalMaterial.clearcoat > 0)
// Returns the material.
export function installSaagen(material, { snippet = '', wrapper = 'deferred_sum_fragment', normal = 'geometric', filter = true, clearcoat = true } = {}) {
  if (!TANGENT_FREE_WRAPPERS.includes(wrapper)) {
    throw new Error(`saagen-three: wrapper '${wrapper}' is not one of ${TANGENT_FREE_WRAPPERS.join(', ')}`);
  }
  if (!Object.hasOwn(NORMALS, normal)) {
    throw new Error(`saagen-three: normal '${normal}' is not one of ${Object.keys(NORMALS).join(', ')}`);
  }
  let functionName = '';
  if (filter) {
    functionName = snippetPrefix(snippet) + wrapper;
    if (!snippet.includes(`${functionName}(`)) {
      throw new Error(`saagen-three: the snippet defines no ${functionName}; emit the variant that has it`);
    }
  }
  const key = filter ? `saagen|${functionName}|${normal}|${clearcoat}|${fingerprint(snippet)}` : 'saagen|unfiltered';
  material.onBeforeCompile = (shader) => {
    const head = filter ? snippet + roughnessFilter(functionName) : '';
    shader.fragmentShader = head + shader.fragmentShader.replace('#include <lights_physical_fragment>', lightsChunk(filter, clearcoat, normal));
  };
  // Two configurations (snippet, wrapper, normal, clearcoat, on/off) never share a compiled program.
  material.customProgramCacheKey = () => key;
  material.needsUpdate = true;
  return material;
}
