// saagen reference: everything (double-precision re-implementation of templates/*.saa).
#pragma once

#include "saagen/reference/brdf.hpp"
#include "saagen/reference/jacobian.hpp"
#include "saagen/reference/math.hpp"
#include "saagen/reference/prefilter.hpp"
#include "saagen/reference/quad.hpp"
#include "saagen/reference/saa.hpp"
