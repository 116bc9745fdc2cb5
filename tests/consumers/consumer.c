/* A program built outside the libroma tree against an installed libroma (CMake package or
 * pkg-config): it builds the maps of a box on a floor, traces eight rays from its own
 * compute shader (probe.comp, which includes the installed roma/trace_descriptors.glsl)
 * and checks the answers, which are known. Vulkan validation is on; any message fails.
 * Exit status 0 when every answer is right. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <roma/roma.h>

#include "probe_spv.h" /* glslangValidator --vn probe_spv */

typedef struct probe_ray {
    float origin[4]; /* w: tmax */
    float direction[4];
} probe_ray;

typedef struct probes {
    probe_ray rays[8];
    roma_hit hits[8];
} probes;

/* A box [-1, 1]^3 and a floor quad at y = -2 from -4 to 4 in x and z. */
static roma_result make_scene(roma_scene **out)
{
    static const float p[] = {-1, -1, -1, 1, -1, -1, -1, 1, -1, 1, 1, -1,
                              -1, -1, 1,  1, -1, 1,  -1, 1, 1,  1, 1, 1,
                              -4, -2, -4, 4, -2, -4, -4, -2, 4, 4, -2, 4};
    static const uint32_t t[] = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5,
                                 8, 10, 9, 9, 10, 11};
    roma_scene_desc d = {.positions = p, .vertex_count = 12, .indices = t, .triangle_count = 14,
                         .name = "consumer box"};
    return roma_scene_create(&d, out);
}

/* Eight rays and their expected closest-hit distance (INFINITY: a miss). The hits are
 * short rays at the middle of a face or at the floor, so that ROMA's snapping of the
 * direction to one of its candidate directions cannot take them off their target. */
static const struct {
    float o[3], d[3], t;
} cases[8] = {
    {{0, 0, 2.5f}, {0, 0, -1}, 1.5f},          /* the box's +z face */
    {{-2.5f, 0, 0}, {1, 0, 0}, 1.5f},          /* its -x face */
    {{0, -1.5f, 0}, {0, 1, 0}, 0.5f},          /* its bottom, from below */
    {{2.2f, 0, 0.9f}, {-0.8f, 0, -0.6f}, 1.5f}, /* slanted, the middle of its +x face */
    {{3, 0, 0}, {0, -1, 0}, 2},                /* the floor */
    {{3, 0, 0}, {0, 1, 0}, INFINITY},          /* up, out of the volume */
    {{0, 0, 2.5f}, {0, 0, 1}, INFINITY},       /* away from the box */
    {{-3, 0, -3}, {-0.6f, 0.8f, 0}, INFINITY}, /* up and away */
};

static int find_memory(VkPhysicalDevice pd, uint32_t bits, VkMemoryPropertyFlags want)
{
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(pd, &mp);
    for (uint32_t i = 0; i < mp.memoryTypeCount; ++i)
        if ((bits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & want) == want)
            return (int)i;
    return -1;
}

#define VK_OK(call) ok = ok && (call) == VK_SUCCESS

