#include "effects/light_data.h"

#include <math.h>
#include <string.h>

#include "roma_shared.h"
#include "scene/emitters.h"

#define PI_F 3.14159265358979323846f

int roma_light_valid(const roma_light *l)
{
    const float v[] = {l->position[0], l->position[1], l->position[2], l->direction[0], l->direction[1],
                       l->direction[2], l->color[0], l->color[1], l->color[2], l->intensity, l->range,
                       l->inner_cone_angle, l->outer_cone_angle};
    for (size_t i = 0; i < sizeof v / sizeof v[0]; ++i)
        if (!isfinite(v[i]))
            return 0;
    return l->type >= ROMA_LIGHT_POINT && l->type <= ROMA_LIGHT_DIRECTIONAL;
}

/* The reference's expressions (src/reference/estimators.c), evaluated once here. */
int roma_light_pack(const roma_light *l, roma_gpu_light *out)
{
    memset(out, 0, sizeof *out);
    if (!(l->intensity > 0.0f) || !(l->color[0] > 0.0f || l->color[1] > 0.0f || l->color[2] > 0.0f))
        return 0;
    float d[3] = {l->direction[0], l->direction[1], l->direction[2]};
    float len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (l->type != ROMA_LIGHT_POINT) {
        if (!(len > 0.0f) || !isfinite(len))
            return 0;
        for (int k = 0; k < 3; ++k)
            d[k] *= 1.0f / len;
    }
    uint32_t type = l->type == ROMA_LIGHT_SPOT ? ROMA_GPU_LIGHT_SPOT
                    : l->type == ROMA_LIGHT_DIRECTIONAL ? ROMA_GPU_LIGHT_DIRECTIONAL
                                                         : ROMA_GPU_LIGHT_POINT;
    for (int k = 0; k < 3; ++k) {
        out->position_type[k] = l->position[k];
        out->direction_range[k] = d[k];
        out->color_intensity[k] = l->color[k];
    }
    out->position_type[3] = (float)type;
    out->direction_range[3] = l->range;
    out->color_intensity[3] = l->intensity;
    if (type == ROMA_GPU_LIGHT_SPOT) {
        float outer = l->outer_cone_angle > 0.0f ? l->outer_cone_angle : PI_F / 4.0f;
        float cos_outer = cosf(outer), cos_inner = cosf(l->inner_cone_angle);
        float s = 1.0f / fmaxf(0.001f, cos_inner - cos_outer);
        out->cone[0] = s;
        out->cone[1] = -cos_outer * s;
    }
    return 1;
}

roma_result roma_light_data_create(roma_context *ctx, const roma_scene *scene, const roma_logger *log,
                                   roma_light_data *out)
{
    memset(out, 0, sizeof *out);
    roma_scene_view v;
    roma_result r = roma_scene_get_view(scene, &v);
    if (r != ROMA_SUCCESS)
        return r;
    roma_emitter_table table;
    r = roma_emitter_table_build(&v, log, &table);
    if (r != ROMA_SUCCESS || table.count == 0) {
        roma_emitter_table_free(&table);
        return r;
    }
    /* Read at every light sample: device-local memory (vulkan/upload.h). */
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    const VkDeviceSize emitter_bytes = sizeof(roma_gpu_emitter) * (VkDeviceSize)table.count;
    const VkDeviceSize cdf_bytes = sizeof(float) * (VkDeviceSize)table.count;
    const VkDeviceSize bit_bytes = sizeof(uint32_t) * (((VkDeviceSize)v.triangle_count + 31) / 32);
    r = roma_upload_create(ctx, emitter_bytes, usage, &out->emitters);
    if (r == ROMA_SUCCESS)
        r = roma_upload_create(ctx, cdf_bytes, usage, &out->cdf);
    if (r == ROMA_SUCCESS)
        r = roma_upload_create(ctx, bit_bytes, usage, &out->bits);
    if (r == ROMA_SUCCESS) {
        roma_gpu_emitter *g = roma_upload_write(&out->emitters, emitter_bytes);
        memset(g, 0, (size_t)emitter_bytes);
        for (uint32_t i = 0; i < table.count; ++i) {
            const roma_emitter *e = &table.emitters[i];
            for (int k = 0; k < 3; ++k) {
                g[i].v0_pdf[k] = e->v0[k];
                g[i].e1[k] = e->e1[k];
                g[i].e2[k] = e->e2[k];
                g[i].normal[k] = e->normal[k];
                g[i].emission[k] = e->emission[k];
            }
            g[i].v0_pdf[3] = e->pdf_area;
        }
        memcpy(roma_upload_write(&out->cdf, cdf_bytes), table.cdf, (size_t)cdf_bytes);
        uint32_t *bits = roma_upload_write(&out->bits, bit_bytes);
        memset(bits, 0, (size_t)bit_bytes);
        for (uint32_t i = 0; i < v.emissive_triangle_count; ++i)
            if (v.emissive_triangles[i] < v.triangle_count)
                bits[v.emissive_triangles[i] / 32] |= 1u << (v.emissive_triangles[i] % 32);
        out->emitter_count = table.count;
        out->bit_triangles = v.triangle_count;
    } else {
        roma_light_data_destroy(ctx, out); /* the caller says what failed */
    }
    roma_emitter_table_free(&table);
    return r;
}

void roma_light_data_record(const roma_light_data *data, VkCommandBuffer cmd)
{
    roma_upload_record(&data->emitters, cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    roma_upload_record(&data->cdf, cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    roma_upload_record(&data->bits, cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

void roma_light_data_done(roma_light_data *data)
{
    roma_upload_done(&data->emitters);
    roma_upload_done(&data->cdf);
    roma_upload_done(&data->bits);
}

void roma_light_data_destroy(roma_context *ctx, roma_light_data *data)
{
    roma_upload_destroy(ctx, &data->emitters);
    roma_upload_destroy(ctx, &data->cdf);
    roma_upload_destroy(ctx, &data->bits);
    memset(data, 0, sizeof *data);
}
