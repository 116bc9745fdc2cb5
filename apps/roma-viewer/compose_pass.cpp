#include "compose_pass.h"

#include <roma/trace_types.h>

#include "compose_comp_spv.h"
#include "display_comp_spv.h"

#include <cstring>
#include <initializer_list>

namespace {
// Set 0 of compose.comp: 0-2 G-buffer (sampled), 3-6 effect outputs, current, display
// (storage images), 7-8 reference and BOM (storage buffers), 9 the temporal effect's
// picture and 10 this frame's positions (storage images; 11 unused), 12 the Frame block
// (storage buffer), 13 the GI output (storage image).
constexpr uint32_t kBindings = 14;
VkDescriptorType binding_type(uint32_t i)
{
    return i < 3    ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER
           : i < 7  ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE
           : i < 9  ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER
           : i < 12 ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE
           : i < 13 ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER
                    : VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
}

struct frame_block { // std430, as compose.comp's Frame
    uint32_t mode_cap[4];
    float steps_light[4];
    float steps_tmin[4];
    uint32_t bom[4];
};
} // namespace

bool compose_pass_create(const vk_base &b, compose_pass &c)
{
    VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    si.magFilter = si.minFilter = VK_FILTER_NEAREST;
    si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    if (vkCreateSampler(b.device, &si, nullptr, &c.sampler) != VK_SUCCESS)
        return false;
    VkDescriptorSetLayoutBinding bindings[kBindings];
    for (uint32_t i = 0; i < kBindings; ++i)
        bindings[i] = {i, binding_type(i), 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
    VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    li.bindingCount = kBindings;
    li.pBindings = bindings;
    if (vkCreateDescriptorSetLayout(b.device, &li, nullptr, &c.set_layout) != VK_SUCCESS)
        return false;
    // Set 1: defined as roma_map_info.trace_set_layout is (roma/trace_descriptors.glsl), so
    // every map's trace set can be bound with this one pipeline layout.
    VkDescriptorSetLayoutBinding trace[ROMA_TRACE_BINDINGS] = {
        {ROMA_TRACE_BINDING_MAPS, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
        {ROMA_TRACE_BINDING_PARAMS, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
    li.bindingCount = ROMA_TRACE_BINDINGS;
    li.pBindings = trace;
    if (vkCreateDescriptorSetLayout(b.device, &li, nullptr, &c.trace_layout) != VK_SUCCESS)
        return false;
    VkDescriptorPoolSize sizes[4] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 12},
                                     {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 32},
                                     {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 12},
                                     {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1}};
    VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pi.maxSets = 4;
    pi.poolSizeCount = 4;
    pi.pPoolSizes = sizes;
    if (vkCreateDescriptorPool(b.device, &pi, nullptr, &c.pool) != VK_SUCCESS)
        return false;
    VkDescriptorSetLayout four[4] = {c.set_layout, c.set_layout, c.set_layout, c.set_layout};
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = c.pool;
    ai.descriptorSetCount = 4;
    ai.pSetLayouts = four;
    if (vkAllocateDescriptorSets(b.device, &ai, &c.sets[0][0]) != VK_SUCCESS)
        return false;
    for (vk_buffer &f : c.frame_data)
        if (!vk_buffer_create(b, sizeof(frame_block), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true, f))
            return false;
    VkDescriptorSetLayout layouts[2] = {c.set_layout, c.trace_layout};
    VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, 112};
    VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    pli.setLayoutCount = 2;
    pli.pSetLayouts = layouts;
    pli.pushConstantRangeCount = 1;
    pli.pPushConstantRanges = &push;
    if (vkCreatePipelineLayout(b.device, &pli, nullptr, &c.layout) != VK_SUCCESS)
        return false;
    c.module = vk_shader_module(b, compose_comp_spv, sizeof compose_comp_spv);
    c.display_module = vk_shader_module(b, display_comp_spv, sizeof display_comp_spv);
    return c.module != VK_NULL_HANDLE && c.display_module != VK_NULL_HANDLE;
}

static VkPipeline view_pipeline(const vk_base &b, compose_pass &c, view_mode view, uint32_t pass)
{
    VkPipeline &pipeline = c.pipelines[pass][view];
    if (pipeline)
        return pipeline;
    // The view, and roma/trace.glsl's division rule as libroma's own pipelines have it.
    uint32_t values[2] = {uint32_t(view), c.corrected_division};
    VkSpecializationMapEntry entries[2] = {{0, 0, sizeof(uint32_t)},
                                           {ROMA_CORRECTED_DIVISION_CONSTANT_ID, sizeof(uint32_t), sizeof(uint32_t)}};
    VkSpecializationInfo spec{2, entries, sizeof values, values};
    VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    ci.stage.module = pass == 0 ? c.module : c.display_module;
    ci.stage.pName = "main";
    ci.stage.pSpecializationInfo = &spec;
    ci.layout = c.layout;
    if (vkCreateComputePipelines(b.device, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline) != VK_SUCCESS)
        pipeline = VK_NULL_HANDLE;
    return pipeline;
}

bool compose_pass_resize(const vk_base &b, compose_pass &c, const gbuffer_pass &g)
{
    vk_image_destroy(b, c.ao);
    vk_image_destroy(b, c.light);
    vk_image_destroy(b, c.gi);
    vk_image_destroy(b, c.display);
    vk_image_destroy(b, c.current);
    for (int k = 0; k < 2; ++k) {
        vk_image_destroy(b, c.accum[k]);
        vk_image_destroy(b, c.positions[k]);
        vk_image_destroy(b, c.t[k]);
        c.history_ready[k] = false;
    }
    c.width = g.width;
    c.height = g.height;
    VkImageUsageFlags storage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    // Sampled too: the temporal effect reads this frame's picture, positions and history so.
    VkImageUsageFlags both = storage | VK_IMAGE_USAGE_SAMPLED_BIT;
    const VkFormat f32x4 = VK_FORMAT_R32G32B32A32_SFLOAT;
    if (!vk_image_create(b, c.width, c.height, VK_FORMAT_R32_SFLOAT, storage, c.ao) ||
        !vk_image_create(b, c.width, c.height, f32x4, storage, c.light) ||
        !vk_image_create(b, c.width, c.height, f32x4, storage, c.gi) ||
        !vk_image_create(b, c.width, c.height, VK_FORMAT_R8G8B8A8_UNORM, storage, c.display) ||
        !vk_image_create(b, c.width, c.height, f32x4, both, c.current))
        return false;
    for (int k = 0; k < 2; ++k)
        if (!vk_image_create(b, c.width, c.height, f32x4, both, c.accum[k]) ||
            !vk_image_create(b, c.width, c.height, f32x4, both, c.positions[k]) ||
            !vk_image_create(b, c.width, c.height, f32x4, storage, c.t[k]))
            return false;
    for (uint32_t set = 0; set < 4; ++set) {
        // Parity k composes into current and positions[k]; the display reads accum[k] (the
        // temporal effect's output) or, filtered, t[0].
        uint32_t k = set / 2, filtered = set % 2;
        VkDescriptorImageInfo images[kBindings] = {
            {c.sampler, g.position.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
            {c.sampler, g.normal.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
            {c.sampler, g.albedo.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
            {VK_NULL_HANDLE, c.ao.view, VK_IMAGE_LAYOUT_GENERAL},
            {VK_NULL_HANDLE, c.light.view, VK_IMAGE_LAYOUT_GENERAL},
            {VK_NULL_HANDLE, c.current.view, VK_IMAGE_LAYOUT_GENERAL},
            {VK_NULL_HANDLE, c.display.view, VK_IMAGE_LAYOUT_GENERAL},
            {},
            {},
            {VK_NULL_HANDLE, filtered ? c.t[0].view : c.accum[k].view, VK_IMAGE_LAYOUT_GENERAL},
            {VK_NULL_HANDLE, c.positions[k].view, VK_IMAGE_LAYOUT_GENERAL},
            {},
            {},
            {VK_NULL_HANDLE, c.gi.view, VK_IMAGE_LAYOUT_GENERAL}};
        VkDescriptorBufferInfo frame{c.frame_data[k].buffer, 0, VK_WHOLE_SIZE};
        VkWriteDescriptorSet writes[kBindings];
        uint32_t n = 0;
        for (uint32_t i = 0; i < kBindings; ++i) {
            if (i == 7 || i == 8 || i == 11)
                continue; // the buffers: compose_pass_set_buffers; 11 unused
            writes[n] = VkWriteDescriptorSet{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            writes[n].dstSet = c.sets[k][filtered];
            writes[n].dstBinding = i;
            writes[n].descriptorCount = 1;
            writes[n].descriptorType = binding_type(i);
            if (i == 12)
                writes[n].pBufferInfo = &frame;
            else
                writes[n].pImageInfo = &images[i];
            ++n;
        }
        vkUpdateDescriptorSets(b.device, n, writes, 0, nullptr);
    }
    return true;
}

void compose_pass_set_buffers(const vk_base &b, compose_pass &c, VkBuffer reference, VkBuffer bom)
{
    VkDescriptorBufferInfo infos[2] = {{reference, 0, VK_WHOLE_SIZE}, {bom, 0, VK_WHOLE_SIZE}};
    VkWriteDescriptorSet writes[8];
    for (uint32_t i = 0; i < 8; ++i) {
        writes[i] = VkWriteDescriptorSet{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[i].dstSet = (&c.sets[0][0])[i / 2];
        writes[i].dstBinding = 7 + i % 2;
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        writes[i].pBufferInfo = &infos[i % 2];
    }
    vkUpdateDescriptorSets(b.device, 8, writes, 0, nullptr);
}

void compose_pass_destroy(const vk_base &b, compose_pass &c)
{
    vk_image_destroy(b, c.ao);
    vk_image_destroy(b, c.light);
    vk_image_destroy(b, c.gi);
    vk_image_destroy(b, c.display);
    vk_image_destroy(b, c.current);
    for (int k = 0; k < 2; ++k) {
        vk_image_destroy(b, c.accum[k]);
        vk_image_destroy(b, c.positions[k]);
        vk_image_destroy(b, c.t[k]);
        vk_buffer_destroy(b, c.frame_data[k]);
    }
    for (auto &per_pass : c.pipelines)
        for (VkPipeline p : per_pass)
            if (p)
                vkDestroyPipeline(b.device, p, nullptr);
    if (c.module)
        vkDestroyShaderModule(b.device, c.module, nullptr);
    if (c.display_module)
        vkDestroyShaderModule(b.device, c.display_module, nullptr);
    if (c.layout)
        vkDestroyPipelineLayout(b.device, c.layout, nullptr);
    if (c.pool)
        vkDestroyDescriptorPool(b.device, c.pool, nullptr);
    if (c.set_layout)
        vkDestroyDescriptorSetLayout(b.device, c.set_layout, nullptr);
    if (c.trace_layout)
        vkDestroyDescriptorSetLayout(b.device, c.trace_layout, nullptr);
    if (c.sampler)
        vkDestroySampler(b.device, c.sampler, nullptr);
    c = compose_pass{};
}

void compose_pass_prepare(const compose_pass &c, VkCommandBuffer cmd)
{
    // The accumulation image keeps its contents (GENERAL to GENERAL); the others are
    // rewritten every frame. Last frame's readers: compose (compute) and the copies.
    const VkPipelineStageFlags2 before = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT;
    const VkAccessFlags2 rw = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    vk_image_barrier(cmd, c.ao.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, before, 0,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, rw);
    vk_image_barrier(cmd, c.light.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, before, 0,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, rw);
    vk_image_barrier(cmd, c.gi.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, before, 0,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, rw);
}

// A global barrier: compute-shader storage writes before the next compute reads and writes.
static void compute_to_compute(VkCommandBuffer cmd)
{
    VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    mb.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    mb.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    mb.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    mb.dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                       VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &mb;
    vkCmdPipelineBarrier2(cmd, &dep);
}

bool compose_pass_record(const vk_base &b, compose_pass &c, VkCommandBuffer cmd, const compose_settings &s,
                         VkDescriptorSet trace_set, roma_temporal_effect *temporal, const gbuffer_pass &g)
{
    VkPipeline compose = view_pipeline(b, c, s.view, 0), display = view_pipeline(b, c, s.view, 1);
    if (!compose || !display)
        return false;
    const VkPipelineStageFlags2 cs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    const VkPipelineStageFlags2 before = cs | VK_PIPELINE_STAGE_2_TRANSFER_BIT;
    const VkAccessFlags2 sampled = VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;
    // The effects' storage writes, read here.
    compute_to_compute(cmd);
    // This frame composes into current and positions[k] (rewritten whole), the temporal
    // effect writes accum[k] (and t) and reads accum and positions of the other parity,
    // which the last frame wrote; before the first such frame there is no history.
    const uint32_t k = s.parity & 1u, other = 1u - k;
    bool history = c.history_ready[other] && s.history_mode != 0 && s.view != VIEW_ROTATED_MAP;
    for (vk_image *img : {&c.current, &c.positions[k], &c.accum[k], &c.t[0], &c.t[1], &c.display})
        vk_image_barrier(cmd, img->image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, before, 0, cs,
                         VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    if (!c.history_ready[other]) { // the bindings of an unwritten pair still need their layouts
        vk_image_barrier(cmd, c.accum[other].image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                         VK_PIPELINE_STAGE_2_NONE, 0, cs, sampled);
        vk_image_barrier(cmd, c.positions[other].image, VK_IMAGE_LAYOUT_UNDEFINED,
                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0, cs, sampled);
    }
    frame_block fb{};
    fb.mode_cap[2] = s.steps_max;
    fb.mode_cap[3] = s.map_index;
    std::memcpy(fb.steps_light, s.steps_light, sizeof fb.steps_light);
    fb.steps_tmin[0] = s.steps_tmin;
    fb.steps_tmin[1] = s.ao_skip;
    fb.bom[0] = uint32_t(s.bom_address);
    fb.bom[1] = uint32_t(s.bom_address >> 32);
    std::memcpy(c.frame_data[k].mapped, &fb, sizeof fb); // the slot's fence has passed: not in use
    struct {
        float ambient[4], background[4], bom_origin[4];
        uint32_t size[2], view, accumulated;
        float exposure, debug_length, offset;
        uint32_t ao_on, direct_on, slice_axis, slice_depth, bom_res, compared, gi_on;
    } push{};
    static_assert(sizeof push == 104, "the push block of compose.comp");
    for (int i = 0; i < 3; ++i) {
        push.ambient[i] = s.ambient[i];
        push.background[i] = s.background[i];
    }
    for (int i = 0; i < 4; ++i)
        push.bom_origin[i] = s.bom_origin[i];
    push.slice_axis = s.slice_axis;
    push.slice_depth = s.slice_depth;
    push.bom_res = s.bom_res;
    push.compared = s.compared;
    push.size[0] = c.width;
    push.size[1] = c.height;
    push.view = s.view;
    push.accumulated = s.accumulated;
    push.exposure = s.exposure;
    push.debug_length = s.debug_length;
    push.offset = s.offset;
    push.ao_on = s.ao_on;
    push.direct_on = s.direct_on;
    push.gi_on = s.gi_on;
    VkDescriptorSet sets[2] = {c.sets[k][s.filter ? 1 : 0], trace_set};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, compose);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, c.layout, 0, 2, sets, 0, nullptr);
    vkCmdPushConstants(cmd, c.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    vkCmdDispatch(cmd, (c.width + 7) / 8, (c.height + 7) / 8, 1);

    // libroma's temporal effect: the picture averaged over frames (reprojected through last
    // frame's world -> clip while the camera moves), filtered where the history is short.
    for (vk_image *img : {&c.current, &c.positions[k]})
        vk_image_barrier(cmd, img->image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, cs,
                         VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, cs, sampled);
    roma_temporal_images ti{};
    ti.width = c.width;
    ti.height = c.height;
    ti.current = c.current.view;
    ti.position = g.position.view;
    ti.normal = g.normal.view;
    ti.previous_position = c.positions[other].view;
    ti.history = c.accum[other].view;
    ti.accumulated = c.accum[k].view;
    ti.filtered = s.filter ? c.t[0].view : VK_NULL_HANDLE;
    ti.scratch = c.t[1].view;
    ti.input_layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    ti.history_layout = VK_IMAGE_LAYOUT_GENERAL;
    roma_temporal_settings ts{};
    ts.reset = history ? 0u : 1u;
    ts.max_history = s.history_cap;
    ts.frame = s.frame;
    if (s.history_mode == 2) // rows in, column-major out; zero (a still camera) otherwise
        for (int row = 0; row < 4; ++row)
            for (int col = 0; col < 4; ++col)
                ts.previous_view_proj[col * 4 + row] = s.prev_clip_rows[row][col];
    if (roma_temporal_effect_record(temporal, cmd, k, &ti, &ts) != ROMA_SUCCESS)
        return false;

    // The display (the effect bound its own pipeline, sets and push constants: bound again).
    compute_to_compute(cmd);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, display);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, c.layout, 0, 2, sets, 0, nullptr);
    vkCmdPushConstants(cmd, c.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    vkCmdDispatch(cmd, (c.width + 7) / 8, (c.height + 7) / 8, 1);
    vk_image_barrier(cmd, c.display.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, cs,
                     VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                     VK_ACCESS_2_TRANSFER_READ_BIT);
    c.history_ready[k] = true;
    c.current_accum = k;
    c.filtered = s.filter;
    // The history is read by copies (screenshots) and the next frame.
    VkMemoryBarrier2 after{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    after.srcStageMask = cs;
    after.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    after.dstStageMask = VK_PIPELINE_STAGE_2_TRANSFER_BIT | cs;
    after.dstAccessMask = VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                          VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | sampled;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &after;
    vkCmdPipelineBarrier2(cmd, &dep);
    return true;
}

const vk_image &compose_pass_picture(const compose_pass &c)
{
    return c.filtered ? c.t[0] : c.accum[c.current_accum];
}
