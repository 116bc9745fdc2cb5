#include "compose_pass.h"

#include <roma/trace_types.h>

#include "atrous_comp_spv.h"
#include "compose_comp_spv.h"

#include <cstring>
#include <initializer_list>

namespace {
// Set 0 of compose.comp: 0-2 G-buffer (sampled), 3-6 effect outputs, accum out, display
// (storage images), 7-8 reference and BOM (storage buffers), 9-11 history (storage
// images), 12 the Frame block (storage buffer), 13 the GI output (storage image).
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
    float prev_rows[4][4];
    float eye_angle[4];
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
    VkDescriptorPoolSize sizes[4] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 6},
                                     {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 16},
                                     {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 6},
                                     {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1}};
    VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pi.maxSets = 2;
    pi.poolSizeCount = 4;
    pi.pPoolSizes = sizes;
    if (vkCreateDescriptorPool(b.device, &pi, nullptr, &c.pool) != VK_SUCCESS)
        return false;
    VkDescriptorSetLayout both[2] = {c.set_layout, c.set_layout};
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = c.pool;
    ai.descriptorSetCount = 2;
    ai.pSetLayouts = both;
    if (vkAllocateDescriptorSets(b.device, &ai, c.sets) != VK_SUCCESS)
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
    if (!c.module)
        return false;
    // The a-trous filter: G-buffer position and normal, source, destination, display.
    VkDescriptorSetLayoutBinding ab[5];
    for (uint32_t i = 0; i < 5; ++i)
        ab[i] = {i, i < 2 ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER : VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1,
                 VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
    VkDescriptorSetLayoutCreateInfo ali{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    ali.bindingCount = 5;
    ali.pBindings = ab;
    if (vkCreateDescriptorSetLayout(b.device, &ali, nullptr, &c.atrous_set_layout) != VK_SUCCESS)
        return false;
    VkDescriptorPoolSize asz[2] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 12},
                                   {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 18}};
    VkDescriptorPoolCreateInfo api{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    api.maxSets = 6;
    api.poolSizeCount = 2;
    api.pPoolSizes = asz;
    if (vkCreateDescriptorPool(b.device, &api, nullptr, &c.atrous_pool) != VK_SUCCESS)
        return false;
    VkDescriptorSetLayout six[6] = {c.atrous_set_layout, c.atrous_set_layout, c.atrous_set_layout,
                                    c.atrous_set_layout, c.atrous_set_layout, c.atrous_set_layout};
    VkDescriptorSetAllocateInfo aai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    aai.descriptorPool = c.atrous_pool;
    aai.descriptorSetCount = 6;
    aai.pSetLayouts = six;
    if (vkAllocateDescriptorSets(b.device, &aai, &c.atrous_sets[0][0]) != VK_SUCCESS)
        return false;
    VkPushConstantRange apush{VK_SHADER_STAGE_COMPUTE_BIT, 0, 48};
    VkPipelineLayoutCreateInfo apli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    apli.setLayoutCount = 1;
    apli.pSetLayouts = &c.atrous_set_layout;
    apli.pushConstantRangeCount = 1;
    apli.pPushConstantRanges = &apush;
    if (vkCreatePipelineLayout(b.device, &apli, nullptr, &c.atrous_layout) != VK_SUCCESS)
        return false;
    VkShaderModule am = vk_shader_module(b, atrous_comp_spv, sizeof atrous_comp_spv);
    VkComputePipelineCreateInfo aci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    aci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    aci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    aci.stage.module = am;
    aci.stage.pName = "main";
    aci.layout = c.atrous_layout;
    bool ok = am && vkCreateComputePipelines(b.device, VK_NULL_HANDLE, 1, &aci, nullptr, &c.atrous) == VK_SUCCESS;
    if (am)
        vkDestroyShaderModule(b.device, am, nullptr);
    return ok;
}

