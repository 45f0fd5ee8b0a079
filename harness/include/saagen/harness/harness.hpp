// Umbrella header for the saagen Vulkan harness.
#pragma once

#include <saagen/harness/bytes.hpp>
#include <saagen/harness/compare.hpp>
#include <saagen/harness/context.hpp>
#include <saagen/harness/description.hpp>
#include <saagen/harness/error.hpp>
#include <saagen/harness/program.hpp>
#include <saagen/harness/shader.hpp>
