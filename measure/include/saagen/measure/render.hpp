// saagen measurement wing (`saagen::measure`): everything.
#pragma once

#include "saagen/measure/gltf.hpp"
#include "saagen/measure/height_field.hpp"
#include "saagen/measure/image.hpp"
#include "saagen/measure/mesh.hpp"
#include "saagen/measure/normal_map.hpp"
#include "saagen/measure/parallel.hpp"
#include "saagen/measure/renderer.hpp"
#include "saagen/measure/sampling.hpp"
#include "saagen/measure/scalar_map.hpp"
#include "saagen/measure/scene.hpp"
#include "saagen/measure/trade.hpp"
