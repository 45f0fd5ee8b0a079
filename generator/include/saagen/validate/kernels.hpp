// Kernels: shaders that run emitted functions over buffers, for the GPU harness (comparisons
// with the CPU reference, stability sweeps, timings). A kernel is the emitted file plus a
// target skeleton plus a body written in the template dialect, so one body serves every target.
//
// In a body:
//   SAAGEN_LOAD(i)      the i-th float of this element's input (compute), or of the whole input
//                       buffer (fragment, quad_compute: parameters shared by all pixels)
//   SAAGEN_STORE(i, v)  writes float v as the i-th output of this element (pixel)
//   saagen_index        the element (compute) or pixel (y * width + x) index
//   saagen_frag_coord   the pixel centre (fragment and quad_compute kernels)
// Bindings: input floats at (set 0, binding 0), output floats at (set 0, binding 1).
#pragma once

#include "saagen/emit/emitter.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/print/glue.hpp"
#include "saagen/validate/compiler.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace saagen {

enum class KernelKind {
  compute,       // core functions only (the file is included under <PREFIX>CORE_ONLY)
  quad_compute,  // compute emulating 2x2 quads with subgroup quad operations: the fragment
                 // wrappers run unchanged, their derivative intrinsics redirected by macros
  fragment,      // a fragment shader over a full-screen triangle: real ddx/ddy
};

// What a plain ddx/ddy (dFdx/dFdy) means in a quad_compute kernel. Vulkan lets the driver pick.
enum class PlainDerivative { coarse, fine };

struct KernelRequest {
  KernelKind kind = KernelKind::compute;
  std::string body;                 // dialect statements
  std::uint32_t input_stride = 0;   // floats per element (compute kinds)
  std::uint32_t output_stride = 0;  // floats per element / pixel
  std::uint32_t width = 0;          // framebuffer / emulated image width in pixels (even)
  std::uint32_t workgroup_size = 64;
  PlainDerivative plain_derivative = PlainDerivative::coarse;
  // Also for the other kinds: the emitted file's plain ddx/ddy calls are spelt as
  // plain_derivative's (a target without macros, WGSL, cannot redirect them in the skeleton).
  bool redirect_plain_derivatives = false;
};

// Source pieces for compile_to_spirv: skeleton prologue, the emitted file, skeleton epilogue
// with the body printed from its typed tree (saagen/print/glue.hpp). `content` must carry a saagen marker (it names target and prefix).
std::vector<SourcePiece> kernel_sources(const Catalogue& catalogue, const std::string& file_name, const std::string& content,
                                        const KernelRequest& request);

// The complete compile request for a kernel: language, stage and 16-bit settings from the
// file's marker, and kernel_sources().
CompileRequest kernel_compile_request(const Catalogue& catalogue, const std::string& file_name, const std::string& content,
                                      const KernelRequest& request);

// A body that loads every parameter of `function` from the input (in declaration order, each
// vector component by component), calls it, and stores every component of the result. Sets
// the request's strides.
std::string load_call_store_body(const Catalogue& catalogue, const std::string& function_name, KernelRequest& request);

// The symbols of the kernel skeletons: SAAGEN_LOAD, SAAGEN_STORE, saagen_index, saagen_frag_coord.
const GlueSymbols& kernel_glue_symbols();

// Number of floats in a dialect type (real3 -> 3).
std::uint32_t component_count(const std::string& dialect_type);

}  // namespace saagen
