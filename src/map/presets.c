/* Quality presets (roma/presets.h): the ROMA settings on the measured front of AO error
 * against time on the built-in room (docs/bench/cornell_accuracy.txt). */
#include "roma/presets.h"

#include <ctype.h>
#include <stddef.h>

static const struct {
    const char *name;
    uint32_t resolution, angular;
} presets[ROMA_PRESET_COUNT + 1] = {
    [ROMA_PRESET_DEFAULT] = {"medium", 128, 4}, [ROMA_PRESET_LOW] = {"low", 128, 2},
    [ROMA_PRESET_MEDIUM] = {"medium", 128, 4},  [ROMA_PRESET_HIGH] = {"high", 256, 4},
    [ROMA_PRESET_ULTRA] = {"ultra", 256, 8},
};

/* ASCII case-insensitive equality (strcasecmp is POSIX, not C11). */
static int same_name(const char *a, const char *b)
{
    for (; *a && *b; ++a, ++b)
        if (tolower((unsigned char)*a) != tolower((unsigned char)*b))
            return 0;
    return *a == *b;
}

static int known(roma_preset p)
{
    return (unsigned)p <= ROMA_PRESET_COUNT;
}

roma_result roma_preset_map_settings(roma_preset preset, uint32_t *resolution, uint32_t *angular)
{
    if (!known(preset))
        return ROMA_ERROR_INVALID_ARGUMENT;
    if (resolution)
        *resolution = presets[preset].resolution;
    if (angular)
        *angular = presets[preset].angular;
    return ROMA_SUCCESS;
}

const char *roma_preset_name(roma_preset preset)
{
    return known(preset) ? presets[preset].name : NULL;
}

roma_result roma_preset_parse(const char *name, roma_preset *out)
{
    if (!name || !out)
        return ROMA_ERROR_INVALID_ARGUMENT;
    for (unsigned p = ROMA_PRESET_LOW; p <= ROMA_PRESET_COUNT; ++p)
        if (same_name(name, presets[p].name)) {
            *out = (roma_preset)p;
            return ROMA_SUCCESS;
        }
    return ROMA_ERROR_INVALID_ARGUMENT;
}
