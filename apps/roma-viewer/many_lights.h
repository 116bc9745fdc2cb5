// roma-viewer: the many-lights demo: synthetic point lights spread through the scene's
// bounds, added to the direct light (roma_light_effect, which samples a few of them per
// pixel and frame: roma_light_settings.lights_per_frame).
#pragma once

#include <roma/scene.h>

#include <cstdint>
#include <vector>

// `count` point lights at hashed positions inside the middle 80% of the box, each a
// saturated colour, with intensities that sum to the same total for any count (so the
// picture keeps its brightness when the count changes). Deterministic.
std::vector<roma_light> make_many_lights(const float bounds_min[3], const float bounds_max[3], uint32_t count);
