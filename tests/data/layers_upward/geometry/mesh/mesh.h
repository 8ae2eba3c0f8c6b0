#pragma once
// A deliberate upward include: the layer check must refuse it (tests/CMakeLists.txt).
#include "planner/plan/plan.h"
