#pragma once
// The named classical tableaus, one file each under integrators/methods/.
// Adding one is a file there (and its include here) plus a registry line.
#include "integrators/methods/euler.hpp"
#include "integrators/methods/heun.hpp"
#include "integrators/methods/kutta3.hpp"
#include "integrators/methods/rk4.hpp"
#include "integrators/methods/rk38.hpp"
