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
// three.js's own term reads: the feed `saagen plan` gives the example's named normal-mapped
// filter (terrain; Advice.ExamplesAndDocsAgreeWithThePlanner), as HDRP, Filament and Unreal also
// do; 'shading' feeds the normal-mapped normal, where the plan's measured configuration is fed it
// (installPlan follows the plan's `feed`). What saagen advises per content is `saagen plan --advice` (examples/INTEGRATION.md).
// The normal map's detail is the texture's
// to filter (a roughness map baked from it with `saagen texture prefilter --method hdrp --gltf`),
// not the kernel's, whose quad derivatives of a mapped normal alias into 2x2 blocks.
// 'shading' feeds the normal-mapped `normal` (and `clearcoatNormal`). Without normal maps the two
// are the same vector and give the same picture. Advice.ExamplesAndDocsAgreeWithThePlanner checks
// these defaults against `saagen plan`.
//
// Measured in three.js (examples/INTEGRATION.md, "Measured in three.js": the example scene at
// 128 x 128 pixels, 24 frames, `saagen score` against a 1024-sample ground truth; differences in
// image error (LDR-FLIP) / video error (10 - JOD), negative is better): on the smooth spheres every
// tail-preserving plan beat no SAA in both (-0.0012 to -0.0015 / -1.33 to -1.41) yet was mixed
// against three.js's own geometryRoughness (-0.0013 to -0.0016 / +0.25 to +0.33); on the
// normal-mapped spheres both plans beat no SAA and three.js's term: forward-axis-projected/tail on
// the normal-mapped normal (bumpy, saagen's advice then, now forward-aniso-projected/tail;
// -0.0012 / -0.07 against three.js's) and the
// named deferred-sum on the geometric normal (bumpy_named; -0.0012 / -0.12).
//
// LOD bias: where the material's roughness map holds the normal map's bake (option `bake`, the
// plan's `prefilter`), the normal map and the baked roughness map (and the clearcoat's) are
// sampled one MIP level coarser than the implicit LOD (PREFILTER_LOD_BIAS, saagen's advice:
// generator/include/saagen/advice.hpp, kPrefilterLodBias; docs/PREFILTER.md, "The LOD bias"), as
// the trade measures its baked rows: at the implicit LOD, map detail near the pixel grid's Nyquist
// frequency stays in the shading normal, aliased, and the bake's wider lobe turns it into
// flicker; one level coarser it moves into the bake. three.js's texture2D calls in
// normal_fragment_maps, roughnessmap_fragment, clearcoat_normal_fragment_maps and the clearcoat
// roughness map's line get the bias argument. Without a bake (whatever the normal) and with
// filter: false the maps keep the implicit LOD, as the trade's rows without a bake do.
//
// Domains: three.js's roughness is perceptual (r, the glTF convention): its GGX takes
// alpha = r^2, so alpha^2 = r^4. The tangent-free wrappers take and return alpha^2; the result
// goes back as r = (alpha^2)^(1/4). Their normal argument may be in any frame that does not
// change across the quad's pixels faster than the normal itself: the kernels depend only on the
// lengths of the normal's screen derivatives, which a rotation keeps, so three.js's view-space
// normals serve (the camera's rotation is the same at the four pixels of a quad).
//
// installPlan(material, entry, { snippet }) installs what `saagen plan MANIFEST --json` says for
// one material (its entry in "materials"), the way to use this module: no filter (variant
// "none": three.js's own geometric roughness term dropped, so the material shades its own
// roughness), a tangent-free filter of the roughness, or, with the tail-preserving filtered GGX
// (the plan's brdf ggx_brdf_filtered_*: docs/FILTERED_GGX.md), three.js's BRDF_GGX patched to
// evaluate saagen's lobe for the punctual lights: forward-aniso-projected and
// forward-axis-projected per light on the half vector, deferred-aniso's G-buffer tensor added to
// alpha^2 I (docs/DEFERRED_KERNEL.md), the tangent-free filters' roughness. The
// snippet is the bundle `saagen emit --manifest MANIFEST` writes for a manifest with
// targets = ["gles"]; installSaagen below is the lower-level roughness-only form.
import * as THREE from 'three';

