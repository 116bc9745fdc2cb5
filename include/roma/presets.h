/** @file
 * libroma: named quality presets, the RES and A of a map chosen from the measured front of
 * accuracy against time (docs/accuracy-vs-time.md, "Presets").
 *
 * Measured on ambient occlusion of the built-in room (roma-bench --accuracy): the settings
 * of ROMA that no other ROMA setting beats in both time and error, from the fastest to the
 * most accurate. Left out: RES 64, on that front only at its fast end, 1-4.5 ms faster than
 * low (within the measuring machine's spread) for 60-77% more error, and RES 128 at A 8,
 * between medium and high (high costs 10% more time for 27% less error). A preset sets what a
 * desc leaves at 0: roma_map_desc.resolution and .angular, roma_effect_options.resolution,
 * .ao_angular and .gi_angular (the rays that are snapped); shadow rays keep A = 8.
 * The functions are pure (no state): any thread. */
#ifndef ROMA_PRESETS_H
#define ROMA_PRESETS_H

#include "roma/api.h"

#include <stdint.h>

#include "roma/result.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Quality presets, from the fastest to the most accurate. The zero value is the default. */
typedef enum roma_preset {
    ROMA_PRESET_DEFAULT = 0, /**< the same as ROMA_PRESET_MEDIUM */
    ROMA_PRESET_LOW = 1,     /**< RES 128, A 2 */
    ROMA_PRESET_MEDIUM = 2,  /**< RES 128, A 4: libroma's defaults */
    ROMA_PRESET_HIGH = 3,    /**< RES 256, A 4 */
    ROMA_PRESET_ULTRA = 4,   /**< RES 256, A 8 */
} roma_preset;

/** Number of named presets (LOW .. ULTRA). */
#define ROMA_PRESET_COUNT 4u

/** RES and A of a preset.
 *
 * @param preset            a roma_preset.
 * @param[out] resolution   RES; may be NULL.
 * @param[out] angular      A (A x A maps); may be NULL.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a value outside the enum (the
 *         outputs are then left unchanged). */
ROMA_API roma_result roma_preset_map_settings(roma_preset preset, uint32_t *resolution, uint32_t *angular);

/** The name of a preset.
 *
 * @param preset  a roma_preset.
 * @return "low", "medium", "high" or "ultra" ("medium" for ROMA_PRESET_DEFAULT), static
 *         storage; NULL for a value outside the enum. */
ROMA_API const char *roma_preset_name(roma_preset preset);

/** The preset of a name roma_preset_name gives (case-insensitive).
 *
 * @param name      the name.
 * @param[out] out  the preset.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for NULL arguments or an unknown name
 *         (*out is then left unchanged). */
ROMA_API roma_result roma_preset_parse(const char *name, roma_preset *out);

#ifdef __cplusplus
}
#endif

#endif /* ROMA_PRESETS_H */