int main(void)
{
    roma_context_desc cd = {.flags = ROMA_CONTEXT_VALIDATION};
    roma_context *ctx = NULL;
    roma_scene *scene = NULL;
    roma_map *map = NULL;
    roma_result r = roma_context_create(&cd, &ctx);
    if (r == ROMA_SUCCESS)
        r = make_scene(&scene);
    if (r == ROMA_SUCCESS)
        r = roma_map_create(ctx, &(roma_map_desc){0}, scene, &map);
    if (r == ROMA_SUCCESS)
        r = roma_map_build(map, &(roma_map_frame_desc){0}, NULL);
    if (r != ROMA_SUCCESS) {
        fprintf(stderr, "consumer: libroma failed: %s\n", roma_result_string(r));
        roma_map_destroy(map);
        roma_scene_destroy(scene);
        roma_context_destroy(ctx);
        return 1;
    }
    roma_map_info info;
    roma_map_get_info(map, &info);

    VkDevice dev = roma_context_device(ctx);
    VkPhysicalDevice pd = roma_context_physical_device(ctx);
    int ok = 1;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkShaderModule module = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkCommandPool cmd_pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    probes *mapped = NULL;

    /* The rays and hits: one host-visible buffer. */
    VK_OK(vkCreateBuffer(dev, &(VkBufferCreateInfo){.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                                                    .size = sizeof(probes),
                                                    .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT},
                         NULL, &buffer));
    if (ok) {
        VkMemoryRequirements req;
        vkGetBufferMemoryRequirements(dev, buffer, &req);
        int type = find_memory(pd, req.memoryTypeBits,
                               VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
        ok = type >= 0;
        VK_OK(vkAllocateMemory(dev, &(VkMemoryAllocateInfo){.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                                                            .allocationSize = req.size,
                                                            .memoryTypeIndex = (uint32_t)type},
                               NULL, &memory));
        VK_OK(vkBindBufferMemory(dev, buffer, memory, 0));
        VK_OK(vkMapMemory(dev, memory, 0, VK_WHOLE_SIZE, 0, (void **)&mapped));
    }
    if (ok) {
        memset(mapped, 0, sizeof *mapped);
        for (int i = 0; i < 8; ++i) {
            memcpy(mapped->rays[i].origin, cases[i].o, sizeof cases[i].o);
            mapped->rays[i].origin[3] = 100.0f;
            memcpy(mapped->rays[i].direction, cases[i].d, sizeof cases[i].d);
        }
    }

    /* Set 0: libroma's trace set; set 1: the probes. */
    VkDescriptorSetLayoutBinding binding = {.binding = 0, .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                            .descriptorCount = 1, .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT};
    VK_OK(vkCreateDescriptorSetLayout(dev, &(VkDescriptorSetLayoutCreateInfo){
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO, .bindingCount = 1, .pBindings = &binding},
        NULL, &set_layout));
    VK_OK(vkCreateDescriptorPool(dev, &(VkDescriptorPoolCreateInfo){
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, .maxSets = 1, .poolSizeCount = 1,
        .pPoolSizes = &(VkDescriptorPoolSize){VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1}},
        NULL, &pool));
    VK_OK(vkAllocateDescriptorSets(dev, &(VkDescriptorSetAllocateInfo){
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO, .descriptorPool = pool,
        .descriptorSetCount = 1, .pSetLayouts = &set_layout},
        &set));
    if (ok)
        vkUpdateDescriptorSets(dev, 1, &(VkWriteDescriptorSet){
            .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = set, .dstBinding = 0,
            .descriptorCount = 1, .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
            .pBufferInfo = &(VkDescriptorBufferInfo){buffer, 0, VK_WHOLE_SIZE}}, 0, NULL);
    VkDescriptorSetLayout layouts[2] = {info.trace_set_layout, set_layout};
    VkPushConstantRange push = {VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(uint32_t)};
    VK_OK(vkCreatePipelineLayout(dev, &(VkPipelineLayoutCreateInfo){
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, .setLayoutCount = 2, .pSetLayouts = layouts,
        .pushConstantRangeCount = 1, .pPushConstantRanges = &push},
        NULL, &layout));
    VK_OK(vkCreateShaderModule(dev, &(VkShaderModuleCreateInfo){
        .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, .codeSize = sizeof probe_spv, .pCode = probe_spv},
        NULL, &module));
    VK_OK(vkCreateComputePipelines(dev, VK_NULL_HANDLE, 1, &(VkComputePipelineCreateInfo){
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                  .stage = VK_SHADER_STAGE_COMPUTE_BIT, .module = module, .pName = "main"},
        .layout = layout},
        NULL, &pipeline));

    /* Record, submit and wait: this program owns the queue (libroma's context made it). */
    VK_OK(vkCreateCommandPool(dev, &(VkCommandPoolCreateInfo){
        .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, .queueFamilyIndex = roma_context_queue_family(ctx)},
        NULL, &cmd_pool));
    VK_OK(vkAllocateCommandBuffers(dev, &(VkCommandBufferAllocateInfo){
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = cmd_pool,
        .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1},
        &cmd));
    VK_OK(vkBeginCommandBuffer(cmd, &(VkCommandBufferBeginInfo){
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
        .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT}));
    if (ok) {
        VkDescriptorSet sets[2] = {info.trace_set, set};
        uint32_t count = 8;
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 2, sets, 0, NULL);
        vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof count, &count);
        vkCmdDispatch(cmd, 1, 1, 1);
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
                             &(VkMemoryBarrier){.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                                                .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT,
                                                .dstAccessMask = VK_ACCESS_HOST_READ_BIT},
                             0, NULL, 0, NULL);
    }
    VK_OK(vkEndCommandBuffer(cmd));
    VK_OK(vkQueueSubmit(roma_context_queue(ctx), 1, &(VkSubmitInfo){
        .sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &cmd},
        VK_NULL_HANDLE));
    VK_OK(vkQueueWaitIdle(roma_context_queue(ctx)));

    /* A hit within two trace cells of the true distance counts as right (the maps are voxels). */
    int right = 0;
    float worst = 0.0f;
    float tolerance = 2.0f * info.trace_cell;
    for (int i = 0; ok && i < 8; ++i) {
        const roma_hit *h = &mapped->hits[i];
        int hit = (h->info & ROMA_HIT_FLAG) != 0;
        int want_hit = isfinite(cases[i].t);
        int good = hit == want_hit && (!hit || fabsf(h->t - cases[i].t) <= tolerance);
        right += good;
        if (hit && want_hit && fabsf(h->t - cases[i].t) > worst)
            worst = fabsf(h->t - cases[i].t);
        if (!good)
            fprintf(stderr, "consumer: ray %d: %s at t = %g, expected %s at %g\n", i, hit ? "hit" : "miss",
                    (double)h->t, want_hit ? "a hit" : "a miss", (double)cases[i].t);
    }
    if (!ok)
        fprintf(stderr, "consumer: a Vulkan call failed\n");

    if (cmd_pool)
        vkDestroyCommandPool(dev, cmd_pool, NULL);
    if (pipeline)
        vkDestroyPipeline(dev, pipeline, NULL);
    if (module)
        vkDestroyShaderModule(dev, module, NULL);
    if (layout)
        vkDestroyPipelineLayout(dev, layout, NULL);
    if (pool)
        vkDestroyDescriptorPool(dev, pool, NULL);
    if (set_layout)
        vkDestroyDescriptorSetLayout(dev, set_layout, NULL);
    if (buffer)
        vkDestroyBuffer(dev, buffer, NULL);
    if (memory)
        vkFreeMemory(dev, memory, NULL);
    roma_map_destroy(map);
    roma_scene_destroy(scene);
    uint32_t messages = roma_context_validation_error_count(ctx);
    roma_context_destroy(ctx);
    printf("consumer: %d of 8 rays right (RES %u, A %u; largest distance error %.3f, tolerance %.3f), "
           "%u validation messages\n", right, info.resolution, info.angular, (double)worst, (double)tolerance,
           messages);
    return ok && right == 8 && messages == 0 ? 0 : 1;
}
