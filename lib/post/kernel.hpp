#pragma once
// The coarse-graining kernel lives in core/lucy_kernel.hpp: the fluid's local void fraction
// (forces/void_fraction.hpp) weighs the grains with it too.
#include "core/lucy_kernel.hpp"
