// Fixture for the layer check (tests/CMakeLists.txt): device data including the frame loop.
#pragma once
#include "render/renderer.h"