// The wrappers that need only alpha^2 and a normal (no tangent frame, no half vector).
export const TANGENT_FREE_WRAPPERS = [
  'deferred_sum_fragment',
  'deferred_avg_fragment',
  'deferred_max_tangent_free_fragment',
  'deferred_projected_space_fragment',
];

// saagen's advice: the MIP level bias of a prefiltered material's normal map and its bake
// (advice.hpp, kPrefilterLodBias; Advice.ExamplesAndDocsAgreeWithThePlanner checks it).
export const PREFILTER_LOD_BIAS = 1;

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

// The texture reads that take the LOD bias, per chunk: three.js's r187 text of each read.
const BIASED_READS = {
  normal_fragment_maps: ['texture2D( normalMap, vNormalMapUv )'],
  roughnessmap_fragment: ['texture2D( roughnessMap, vRoughnessMapUv )'],
  clearcoat_normal_fragment_maps: ['texture2D( clearcoatNormalMap, vClearcoatNormalMapUv )'],
  lights_physical_fragment: ['texture2D( clearcoatRoughnessMap, vClearcoatRoughnessMapUv )'],
};

// A chunk's text with its BIASED_READS sampled PREFILTER_LOD_BIAS levels coarser (GLSL ES 3.00's
// texture(sampler, uv, bias), which three.js's texture2D names).
function biasedChunk(name, chunk) {
  let text = chunk;
  for (const read of BIASED_READS[name]) {
    if (!text.includes(read)) {
      throw new Error(`saagen-three: three.js r${THREE.REVISION} has no '${read}' in ${name}; this module needs updating`);
    }
    text = text.replaceAll(read, `${read.slice(0, -2)}, ${PREFILTER_LOD_BIAS.toFixed(1)} )`);
  }
  return text;
}

