#pragma once
// The call forms of the filters' fragment-wrapper references (<identifier>_fragment_quad,
// saa.hpp), told apart by the quads each reads, so that the renderer's rows and the tests'
// dispatch pick a wrapper's form from its signature (overload resolution, default arguments
// included) instead of keeping a list of which filter has which form.

#include "saagen/reference/saa.hpp"

#include <type_traits>

// A reference function saagen::ref::function as a callable object, so that the forms below (and
// the tests' forms of the core functions) can ask which arguments it takes.
#define SAAGEN_REFERENCE_CALLABLE(function) \
  [](const auto&... args) -> decltype(::saagen::ref::function(args...)) { return ::saagen::ref::function(args...); }

namespace saagen::ref::wrapper_forms {

using QuadOfVectors = const Quad<Vec3>&;

// The unfiltered roughness per axis and the half vectors (forward-*).
template <class Wrapper>
constexpr bool reads_half_vectors = std::is_invocable_v<Wrapper, const Params&, Vec2, QuadOfVectors, int, Derivative>;
// What such a wrapper returns: a roughness matrix (Sym2, forward-aniso-*) or per axis (Vec2).
template <class Wrapper>
using half_vector_result_t = std::invoke_result_t<Wrapper, const Params&, Vec2, QuadOfVectors, int, Derivative>;

// The unfiltered roughness per axis, the world-space half vectors and the normal, tangent and
// bitangent (forward-*-projected in transported frames: *_transported_fragment_quad).
template <class Wrapper>
constexpr bool reads_half_vectors_in_frames =
    std::is_invocable_v<Wrapper, const Params&, Vec2, QuadOfVectors, QuadOfVectors, QuadOfVectors, QuadOfVectors, int, Derivative>;
template <class Wrapper>
using half_vector_in_frames_result_t =
    std::invoke_result_t<Wrapper, const Params&, Vec2, QuadOfVectors, QuadOfVectors, QuadOfVectors, QuadOfVectors, int, Derivative>;

// alpha^2 and the normal, tangent, bitangent and fragment coordinates (a quad-average normal's
// frame: deferred-previous, deferred-max); the average's own derivative mode may follow.
template <class Wrapper>
constexpr bool reads_normal_frame =
    std::is_invocable_v<Wrapper, const Params&, double, QuadOfVectors, QuadOfVectors, QuadOfVectors, const Quad<Vec2>&, int, Derivative>;

// alpha^2 and the normals (the other isotropic deferred-*).
template <class Wrapper>
constexpr bool reads_normals = std::is_invocable_v<Wrapper, const Params&, double, QuadOfVectors, int, Derivative>;

// The normals alone (deferred-aniso's tensor, which knows no alpha^2).
template <class Wrapper>
constexpr bool reads_normals_alone = std::is_invocable_v<Wrapper, const Params&, QuadOfVectors, int, Derivative>;

}  // namespace saagen::ref::wrapper_forms