static VkPipeline view_pipeline(const vk_base &b, compose_pass &c, view_mode view)
{
    if (c.pipelines[view])
        return c.pipelines[view];
    uint32_t value = view;
    VkSpecializationMapEntry entry{0, 0, sizeof value};
    VkSpecializationInfo spec{1, &entry, sizeof value, &value};
    VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    ci.stage.module = c.module;
    ci.stage.pName = "main";
    ci.stage.pSpecializationInfo = &spec;
    ci.layout = c.layout;
    if (vkCreateComputePipelines(b.device, VK_NULL_HANDLE, 1, &ci, nullptr, &c.pipelines[view]) != VK_SUCCESS)
        c.pipelines[view] = VK_NULL_HANDLE;
    return c.pipelines[view];
}

bool compose_pass_resize(const vk_base &b, compose_pass &c, const gbuffer_pass &g)
{
    vk_image_destroy(b, c.ao);
    vk_image_destroy(b, c.light);
    vk_image_destroy(b, c.gi);
    vk_image_destroy(b, c.display);
    for (int k = 0; k < 2; ++k) {
        vk_image_destroy(b, c.accum[k]);
        vk_image_destroy(b, c.positions[k]);
        c.history_ready[k] = false;
    }
    c.width = g.width;
    c.height = g.height;
    VkImageUsageFlags storage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    const VkFormat f32x4 = VK_FORMAT_R32G32B32A32_SFLOAT;
    if (!vk_image_create(b, c.width, c.height, VK_FORMAT_R32_SFLOAT, storage, c.ao) ||
        !vk_image_create(b, c.width, c.height, f32x4, storage, c.light) ||
        !vk_image_create(b, c.width, c.height, f32x4, storage, c.gi) ||
        !vk_image_create(b, c.width, c.height, VK_FORMAT_R8G8B8A8_UNORM, storage, c.display))
        return false;
    for (int k = 0; k < 2; ++k) {
        vk_image_destroy(b, c.t[k]);
        if (!vk_image_create(b, c.width, c.height, f32x4, storage, c.accum[k]) ||
            !vk_image_create(b, c.width, c.height, f32x4, VK_IMAGE_USAGE_STORAGE_BIT, c.positions[k]) ||
            !vk_image_create(b, c.width, c.height, f32x4, storage, c.t[k]))
            return false;
    }
    for (uint32_t k = 0; k < 2; ++k)
        for (uint32_t it = 0; it < 3; ++it) {
            // accum[k] -> t0 -> t1 -> t0 (and the display)
            VkImageView from = it == 0 ? c.accum[k].view : c.t[(it + 1) % 2].view, to = c.t[it % 2].view;
            VkDescriptorImageInfo ai[5] = {{c.sampler, g.position.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
                                           {c.sampler, g.normal.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
                                           {VK_NULL_HANDLE, from, VK_IMAGE_LAYOUT_GENERAL},
                                           {VK_NULL_HANDLE, to, VK_IMAGE_LAYOUT_GENERAL},
                                           {VK_NULL_HANDLE, c.display.view, VK_IMAGE_LAYOUT_GENERAL}};
            VkWriteDescriptorSet aw[5];
            for (uint32_t i = 0; i < 5; ++i) {
                aw[i] = VkWriteDescriptorSet{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
                aw[i].dstSet = c.atrous_sets[k][it];
                aw[i].dstBinding = i;
                aw[i].descriptorCount = 1;
                aw[i].descriptorType = i < 2 ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER : VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
                aw[i].pImageInfo = &ai[i];
            }
            vkUpdateDescriptorSets(b.device, 5, aw, 0, nullptr);
        }
    for (uint32_t k = 0; k < 2; ++k) {
        // Parity k writes accum[k] and positions[k] and reads the other pair.
        VkDescriptorImageInfo images[kBindings] = {
            {c.sampler, g.position.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
            {c.sampler, g.normal.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
            {c.sampler, g.albedo.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
            {VK_NULL_HANDLE, c.ao.view, VK_IMAGE_LAYOUT_GENERAL},
            {VK_NULL_HANDLE, c.light.view, VK_IMAGE_LAYOUT_GENERAL},
            {VK_NULL_HANDLE, c.accum[k].view, VK_IMAGE_LAYOUT_GENERAL},
            {VK_NULL_HANDLE, c.display.view, VK_IMAGE_LAYOUT_GENERAL},
            {},
            {},
            {VK_NULL_HANDLE, c.accum[1 - k].view, VK_IMAGE_LAYOUT_GENERAL},
            {VK_NULL_HANDLE, c.positions[k].view, VK_IMAGE_LAYOUT_GENERAL},
            {VK_NULL_HANDLE, c.positions[1 - k].view, VK_IMAGE_LAYOUT_GENERAL},
            {},
            {VK_NULL_HANDLE, c.gi.view, VK_IMAGE_LAYOUT_GENERAL}};
        VkDescriptorBufferInfo frame{c.frame_data[k].buffer, 0, VK_WHOLE_SIZE};
        VkWriteDescriptorSet writes[kBindings];
        uint32_t n = 0;
        for (uint32_t i = 0; i < kBindings; ++i) {
            if (i == 7 || i == 8)
                continue; // the buffers: compose_pass_set_buffers
            writes[n] = VkWriteDescriptorSet{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            writes[n].dstSet = c.sets[k];
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
    VkWriteDescriptorSet writes[4];
    for (uint32_t i = 0; i < 4; ++i) {
        writes[i] = VkWriteDescriptorSet{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[i].dstSet = c.sets[i / 2];
        writes[i].dstBinding = 7 + i % 2;
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        writes[i].pBufferInfo = &infos[i % 2];
    }
    vkUpdateDescriptorSets(b.device, 4, writes, 0, nullptr);
}

void compose_pass_destroy(const vk_base &b, compose_pass &c)
{
    vk_image_destroy(b, c.ao);
    vk_image_destroy(b, c.light);
    vk_image_destroy(b, c.gi);
    vk_image_destroy(b, c.display);
    for (int k = 0; k < 2; ++k) {
        vk_image_destroy(b, c.accum[k]);
        vk_image_destroy(b, c.positions[k]);
        vk_image_destroy(b, c.t[k]);
        vk_buffer_destroy(b, c.frame_data[k]);
    }
    if (c.atrous)
        vkDestroyPipeline(b.device, c.atrous, nullptr);
    if (c.atrous_layout)
        vkDestroyPipelineLayout(b.device, c.atrous_layout, nullptr);
    if (c.atrous_pool)
        vkDestroyDescriptorPool(b.device, c.atrous_pool, nullptr);
    if (c.atrous_set_layout)
        vkDestroyDescriptorSetLayout(b.device, c.atrous_set_layout, nullptr);
    for (VkPipeline p : c.pipelines)
        if (p)
            vkDestroyPipeline(b.device, p, nullptr);
    if (c.module)
        vkDestroyShaderModule(b.device, c.module, nullptr);
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

bool compose_pass_record(const vk_base &b, compose_pass &c, VkCommandBuffer cmd, const compose_settings &s,
                         VkDescriptorSet trace_set)
{
    VkPipeline pipeline = view_pipeline(b, c, s.view);
    if (!pipeline)
        return false;
    const VkPipelineStageFlags2 cs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    const VkAccessFlags2 rw = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    // The effects' storage writes, read here.
    VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    mb.srcStageMask = cs;
    mb.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    mb.dstStageMask = cs;
    mb.dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_READ_BIT;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &mb;
    vkCmdPipelineBarrier2(cmd, &dep);
    // History: this frame writes the parity's pair (rewritten whole) and reads the other,
    // which the last frame wrote; before the first such frame there is nothing to read.
    const uint32_t k = s.parity & 1u, other = 1u - k;
    uint32_t mode = c.history_ready[other] ? s.history_mode : 0u;
    for (vk_image *img : {&c.accum[k], &c.positions[k]})
        vk_image_barrier(cmd, img->image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                         cs | VK_PIPELINE_STAGE_2_TRANSFER_BIT, 0, cs, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    if (!c.history_ready[other]) // the reads of an unwritten pair still need a layout
        for (vk_image *img : {&c.accum[other], &c.positions[other]})
            vk_image_barrier(cmd, img->image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                             VK_PIPELINE_STAGE_2_NONE, 0, cs, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    frame_block fb{};
    std::memcpy(fb.prev_rows, s.prev_clip_rows, sizeof fb.prev_rows);
    for (int i = 0; i < 3; ++i)
        fb.eye_angle[i] = s.eye[i];
    fb.eye_angle[3] = s.pixel_angle;
    fb.mode_cap[0] = mode;
    fb.mode_cap[1] = s.history_cap;
    fb.mode_cap[2] = s.steps_max;
    fb.mode_cap[3] = s.map_index;
    std::memcpy(fb.steps_light, s.steps_light, sizeof fb.steps_light);
    fb.steps_tmin[0] = s.steps_tmin;
    fb.steps_tmin[1] = s.ao_skip;
    fb.bom[0] = uint32_t(s.bom_address);
    fb.bom[1] = uint32_t(s.bom_address >> 32);
    std::memcpy(c.frame_data[k].mapped, &fb, sizeof fb); // the slot's fence has passed: not in use
    vk_image_barrier(cmd, c.display.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                     VK_PIPELINE_STAGE_2_TRANSFER_BIT, 0, cs, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
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
    VkDescriptorSet sets[2] = {c.sets[k], trace_set};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, c.layout, 0, 2, sets, 0, nullptr);
    vkCmdPushConstants(cmd, c.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    vkCmdDispatch(cmd, (c.width + 7) / 8, (c.height + 7) / 8, 1);
    if (s.filter) {
        // Three a-trous iterations (steps 1, 2, 4) over this frame's accumulation; the last
        // one rewrites the display image's covered pixels. Each reads what the one before wrote.
        for (vk_image *img : {&c.t[0], &c.t[1]})
            vk_image_barrier(cmd, img->image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, cs, 0, cs,
                             VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        struct {
            uint32_t size[2];
            int32_t step;
            uint32_t last;
            float exposure, pixel_angle, pad[2];
            float eye[4];
        } ap{};
        static_assert(sizeof ap == 48, "the push block of atrous.comp");
        ap.size[0] = c.width, ap.size[1] = c.height;
        ap.exposure = s.tone ? s.exposure : 0.0f;
        ap.pixel_angle = s.pixel_angle;
        for (int i = 0; i < 3; ++i)
            ap.eye[i] = s.eye[i];
        // The last dispatch's writes, read (and t0 and the display written again) now.
        VkMemoryBarrier2 step_barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
        step_barrier.srcStageMask = cs;
        step_barrier.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
        step_barrier.dstStageMask = cs;
        step_barrier.dstAccessMask = rw;
        VkDependencyInfo step_dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        step_dep.memoryBarrierCount = 1;
        step_dep.pMemoryBarriers = &step_barrier;
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, c.atrous);
        for (uint32_t it = 0; it < 3; ++it) {
            vkCmdPipelineBarrier2(cmd, &step_dep);
            ap.step = 1 << it;
            ap.last = it == 2;
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, c.atrous_layout, 0, 1, &c.atrous_sets[k][it],
                                    0, nullptr);
            vkCmdPushConstants(cmd, c.atrous_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof ap, &ap);
            vkCmdDispatch(cmd, (c.width + 7) / 8, (c.height + 7) / 8, 1);
        }
    }
    vk_image_barrier(cmd, c.display.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, cs,
                     VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                     VK_ACCESS_2_TRANSFER_READ_BIT);
    c.history_ready[k] = true;
    c.current = k;
    c.filtered = s.filter;
    // The history is read by copies (screenshots) and the next frame.
    VkMemoryBarrier2 after{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    after.srcStageMask = cs;
    after.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    after.dstStageMask = VK_PIPELINE_STAGE_2_TRANSFER_BIT | cs;
    after.dstAccessMask = VK_ACCESS_2_TRANSFER_READ_BIT | rw;
    dep.pMemoryBarriers = &after;
    vkCmdPipelineBarrier2(cmd, &dep);
    return true;
}
