/* Helpers shared by the command-line tools and the viewer. */
#ifndef ROMA_APP_COMMON_H
#define ROMA_APP_COMMON_H

#include "roma/image.h"
#include "roma/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum roma_png_mode {
    ROMA_PNG_SRGB = 0, /* linear values times exposure, clamped, sRGB-encoded */
    ROMA_PNG_HEAT      /* values / scale through a black-red-yellow-white ramp */
} roma_png_mode;

/* Writes an 8-bit PNG of a 1- or 3-channel float image. scale: exposure for
 * ROMA_PNG_SRGB, the value shown as white for ROMA_PNG_HEAT. */
roma_result roma_app_write_png(const roma_image *image, const char *path, roma_png_mode mode,
                               float scale);

/* OpenEXR (32-bit float, ZIP): one channel as Y, three as R, G, B (exr_io.c). */
roma_result roma_app_write_exr(const roma_image *image, const char *path);
/* Reads a scanline EXR's Y channel, or its R, G, B channels, as float. */
roma_result roma_app_read_exr(const char *path, roma_image *out);
/* Reads .exr with roma_app_read_exr, anything else as PFM. */
roma_result roma_app_read_image(const char *path, roma_image *out);

/* "builtin:NAME" (or "builtin" for the default) or a .gltf/.glb path (camera_index: which of
 * its perspective cameras, roma_gltf_desc.camera_index). A missing file, a
 * directory, or another format is refused with the cause on stderr (and a near built-in
 * name suggested). */
roma_result roma_app_load_scene(const char *arg, const roma_logger *logger, uint32_t camera_index,
                                roma_scene **out_scene);

/* Monotonic wall clock in milliseconds. */
double roma_app_now_ms(void);
/* Median of count values (sorts them in place); 0 for none. */
double roma_app_median(double *values, int count);

/* --up +y|-y|+z: a copy of scene turned so that the given axis points up (+y). Animation
 * data is not kept (turn a posed copy). ROMA_ERROR_INVALID_ARGUMENT for another value. */
roma_result roma_app_reorient(const roma_scene *scene, const char *up, roma_scene **out);
int roma_app_valid_up(const char *up);

/* The name in names (NULL-terminated) closest to typed, or NULL when none is close. */
const char *roma_app_suggest(const char *typed, const char *const *names);

/* The finest cascade level's edge where none is given: ROMA_APP_FINEST_CELLS cells of RES
 * to the AO radius (of 25, 30, 32, 35 and 40, the one whose largest AO error on the shared game
 * levels is lowest: docs/accuracy.md, "Game levels"); 0 (the library's default) for a radius
 * that is not finite and positive. */
#define ROMA_APP_FINEST_CELLS 30
float roma_app_finest_extent(uint32_t res, float ao_radius);

/* Cascade levels for AO of radius ao_radius in a scene of bounds [bounds_min, bounds_max] seen
 * from eye (NULL: unknown), maps of RES res: the finest level finest_extent wide (0:
 * roma_app_finest_extent; written to *finest), enough levels, each twice the last, to cover the
 * scene's longest edge, at most ROMA_MAX_LEVELS. 1 (one grid over the scene) unless the level
 * that holds the scene's part nearest the camera (the finest for a camera inside the box) has
 * cells at least twice as fine as one grid's, or where the radius is not finite and positive;
 * without an eye, unless the scene is wider than four finest levels. */
uint32_t roma_app_auto_cascades(const float bounds_min[3], const float bounds_max[3], const float *eye, uint32_t res,
                                float ao_radius, float finest_extent, float *finest);

/* The most cascade levels a map of RES res and A angular can have on a device whose storage
 * buffers hold max_storage_range bytes (maxStorageBufferRange: roma_map_create refuses maps
 * larger than one buffer) and within 256 maps; 0 when not even one level fits. */
uint32_t roma_app_levels_that_fit(uint32_t res, uint32_t angular, uint64_t max_storage_range);

/* Creates the folder (and parents) if needed; 0 on failure, with errno set. */
int roma_app_make_dir(const char *path);

#ifdef __cplusplus
}
#endif

#endif /* ROMA_APP_COMMON_H */
