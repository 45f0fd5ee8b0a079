// The short names the precision test and the stability properties write their inputs and
// references in, declared once: each brings them in with
// `using namespace saagen::stability::short_names;` inside its anonymous namespace.
#pragma once

#include "saagen/front/catalogue.hpp"
#include "saagen/reference/quad.hpp"
#include "saagen/reference/reference.hpp"

namespace saagen::stability::short_names {

namespace ref = saagen::ref;
namespace stab = saagen::stability;
using ref::Quad;
using ref::Sym2;
using ref::Vec2;
using ref::Vec3;
using saagen::Catalogue;
using saagen::Function;

}  // namespace saagen::stability::short_names
