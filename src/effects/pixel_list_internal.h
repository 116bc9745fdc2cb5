/* What the effects read of a roma_pixel_list (roma/pixel_list.h): the buffer of a slot's
 * list, a roma_pixel_list_header (the indirect dispatch's arguments) and the pixels
 * ((y << 16) | x). */
#ifndef ROMA_EFFECTS_PIXEL_LIST_INTERNAL_H
#define ROMA_EFFECTS_PIXEL_LIST_INTERNAL_H

#include "roma/pixel_list.h"
#include "vulkan/vk_internal.h"

/* The slot's list when it was made on ctx and recorded for images of width x height; else
 * fails, logged on the effect's logger under name (the effect's record). */
roma_result roma_pixel_list_slot_buffer(const roma_pixel_list *list, const roma_context *ctx, const roma_logger *log,
                                        const char *name, uint32_t slot, uint32_t width, uint32_t height,
                                        VkBuffer *out);

#endif /* ROMA_EFFECTS_PIXEL_LIST_INTERNAL_H */