// Patches three.js's lights_physical_fragment chunk: the filter replaces the geometric-roughness
// term (filter = true), reading the normals of NORMALS[normal], or the term is dropped
// (filter = false: the unfiltered reference render).
function lightsChunk(filter, clearcoat, normal, bake) {
  const shipped = THREE.ShaderChunk.lights_physical_fragment;
  const chunk = biases(filter, bake) ? biasedChunk('lights_physical_fragment', shipped) : shipped;
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

// Whether the normal map and its bake are sampled with the LOD bias: a filter with a bake.
function biases(filter, bake) {
  return filter && bake;
}

// The fragment shader's includes of the chunks with biased reads, expanded with the bias.
function withBiasedReads(fragmentShader) {
  let text = fragmentShader;
  for (const name of Object.keys(BIASED_READS)) {
    if (name !== 'lights_physical_fragment') text = text.replace(`#include <${name}>`, biasedChunk(name, THREE.ShaderChunk[name]));
  }
  return text;
}

// Installs the snippet into `material`. Options:
//   snippet   the text of a `saagen emit --target gles` file (fp32 or fp16) with the wrapper
//   wrapper   the unprefixed wrapper name (one of TANGENT_FREE_WRAPPERS; default deferred_sum_fragment)
//   normal    which normal the filter reads: 'geometric' (default) the interpolated vertex normal
//             before the normal map (three.js's nonPerturbedNormal); 'shading' the normal-mapped
//             normal (and clearcoatNormal)
//   bake      true where material.roughnessMap holds the normal map's bake (`saagen texture
//             prefilter`): the normal map and the roughness maps are sampled PREFILTER_LOD_BIAS
//             levels coarser; false (default): the implicit LOD
//   filter    false: no filter and no three.js geometric roughness (the unfiltered render)
//   clearcoat filter the clearcoat roughness too (default true; needs MeshPhysicalMaterial.clearcoat > 0)
// Returns the material.
export function installSaagen(material, { snippet = '', wrapper = 'deferred_sum_fragment', normal = 'geometric', bake = false, filter = true, clearcoat = true } = {}) {
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
  const key = filter ? `saagen|${functionName}|${normal}|${bake}|${clearcoat}|${fingerprint(snippet)}` : 'saagen|unfiltered';
  material.onBeforeCompile = (shader) => {
    const head = filter ? snippet + roughnessFilter(functionName) : '';
    const fragment = biases(filter, bake) ? withBiasedReads(shader.fragmentShader) : shader.fragmentShader;
    shader.fragmentShader = head + fragment.replace('#include <lights_physical_fragment>', lightsChunk(filter, clearcoat, normal, bake));
  };
  // Two configurations (snippet, wrapper, normal, bake, clearcoat, on/off) never share a compiled program.
  material.customProgramCacheKey = () => key;
  material.needsUpdate = true;
  return material;
}

// ---------------------------------------------------------------------------------------------
// Installing a plan (`saagen plan MANIFEST --json`, one entry of "materials")

// The plan's wrappers this module installs, and how: 'roughness' filters three.js's roughness
// (a tangent-free wrapper, alpha^2 in and out); 'tensor' writes deferred-aniso's kernel tensor
// per pixel and evaluates its lighting pass per light; 'matrix' and 'axis' filter per light on
// the half vector (forward-*), returning a roughness matrix or per-axis alpha^2; the projected
// forms' *_transported_fragment wrappers (what saagen plans) read it in view space with the frame.
export const PLAN_WRAPPERS = {
  deferred_sum_fragment: 'roughness',
  deferred_avg_fragment: 'roughness',
  deferred_max_tangent_free_fragment: 'roughness',
  deferred_projected_space_fragment: 'roughness',
  deferred_aniso_fragment: 'tensor',
  forward_aniso_projected_fragment: 'matrix',
  forward_aniso_projected_transported_fragment: 'matrix',
  forward_aniso_slope_fragment: 'matrix',
  forward_axis_projected_fragment: 'axis',
  forward_axis_projected_transported_fragment: 'axis',
  forward_axis_slope_fragment: 'axis',
};

const BRDF_GGX_HEAD = 'vec3 BRDF_GGX( const in vec3 lightDir, const in vec3 viewDir, const in vec3 normal, const in PhysicalMaterial material ) {';
const BRDF_GGX_RETURN = 'return F * ( V * D );';

// The GLSL the plan's lobe needs: the material's own alpha^2, the normal the filter read, the
// filter's per-pixel result, a tangent frame built from a normal (Duff et al. 2017, "Building an
// Orthonormal Basis, Revisited", JCGT 6(1), Listing 3: continuous except where n.z changes sign;
// the isotropic materials this module serves need any frame, the same at the four pixels of a
// quad), and saagenSpecular(l, v, n), the specular BRDF value without Fresnel that replaces
// three.js's V * D. The lobe is evaluated about the shading normal n (BRDF_GGX's, normal-mapped
// where the material has a map); the forward filters measure the half vector in the frame of the
// normal they are fed, deferred-aniso's lighting pass rebuilds its tensor's frame from that normal.
function lobeGlsl(kind, prefix, plan) {
  // The forward filters' half vector: in the fed normal's frame (the papers' wrappers), or in view
  // space with that frame, whose turn about the normal from pixel to pixel the transported
  // wrappers leave out (docs/FORWARD_DERIVATIVES.md).
  const half = plan.wrapper.endsWith('_transported_fragment')
    ? 'normalize(l + v), saagenFeedNormal, saagenFeedTangent(), cross(saagenFeedNormal, saagenFeedTangent())'
    : 'saagenFeedHalf(l, v)';
  // The deferred forms' lobe: split per pixel and per light where the plan names the pair (more
  // than one light), else in one pass (perPixelGlsl computes the split's per-pixel part).
  const specular = {
    roughness: plan.split
      ? `return ${prefix}ggx_brdf_filtered_lobe(i, o, saagenFiltered, saagenAlpha2, saagenLobe);`
      : `return ${prefix}ggx_brdf_filtered_axis(i, o, vec2(saagenFiltered), vec2(saagenAlpha2));`,
    tensor: plan.split
      ? `return ${prefix}deferred_aniso_brdf_lobe(l, v, saagenFeedNormal, saagenTensor, saagenAlpha2, saagenLobe);`
      : `return ${prefix}deferred_aniso_brdf(l, v, saagenFeedNormal, saagenTensor, saagenAlpha2);`,
    matrix: `highp vec3 a = ${prefix}${plan.wrapper}(vec2(saagenAlpha2), ${half});
  return ${prefix}ggx_brdf_filtered_matrix(i, o, a, vec2(saagenAlpha2));`,
    axis: `highp vec2 a = ${prefix}${plan.wrapper}(vec2(saagenAlpha2), ${half});
  return ${prefix}ggx_brdf_filtered_axis(i, o, a, vec2(saagenAlpha2));`,
  }[kind];
  return `
highp float saagenAlpha2;      // the material's own alpha^2 (three.js: r^4)
highp float saagenFiltered;    // a tangent-free filter's alpha^2
highp vec4 saagenLobe;         // a deferred form's lobe, its light-independent part, once per pixel
highp vec3 saagenTensor;       // deferred-aniso's kernel tensor (Kxx, Kxy, Kyy)
highp vec3 saagenFeedNormal;   // the normal the filter read
void saagenFrame(highp vec3 n, out highp vec3 t, out highp vec3 b) {
  highp float s = n.z >= 0.0 ? 1.0 : -1.0;
  highp float a = -1.0 / (s + n.z);
  highp float c = n.x * n.y * a;
  t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
  b = vec3(c, s + n.y * n.y * a, -n.y);
}
// The half vector in the frame of the normal the filter is fed.
highp vec3 saagenFeedHalf(highp vec3 l, highp vec3 v) {
  highp vec3 t, b;
  saagenFrame(saagenFeedNormal, t, b);
  highp vec3 h = normalize(l + v);
  return vec3(dot(h, t), dot(h, b), dot(h, saagenFeedNormal));
}
// That frame's tangent (its bitangent is n x t).
highp vec3 saagenFeedTangent() {
  highp vec3 t, b;
  saagenFrame(saagenFeedNormal, t, b);
  return t;
}
highp float saagenSpecular(highp vec3 l, highp vec3 v, highp vec3 n) {
  highp vec3 t, b;
  saagenFrame(n, t, b);
  highp vec3 i = vec3(dot(l, t), dot(l, b), dot(l, n)), o = vec3(dot(v, t), dot(v, b), dot(v, n));
  ${specular}
}
`;
}

// The lines that replace three.js's geometric roughness term in lights_physical_fragment, per kind.
function perPixelGlsl(plan, prefix) {
  const { kind, wrapper, normal } = plan;
  const own = `saagenFeedNormal = ${normal};
saagenAlpha2 = pow2(pow2(material.roughness));`;
  if (kind === 'tensor') {
    const lobe = plan.split ? `\nsaagenLobe = ${prefix}deferred_aniso_lobe(saagenTensor, saagenAlpha2);` : '';
    return `${own}\nsaagenTensor = ${prefix}${wrapper}(${normal});${lobe}`;
  }
  if (kind === 'roughness') {
    const lobe = plan.split ? `\nsaagenLobe = ${prefix}ggx_filtered_lobe_isotropic(saagenFiltered, saagenAlpha2);` : '';
    return `${own}\nsaagenFiltered = ${prefix}${wrapper}(saagenAlpha2, ${normal});${lobe}
material.roughness = sqrt(sqrt(saagenFiltered));`;
  }
  return own;  // matrix, axis: per light, in saagenSpecular
}

// three.js's BRDF_GGX with its V * D replaced by saagenSpecular.
function patchedBrdf(pars) {
  const head = pars.indexOf(BRDF_GGX_HEAD);
  const ret = head < 0 ? -1 : pars.indexOf(BRDF_GGX_RETURN, head);
  if (ret < 0) throw new Error(`saagen-three: three.js r${THREE.REVISION} has no '${BRDF_GGX_RETURN}' in BRDF_GGX; this module needs updating`);
  return pars.slice(0, ret) + 'return F * saagenSpecular( lightDir, viewDir, normal );' + pars.slice(ret + BRDF_GGX_RETURN.length);
}

// How the plan's entry is installed: { kind, wrapper, tail, normal, bias, split }, or throws saying why not.
function planKind(entry) {
  if (entry.variant === 'none') return { kind: 'none' };
  const wrapper = entry.wrapper;
  const kind = PLAN_WRAPPERS[wrapper];
  if (!kind) throw new Error(`saagen-three: the plan's wrapper '${wrapper}' is not one of ${Object.keys(PLAN_WRAPPERS).join(', ')}`);
  const tail = typeof entry.brdf === 'string' && (entry.brdf.startsWith('ggx_brdf_filtered_') || entry.brdf.startsWith('deferred_aniso_brdf'));
  if (kind !== 'roughness' && !tail) {
    throw new Error(`saagen-three: ${entry.variant} without the tail-preserving lobe (brdf ${entry.brdf}) needs a matrix BRDF three.js does not have`);
  }
  if (entry.prefilter !== 'none' && kind !== 'roughness') {
    throw new Error(`saagen-three: ${entry.variant} with the ${entry.prefilter} bake (a texture covariance) is not installable by this module; plan it with a tangent-free variant`);
  }
  const normal = entry.feed === 'shading' ? 'normal' : 'nonPerturbedNormal';
  // The plan names a deferred form's lobe split per pixel and per light from 4 lights on.
  const split = entry.brdf === 'ggx_brdf_filtered_lobe' || entry.brdf === 'deferred_aniso_brdf_lobe';
  return { kind, wrapper, tail, normal, bias: entry.prefilter !== 'none', split };
}

// Installs one material's plan entry. Options: snippet, the bundle's text (gles, with the
// entry's functions); clearcoat, 'none' (default: saagen's advice for clearcoat content is no
// filter) or a tangent-free wrapper name for the coat's roughness.
export function installPlan(material, entry, { snippet = '', clearcoat = 'none' } = {}) {
  const plan = planKind(entry);
  if (plan.kind === 'none') return installSaagen(material, { filter: false });
  const prefix = snippetPrefix(snippet);
  for (const name of entry.functions ?? [plan.wrapper]) {
    if (!snippet.includes(`${prefix}${name}(`)) throw new Error(`saagen-three: the snippet defines no ${prefix}${name}; emit the manifest's bundle`);
  }
  if (!plan.tail) {
    // The roughness filter alone, with three.js's own GGX.
    return installSaagen(material, { snippet, wrapper: plan.wrapper, normal: plan.normal === 'normal' ? 'shading' : 'geometric',
                                     bake: plan.bias, clearcoat: clearcoat !== 'none' });
  }
  const key = `saagen-plan|${prefix}|${plan.kind}|${plan.wrapper}|${plan.normal}|${plan.bias}|${clearcoat}|${fingerprint(snippet)}`;
  material.onBeforeCompile = (shader) => {
    const head = snippet + lobeGlsl(plan.kind, prefix, plan) + (clearcoat !== 'none' ? roughnessFilter(prefix + clearcoat) : '');
    const shipped = THREE.ShaderChunk.lights_physical_fragment;
    const lights = plan.bias ? biasedChunk('lights_physical_fragment', shipped) : shipped;
    for (const line of [ROUGHNESS_LINE, CLEARCOAT_LINE]) {
      if (!lights.includes(line)) throw new Error(`saagen-three: three.js r${THREE.REVISION} has no '${line}' in lights_physical_fragment; this module needs updating`);
    }
    const coat = clearcoat !== 'none' ? `material.clearcoatRoughness = saagenFilterRoughness(material.clearcoatRoughness, ${NORMALS.geometric[1]});` : '';
    const chunk = lights.replace(ROUGHNESS_LINE, perPixelGlsl(plan, prefix)).replace(CLEARCOAT_LINE, coat);
    const fragment = plan.bias ? withBiasedReads(shader.fragmentShader) : shader.fragmentShader;
    shader.fragmentShader = head + fragment
      .replace('#include <lights_physical_pars_fragment>', patchedBrdf(THREE.ShaderChunk.lights_physical_pars_fragment))
      .replace('#include <lights_physical_fragment>', chunk);
  };
  material.customProgramCacheKey = () => key;
  material.needsUpdate = true;
  return material;
}

// The plan's entry for a material name (`saagen plan --json` output, parsed).
export function planEntry(plan, name) {
  const entry = (plan.materials ?? []).find((m) => m.material === name);
  if (!entry) throw new Error(`saagen-three: the plan has no material '${name}'`);
  return entry;
}
