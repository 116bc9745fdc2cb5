/* The tests' converged ROMA images through the public effect passes, as roma-render records
 * them (apps/common/effect_api.h), and the G-buffer they were shaded at (the reference's
 * primary rays through the pixel centres), for the Embree side at the same points. */
#ifndef ROMA_TEST_PUBLIC_RENDER_H
#define ROMA_TEST_PUBLIC_RENDER_H

#include "effect_api.h"
#include "roma_shared.h"

/* out_px (may be NULL): width * height pixels; position_t.w the distance from the eye, +INF
 * where the pixel sees nothing (then the rest is zero); albedo.w the bits of the triangle's
 * index. */
roma_result roma_test_public_render(roma_context *ctx, const roma_scene *scene, const roma_ref *ref,
                                    const effect_api_desc *desc, effect_api_result *out, roma_gbuffer_pixel *out_px);

#endif /* ROMA_TEST_PUBLIC_RENDER_H */
