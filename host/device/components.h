// The igi family's components (docs/igi.md §1: soft shadows, indirect diffuse, participating
// media, and the AIS edge samples) as the host names them: one table for --components'
// parser and printer (integrators/method.cpp) and for the messages that say a component
// computes nothing on a scene (device/effect_plan.cpp), so the names cannot drift apart.
#pragma once
#include <cstdint>

#include "kernels/shared/layout_igi.h"

namespace tessera {

/// A component's TS_COMPONENT_* bit (kernels/shared/layout_igi.h) and its names.
struct ComponentName {
    uint32_t bit;
    const char* option;  ///< --components' name, e.g. "ss"
    const char* label;   ///< the name docs and the viewer's HUD use, e.g. "SS"
    const char* key;     ///< the viewer's toggle (docs/viewer.md), e.g. "SS (1)"
};

/// Every component, in --components order (the order components_text lists them).
inline constexpr ComponentName kComponentNames[] = {{TS_COMPONENT_SS, "ss", "SS", "SS (1)"},
                                                    {TS_COMPONENT_ID, "id", "ID", "ID (2)"},
                                                    {TS_COMPONENT_PM, "pm", "PM", "PM (3)"},
                                                    {TS_COMPONENT_EDGE, "edge", "edge", "edge (4)"}};

}  // namespace tessera
