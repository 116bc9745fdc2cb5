// roma-viewer: the many-lights demo's lights (see many_lights.h).
#include "many_lights.h"

#include <cmath>

#include <roma/sampling.h>

namespace {

// A well-mixed hash of x mapped to [0, 1): libroma's own (roma/sampling.h).
float unit_hash(uint32_t x)
{
    return roma_u32_to_unit_float(roma_hash_u32(x));
}

} // namespace

std::vector<roma_light> make_many_lights(const float bounds_min[3], const float bounds_max[3], uint32_t count)
{
    std::vector<roma_light> lights(count);
    float diagonal2 = 0.0f;
    for (int a = 0; a < 3; ++a)
        diagonal2 += (bounds_max[a] - bounds_min[a]) * (bounds_max[a] - bounds_min[a]);
    for (uint32_t i = 0; i < count; ++i) {
        roma_light &l = lights[i];
        l = roma_light{};
        l.type = ROMA_LIGHT_POINT;
        for (int a = 0; a < 3; ++a) {
            float u = unit_hash(i * 3u + uint32_t(a) + 0x9e3779b9u);
            l.position[a] = bounds_min[a] + (bounds_max[a] - bounds_min[a]) * (0.1f + 0.8f * u);
        }
        // A hue around the colour wheel, full saturation (r, g, b from three phase-shifted cosines).
        float hue = unit_hash(i + 0x51ed270bu) * 6.2831853f;
        for (int c = 0; c < 3; ++c)
            l.color[c] = 0.5f + 0.5f * std::cos(hue - 2.0943951f * float(c));
        // In total as bright as a 0.3 cd light per square unit of the scene's diagonal: the
        // built-in room reads well at the default exposure.
        l.intensity = 0.3f * diagonal2 / float(count);
    }
    return lights;
}
