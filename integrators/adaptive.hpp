#pragma once
// The adaptive loop is part of the one driver (integrators/driver.hpp).
#include "integrators/driver.hpp"
