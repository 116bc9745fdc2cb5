/* The start of a record of the light-reading effects (lit_record.h). */
#include "effects/lit_record.h"

#include "effects/light_data.h"
#include "roma_shared.h"
#include "util/log.h"

roma_result roma_lit_record_check(const roma_image_effect *e, const char *name, VkCommandBuffer cmd,
                                  const roma_map *map, const roma_light_images *im, const roma_light *lights,
                                  uint32_t light_count)
{
    const roma_logger *log = e ? &e->logger : NULL;
    if (!e || !cmd || !map || !im || (light_count && !lights))
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "%s: %s is NULL", name,
                         !e ? "effect" : !cmd ? "cmd" : !map ? "map" : !im ? "images" : "lights");
    if (!im->width || !im->height || !im->position || !im->normal || !im->output)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "%s: width, height, position, normal and output are required", name);
    roma_result r = roma_image_effect_check_size(e, name, im->width, im->height);
    if (r != ROMA_SUCCESS)
        return r;
    if (light_count > ROMA_LIT_MAX_LIGHTS)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "%s: %u lights, at most %u", name, light_count,
                         ROMA_LIT_MAX_LIGHTS);
    for (uint32_t i = 0; i < light_count; ++i)
        if (!roma_light_valid(&lights[i]))
            return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                             "%s: light %u has an unknown type or a NaN or infinite value", name, i);
    return ROMA_SUCCESS;
}

roma_result roma_lit_record_begin(roma_image_effect *e, const char *name, uint32_t slot, uint32_t frame,
                                  const roma_map *map, const roma_light_images *im, uint32_t resolution_divisor,
                                  roma_map_info *info)
{
    roma_result r = roma_image_effect_begin(e, slot, frame, map, im->pixels, im->width, im->height,
                                            resolution_divisor, info);
    if (r != ROMA_SUCCESS)
        return r;
    /* The lights live in one buffer per slot: a second record in the slot's frame would
     * overwrite what the first one's dispatch reads. */
    if (roma_image_effect_same_frame(e, slot))
        return roma_fail(&e->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "%s: one record per frame slot (slot %u was recorded this frame)", name, slot);
    return ROMA_SUCCESS;
}

roma_result roma_lit_slot_buffer(roma_context *ctx, roma_upload *buf, VkDeviceSize bytes)
{
    if (buf->device.size >= bytes)
        return ROMA_SUCCESS;
    roma_upload_destroy(ctx, buf);
    return roma_upload_create(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                              buf);
}

roma_result roma_lit_record_pack(roma_context *ctx, roma_upload *buf, const roma_light *lights, uint32_t light_count,
                                 uint32_t exact_count, uint32_t *out_packed, uint32_t *out_exact)
{
    VkDeviceSize bytes = sizeof(roma_gpu_light) * (VkDeviceSize)(light_count ? light_count : 1);
    roma_result r = roma_lit_slot_buffer(ctx, buf, bytes);
    if (r != ROMA_SUCCESS)
        return r;
    uint32_t packed = 0, exact = 0;
    roma_gpu_light *dst = roma_upload_write(buf, bytes);
    for (uint32_t i = 0; i < light_count; ++i) {
        packed += (uint32_t)roma_light_pack(&lights[i], dst + packed);
        if (i + 1 == exact_count)
            exact = packed;
    }
    *out_packed = packed;
    *out_exact = exact_count > light_count ? packed : exact;
    return ROMA_SUCCESS;
}
