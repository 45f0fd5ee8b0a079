// saagen ground-truth renderer (`saagen::render`): everything.
#pragma once

#include "saagen/reference/render/gltf.hpp"
#include "saagen/reference/render/height_field.hpp"
#include "saagen/reference/render/image.hpp"
#include "saagen/reference/render/mesh.hpp"
#include "saagen/reference/render/normal_map.hpp"
#include "saagen/reference/render/parallel.hpp"
#include "saagen/reference/render/renderer.hpp"
#include "saagen/reference/render/sampling.hpp"
#include "saagen/reference/render/scalar_map.hpp"
#include "saagen/reference/render/scene.hpp"
#include "saagen/reference/render/trade.hpp"
