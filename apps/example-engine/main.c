/* An engine that links libroma, written against the installed headers only.
 *
 * It owns its Vulkan instance and device (created with roma_get_device_requirements),
 * keeps two frames in flight, and every frame records into its own command buffer:
 *   1. libroma's skinning of an animated glTF character (roma_animator), when given;
 *   2. its own animation pass (animate.comp): the room at rest, the skinned character
 *      placed in it, and a rigid box moved along x, into its own GPU buffer;
 *   3. roma_map_record_build, reading those positions by address (gpu_positions);
 *   4. its own tracing pass (probe.comp, including roma/trace.glsl) over probe rays
 *      whose answers are known from the box's pose that frame;
 *   5. its own G-buffer of the floor seen from above (gbuffer.comp), and libroma's AO
 *      effect on it (roma_ao_effect) into its own image: darker in a corner of the room
 *      than in the open;
 *   6. libroma's temporal effect (roma_temporal_effect) averaging that AO over frames into
 *      its own pair of history images, swapped every frame.
 * The answers come back a frame later, when the slot's fence is waited on.
 *
 *   example-engine [--frames N] [--validation | --sync-validation] [--character file.glb]
 *
 * --validation turns on the Khronos validation layer, --sync-validation the layer with
 * synchronization validation; any message fails the run. Prints resident memory and libroma's device memory at
 * frame 100 and at the end (the soak figures). Exit code 0 when every probe answer is
 * right and no validation message was seen. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "roma/builtin_scenes.h"
#include "roma/gltf.h"
#include "roma/roma.h"

#define SLOTS 2
#define PROBES 24
#define MAX_STEPS 256u
#define GB_W 64 /* the floor G-buffer: x in [-1, 1], z in [-1, 2] */
#define GB_H 96
#define AO_RADIUS 0.3f

typedef struct engine {
    VkInstance instance;
    VkDebugUtilsMessengerEXT messenger;
    VkPhysicalDevice physical;
    VkDevice device;
    VkBool32 corrected_division; /* roma_context_info's: how its shaders including roma/trace.glsl divide */
    VkQueue queue;
    uint32_t family;
    unsigned validation_messages;
} engine;

typedef struct buffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    void *mapped; /* host-visible buffers only */
    VkDeviceAddress address;
} buffer;

typedef struct probe_ray {
    float origin[4];    /* w: tmax */
    float direction[4];
} probe_ray;

static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                 VkDebugUtilsMessageTypeFlagsEXT types,
                                                 const VkDebugUtilsMessengerCallbackDataEXT *data, void *user)
{
    (void)severity, (void)types;
    ((engine *)user)->validation_messages++;
    fprintf(stderr, "validation: %s\n", data->pMessage);
    return VK_FALSE;
}

static void log_to_stderr(roma_log_level level, roma_result code, const char *message, void *user)
{
    (void)user, (void)code;
    if (level >= ROMA_LOG_WARNING)
        fprintf(stderr, "libroma %s: %s\n", roma_log_level_string(level), message);
}

static int create_instance(engine *e, int validation)
{
    VkApplicationInfo app = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
                             .pApplicationName = "example-engine",
                             .apiVersion = VK_API_VERSION_1_3};
    const char *layer = "VK_LAYER_KHRONOS_validation";
    const char *extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    VkDebugUtilsMessengerCreateInfoEXT messenger = {
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT,
        .pfnUserCallback = on_message,
        .pUserData = e};
    const VkValidationFeatureEnableEXT sync = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT features = {.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
                                        .pNext = &messenger,
                                        .enabledValidationFeatureCount = 1,
                                        .pEnabledValidationFeatures = &sync};
    VkInstanceCreateInfo info = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
                                 .pNext = validation == 2 ? (const void *)&features
                                          : validation ? (const void *)&messenger : NULL,
                                 .pApplicationInfo = &app,
                                 .enabledLayerCount = validation ? 1u : 0u,
                                 .ppEnabledLayerNames = &layer,
                                 .enabledExtensionCount = validation ? 1u : 0u,
                                 .ppEnabledExtensionNames = &extension};
    if (vkCreateInstance(&info, NULL, &e->instance) != VK_SUCCESS) {
        fprintf(stderr, "example-engine: vkCreateInstance failed%s\n",
                validation ? " (is vulkan-validationlayers installed?)" : "");
        return 0;
    }
    if (validation) {
        PFN_vkCreateDebugUtilsMessengerEXT create =
            (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(e->instance, "vkCreateDebugUtilsMessengerEXT");
        if (!create || create(e->instance, &messenger, NULL, &e->messenger) != VK_SUCCESS)
            return 0;
    }
    return 1;
}

/* The first Vulkan 1.3 device with a graphics + compute queue that has timestamps, created
 * with exactly what libroma lists. */
static int create_device(engine *e, roma_device_requirements *req)
{
    uint32_t count = 8;
    VkPhysicalDevice devices[8];
    if (vkEnumeratePhysicalDevices(e->instance, &count, devices) < 0)
        return 0;
    roma_get_device_requirements(req);
    for (uint32_t d = 0; d < count && !e->physical; ++d) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(devices[d], &props);
        if (props.apiVersion < req->api_version)
            continue;
        uint32_t families = 16;
        VkQueueFamilyProperties fp[16];
        vkGetPhysicalDeviceQueueFamilyProperties(devices[d], &families, fp);
        for (uint32_t f = 0; f < families && !e->physical; ++f)
            if ((fp[f].queueFlags & req->queue_flags) == req->queue_flags && fp[f].timestampValidBits) {
                e->physical = devices[d];
                e->family = f;
            }
    }
    if (!e->physical) {
        fprintf(stderr, "example-engine: no Vulkan 1.3 device with a graphics + compute queue\n");
        return 0;
    }
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                     .queueFamilyIndex = e->family,
                                     .queueCount = 1,
                                     .pQueuePriorities = &priority};
    VkDeviceCreateInfo info = {.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
                               .pNext = &req->features,
                               .queueCreateInfoCount = 1,
                               .pQueueCreateInfos = &queue,
                               .enabledExtensionCount = req->extension_count,
                               .ppEnabledExtensionNames = req->extensions};
    if (vkCreateDevice(e->physical, &info, NULL, &e->device) != VK_SUCCESS)
        return 0;
    vkGetDeviceQueue(e->device, e->family, 0, &e->queue);
    return 1;
}

static int buffer_create(const engine *e, VkDeviceSize size, int host_visible, buffer *out)
{
    memset(out, 0, sizeof *out);
    VkBufferCreateInfo info = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                               .size = size,
                               .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                        VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_DST_BIT};
    if (vkCreateBuffer(e->device, &info, NULL, &out->buffer) != VK_SUCCESS)
        return 0;
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(e->device, out->buffer, &req);
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(e->physical, &props);
    VkMemoryPropertyFlags want = host_visible
                                     ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
                                     : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    uint32_t type = UINT32_MAX;
    for (uint32_t i = 0; i < props.memoryTypeCount && type == UINT32_MAX; ++i)
        if ((req.memoryTypeBits & (1u << i)) && (props.memoryTypes[i].propertyFlags & want) == want)
            type = i;
    VkMemoryAllocateFlagsInfo flags = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO,
                                       .flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT};
    VkMemoryAllocateInfo alloc = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                                  .pNext = &flags,
                                  .allocationSize = req.size,
                                  .memoryTypeIndex = type};
    if (type == UINT32_MAX || vkAllocateMemory(e->device, &alloc, NULL, &out->memory) != VK_SUCCESS ||
        vkBindBufferMemory(e->device, out->buffer, out->memory, 0) != VK_SUCCESS)
        return 0;
    if (host_visible && vkMapMemory(e->device, out->memory, 0, VK_WHOLE_SIZE, 0, &out->mapped) != VK_SUCCESS)
        return 0;
    VkBufferDeviceAddressInfo at = {.sType = VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO, .buffer = out->buffer};
    out->address = vkGetBufferDeviceAddress(e->device, &at);
    return 1;
}

static void buffer_destroy(const engine *e, buffer *b)
{
    if (b->buffer)
        vkDestroyBuffer(e->device, b->buffer, NULL);
    if (b->memory)
        vkFreeMemory(e->device, b->memory, NULL);
}

typedef struct image {
    VkImage image;
    VkDeviceMemory memory;
    VkImageView view;
} image;

static int image_create(const engine *e, VkFormat format, VkImageUsageFlags usage, image *out)
{
    memset(out, 0, sizeof *out);
    VkImageCreateInfo ii = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, .imageType = VK_IMAGE_TYPE_2D,
                            .format = format, .extent = {GB_W, GB_H, 1}, .mipLevels = 1, .arrayLayers = 1,
                            .samples = VK_SAMPLE_COUNT_1_BIT, .tiling = VK_IMAGE_TILING_OPTIMAL, .usage = usage};
    if (vkCreateImage(e->device, &ii, NULL, &out->image) != VK_SUCCESS)
        return 0;
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(e->device, out->image, &req);
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(e->physical, &props);
    uint32_t type = UINT32_MAX;
    for (uint32_t i = 0; i < props.memoryTypeCount && type == UINT32_MAX; ++i)
        if (req.memoryTypeBits & (1u << i))
            type = i;
    VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size,
                               .memoryTypeIndex = type};
    if (vkAllocateMemory(e->device, &ai, NULL, &out->memory) != VK_SUCCESS ||
        vkBindImageMemory(e->device, out->image, out->memory, 0) != VK_SUCCESS)
        return 0;
    VkImageViewCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = out->image,
                                .viewType = VK_IMAGE_VIEW_TYPE_2D, .format = format,
                                .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    return vkCreateImageView(e->device, &vi, NULL, &out->view) == VK_SUCCESS;
}

static void image_destroy(const engine *e, image *im)
{
    if (im->view)
        vkDestroyImageView(e->device, im->view, NULL);
    if (im->image)
        vkDestroyImage(e->device, im->image, NULL);
    if (im->memory)
        vkFreeMemory(e->device, im->memory, NULL);
}

static void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                           VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access)
{
    VkMemoryBarrier2 b = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2, .srcStageMask = src_stage,
                          .srcAccessMask = src_access, .dstStageMask = dst_stage, .dstAccessMask = dst_access};
    VkDependencyInfo d = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .memoryBarrierCount = 1, .pMemoryBarriers = &b};
    vkCmdPipelineBarrier2(cmd, &d);
}

/* A compute pipeline from SPIR-V compiled at build time (EXAMPLE_SPV_DIR); set_layout may
 * be VK_NULL_HANDLE. */
static int pipeline_create(const engine *e, const char *name, uint32_t push_size, VkDescriptorSetLayout set_layout,
                           VkPipelineLayout *layout, VkPipeline *pipeline)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", EXAMPLE_SPV_DIR, name);
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "example-engine: cannot open %s\n", path);
        return 0;
    }
    static uint32_t code[65536];
    size_t bytes = fread(code, 1, sizeof code, f);
    fclose(f);
    VkShaderModuleCreateInfo mi = {.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, .codeSize = bytes,
                                   .pCode = code};
    VkShaderModule module;
    if (vkCreateShaderModule(e->device, &mi, NULL, &module) != VK_SUCCESS)
        return 0;
    VkPushConstantRange range = {VK_SHADER_STAGE_COMPUTE_BIT, 0, push_size};
    VkPipelineLayoutCreateInfo li = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                     .setLayoutCount = set_layout ? 1u : 0u,
                                     .pSetLayouts = &set_layout,
                                     .pushConstantRangeCount = 1,
                                     .pPushConstantRanges = &range};
    /* roma/trace.glsl's division rule, as libroma's own pipelines have it
     * (roma_context_info.corrected_division); shaders that do not include it ignore it. */
    VkBool32 corrected = e->corrected_division;
    VkSpecializationMapEntry entry = {ROMA_CORRECTED_DIVISION_CONSTANT_ID, 0, sizeof corrected};
    VkSpecializationInfo spec = {1, &entry, sizeof corrected, &corrected};
    VkComputePipelineCreateInfo pi = {
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                  .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                  .module = module,
                  .pName = "main",
                  .pSpecializationInfo = &spec}};
    int ok = vkCreatePipelineLayout(e->device, &li, NULL, layout) == VK_SUCCESS;
    pi.layout = *layout;
    ok = ok && vkCreateComputePipelines(e->device, VK_NULL_HANDLE, 1, &pi, NULL, pipeline) == VK_SUCCESS;
    vkDestroyShaderModule(e->device, module, NULL);
    return ok;
}

/* The scene: the built-in room (x in [-1, 1], y in [0, 2], z in [-1, 2]) and a box of
 * half-size 0.15 at (0, 1.5, 0.5), above the room's two blocks: its vertices come last. */
#define BOX_HALF 0.15f
static const float box_centre[3] = {0.0f, 1.5f, 0.5f};

/* The character stands in the front-left of the room, scaled to 0.9 (its feet on the
 * floor, its head below the probe rays). */
static const float character_placement[4] = {-0.4f, 0.0f, 1.1f, 0.9f};

/* Room, then the character's vertices (placed), then the box's: the order animate.comp
 * relies on. */
static roma_scene *make_scene(roma_logger logger, const roma_scene *character, uint32_t *out_character_first,
                              uint32_t *out_character_count, uint32_t *out_box_first)
{
    roma_scene *room = NULL;
    if (roma_scene_create_builtin("cornell", &logger, &room) != ROMA_SUCCESS)
        return NULL;
    roma_scene_view v, cv = {0};
    roma_scene_get_view(room, &v);
    if (character)
        roma_scene_get_view(character, &cv);
    uint32_t room_vertices = v.vertex_count, room_triangles = v.triangle_count;
    v.vertex_count += cv.vertex_count; /* from here on: room + character */
    v.triangle_count += cv.triangle_count;
    uint32_t nv = v.vertex_count + 8, nt = v.triangle_count + 12;
    float *pos = malloc(sizeof(float) * 3 * nv);
    uint32_t *idx = malloc(sizeof(uint32_t) * 3 * nt), *mat = malloc(sizeof(uint32_t) * nt);
    roma_scene *scene = NULL;
    if (pos && idx && mat) {
        memcpy(pos, v.positions, sizeof(float) * 3 * room_vertices);
        memcpy(idx, v.indices, sizeof(uint32_t) * 3 * room_triangles);
        memcpy(mat, v.triangle_materials, sizeof(uint32_t) * room_triangles);
        for (uint32_t i = 0; i < 3 * cv.vertex_count; ++i)
            pos[3 * room_vertices + i] = cv.positions[i] * character_placement[3] + character_placement[i % 3];
        for (uint32_t i = 0; i < 3 * cv.triangle_count; ++i)
            idx[3 * room_triangles + i] = cv.indices[i] + room_vertices;
        for (uint32_t t = 0; t < cv.triangle_count; ++t)
            mat[room_triangles + t] = 0;
        for (int c = 0; c < 8; ++c)
            for (int a = 0; a < 3; ++a)
                pos[3 * (v.vertex_count + c) + a] = box_centre[a] + ((c >> a) & 1 ? BOX_HALF : -BOX_HALF);
        static const uint32_t faces[36] = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                           2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
        for (int i = 0; i < 36; ++i)
            idx[3 * v.triangle_count + i] = v.vertex_count + faces[i];
        for (int t = 0; t < 12; ++t)
            mat[v.triangle_count + t] = 0;
        roma_scene_desc d = {.positions = pos, .vertex_count = nv, .indices = idx, .triangle_count = nt,
                             .triangle_materials = mat, .materials = v.materials, .material_count = v.material_count,
                             .lights = v.lights, .light_count = v.light_count, .name = "room with a moving box",
                             .logger = logger};
        if (roma_scene_create(&d, &scene) != ROMA_SUCCESS)
            scene = NULL;
        *out_box_first = v.vertex_count;
        *out_character_first = room_vertices;
        *out_character_count = cv.vertex_count;
    }
    free(pos), free(idx), free(mat);
    roma_scene_destroy(room);
    return scene;
}

static float box_offset(uint32_t frame)
{
    return -0.6f + 0.3f * (float)(frame % 5);
}

/* Probe rays along -z at the box's height, from the front wall, x across the room. */
static void make_probes(probe_ray *rays)
{
    for (int i = 0; i < PROBES; ++i) {
        float x = -0.92f + 1.84f * (float)i / (PROBES - 1);
        rays[i] = (probe_ray){{x, box_centre[1], 1.8f, 4.0f}, {0.0f, 0.0f, -1.0f, 0.0f}};
    }
}

/* Rays through the box hit it (front face at t = 1.15, or its back face at 1.45 where the
 * walk stepped over the front one); the others hit nothing before the back wall (t 2.8).
 * `cell` is the map's trace cell (the longest edge a rotated cell can have): rays within
 * two of them of the box's sides are not judged. */
static int wrong_answers(const probe_ray *rays, const roma_hit *hits, float box_x, float cell)
{
    const float front = 1.8f - (box_centre[2] + BOX_HALF), back = front + 2.0f * BOX_HALF;
    int wrong = 0;
    for (int i = 0; i < PROBES; ++i) {
        float dx = rays[i].origin[0] - box_x;
        dx = dx < 0 ? -dx : dx;
        int hit = (hits[i].info & ROMA_HIT_FLAG) != 0;
        if (dx < BOX_HALF - 2.0f * cell)
            wrong += !hit || hits[i].t < front - 4.0f * cell || hits[i].t > back + 4.0f * cell;
        else if (dx > BOX_HALF + 2.0f * cell)
            wrong += hit && hits[i].t < back + 4.0f * cell;
        if (getenv("EXAMPLE_VERBOSE"))
            printf("  x %.3f box %.3f: %s t %.4f (cell %.4f)\n", (double)rays[i].origin[0], (double)box_x,
                   hit ? "hit" : "miss", (double)hits[i].t, (double)cell);
    }
    return wrong;
}

static long resident_kib(void)
{
    long pages = 0, resident = 0;
    FILE *f = fopen("/proc/self/statm", "r");
    if (f) {
        if (fscanf(f, "%ld %ld", &pages, &resident) != 2)
            resident = 0;
        fclose(f);
    }
    return resident * 4;
}

int main(int argc, char **argv)
{
    uint32_t frames = 12;
    int validation = 0;
    const char *character_path = NULL;
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--frames") == 0 && i + 1 < argc)
            frames = (uint32_t)strtoul(argv[++i], NULL, 10);
        else if (strcmp(argv[i], "--validation") == 0)
            validation = 1;
        else if (strcmp(argv[i], "--sync-validation") == 0)
            validation = 2;
        else if (strcmp(argv[i], "--character") == 0 && i + 1 < argc)
            character_path = argv[++i];
        else {
            fprintf(stderr, "usage: example-engine [--frames N] [--validation | --sync-validation] "
                            "[--character file.glb]\n");
            return 2;
        }
    }
    engine e = {0};
    roma_device_requirements req;
    if (!create_instance(&e, validation) || !create_device(&e, &req))
        return 1;

    /* libroma on the engine's device and queue. */
    roma_logger logger = {log_to_stderr, NULL};
    roma_external_device ext = {e.instance, e.physical, e.device, e.family, e.queue, &req.features};
    roma_context_desc cd = {.external = &ext, .logger = logger};
    roma_context *ctx = NULL;
    uint32_t box_first = 0, character_first = 0, character_count = 0;
    roma_scene *scene = NULL, *character = NULL;
    roma_animator *animator = NULL;
    roma_map *map = NULL;
    int status = 1;
    if (roma_context_create(&cd, &ctx) != ROMA_SUCCESS)
        goto done;
    roma_context_info context_info;
    roma_context_get_info(ctx, &context_info);
    e.corrected_division = context_info.corrected_division;
    if (character_path) {
        roma_gltf_desc gd = {.logger = logger};
        if (roma_scene_load_gltf(character_path, &gd, &character) != ROMA_SUCCESS ||
            roma_animator_create(ctx, character, &(roma_animator_desc){.frames_in_flight = SLOTS}, &animator) !=
                ROMA_SUCCESS)
            goto done;
    }
    if (!(scene = make_scene(logger, character, &character_first, &character_count, &box_first)))
        goto done;
    roma_map_desc md = {.resolution = 128, .angular = 4, .frames_in_flight = SLOTS};
    if (roma_map_create(ctx, &md, scene, &map) != ROMA_SUCCESS)
        goto done;
    roma_scene_view sv;
    roma_scene_get_view(scene, &sv);
    /* The volume libroma traces: the room, a little larger (the box stays inside it). */
    const roma_box volume = {{-1.05f, -0.05f, -1.05f}, {1.05f, 2.05f, 2.05f}};

    /* The engine's buffers, pipelines and per-slot objects. */
    buffer rest, positions, rays[SLOTS], hits[SLOTS];
    memset(rays, 0, sizeof rays), memset(hits, 0, sizeof hits);
    int ok = buffer_create(&e, 12ull * sv.vertex_count, 1, &rest) &&
             buffer_create(&e, 12ull * sv.vertex_count, 0, &positions);
    for (int s = 0; s < SLOTS && ok; ++s)
        ok = buffer_create(&e, sizeof(probe_ray) * PROBES, 1, &rays[s]) &&
             buffer_create(&e, sizeof(roma_hit) * PROBES, 1, &hits[s]);
    VkPipelineLayout animate_layout = VK_NULL_HANDLE, probe_layout = VK_NULL_HANDLE;
    VkPipeline animate = VK_NULL_HANDLE, probe = VK_NULL_HANDLE;
    ok = ok && pipeline_create(&e, "animate.spv", 80, VK_NULL_HANDLE, &animate_layout, &animate) &&
         pipeline_create(&e, "probe.spv", 40, VK_NULL_HANDLE, &probe_layout, &probe);
    /* The floor G-buffer and the AO it gets from libroma. */
    image gb_position = {0}, gb_normal = {0}, ao_image = {0}, history[2] = {{0}, {0}};
    buffer ao_readback[SLOTS], history_readback[SLOTS];
    memset(ao_readback, 0, sizeof ao_readback);
    memset(history_readback, 0, sizeof history_readback);
    roma_temporal_effect *temporal = NULL;
    VkDescriptorSetLayout gb_set_layout = VK_NULL_HANDLE;
    VkDescriptorPool gb_pool = VK_NULL_HANDLE;
    VkDescriptorSet gb_set = VK_NULL_HANDLE;
    VkPipelineLayout gb_layout = VK_NULL_HANDLE;
    VkPipeline gb_pipeline = VK_NULL_HANDLE;
    roma_ao_effect *ao = NULL;
    const VkImageUsageFlags gb_usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    ok = ok && image_create(&e, VK_FORMAT_R32G32B32A32_SFLOAT, gb_usage, &gb_position) &&
         image_create(&e, VK_FORMAT_R32G32B32A32_SFLOAT, gb_usage, &gb_normal) &&
         image_create(&e, VK_FORMAT_R32_SFLOAT, gb_usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, &ao_image) &&
         image_create(&e, VK_FORMAT_R32G32B32A32_SFLOAT, gb_usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, &history[0]) &&
         image_create(&e, VK_FORMAT_R32G32B32A32_SFLOAT, gb_usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, &history[1]);
    for (int s = 0; s < SLOTS && ok; ++s)
        ok = buffer_create(&e, 4ull * GB_W * GB_H, 1, &ao_readback[s]) &&
             buffer_create(&e, 16ull * GB_W * GB_H, 1, &history_readback[s]);
    ok = ok && roma_temporal_effect_create(ctx, &(roma_temporal_effect_desc){.frames_in_flight = SLOTS}, &temporal) ==
                   ROMA_SUCCESS;
    if (ok) {
        VkDescriptorSetLayoutBinding b[2] = {{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, NULL},
                                             {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, NULL}};
        VkDescriptorSetLayoutCreateInfo sli = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                               .bindingCount = 2, .pBindings = b};
        VkDescriptorPoolSize size = {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 2};
        VkDescriptorPoolCreateInfo dpi = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, .maxSets = 1,
                                          .poolSizeCount = 1, .pPoolSizes = &size};
        ok = vkCreateDescriptorSetLayout(e.device, &sli, NULL, &gb_set_layout) == VK_SUCCESS &&
             vkCreateDescriptorPool(e.device, &dpi, NULL, &gb_pool) == VK_SUCCESS;
        VkDescriptorSetAllocateInfo dai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                           .descriptorPool = gb_pool, .descriptorSetCount = 1,
                                           .pSetLayouts = &gb_set_layout};
        ok = ok && vkAllocateDescriptorSets(e.device, &dai, &gb_set) == VK_SUCCESS;
        if (ok) {
            VkDescriptorImageInfo ii[2] = {{VK_NULL_HANDLE, gb_position.view, VK_IMAGE_LAYOUT_GENERAL},
                                           {VK_NULL_HANDLE, gb_normal.view, VK_IMAGE_LAYOUT_GENERAL}};
            VkWriteDescriptorSet w[2];
            for (uint32_t i = 0; i < 2; ++i)
                w[i] = (VkWriteDescriptorSet){.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = gb_set,
                                              .dstBinding = i, .descriptorCount = 1,
                                              .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, .pImageInfo = &ii[i]};
            vkUpdateDescriptorSets(e.device, 2, w, 0, NULL);
        }
        ok = ok && pipeline_create(&e, "gbuffer.spv", 32, gb_set_layout, &gb_layout, &gb_pipeline) &&
             roma_ao_effect_create(ctx, &(roma_ao_effect_desc){.frames_in_flight = SLOTS}, &ao) == ROMA_SUCCESS;
    }
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmds[SLOTS];
    VkFence fences[SLOTS] = {VK_NULL_HANDLE, VK_NULL_HANDLE};
    VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                  .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                  .queueFamilyIndex = e.family};
    ok = ok && vkCreateCommandPool(e.device, &pi, NULL, &pool) == VK_SUCCESS;
    VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                      .commandPool = pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                      .commandBufferCount = SLOTS};
    ok = ok && vkAllocateCommandBuffers(e.device, &ai, cmds) == VK_SUCCESS;
    if (ok) { /* the five images to GENERAL once, before the first frame */
        VkCommandBufferBeginInfo once = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                         .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
        vkBeginCommandBuffer(cmds[0], &once);
        VkImageMemoryBarrier2 to_general[5];
        const VkImage imgs[5] = {gb_position.image, gb_normal.image, ao_image.image, history[0].image,
                                 history[1].image};
        for (int i = 0; i < 5; ++i)
            to_general[i] = (VkImageMemoryBarrier2){
                .sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2, .dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                .dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, .oldLayout = VK_IMAGE_LAYOUT_UNDEFINED,
                .newLayout = VK_IMAGE_LAYOUT_GENERAL, .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED, .image = imgs[i],
                .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
        VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .imageMemoryBarrierCount = 5,
                                .pImageMemoryBarriers = to_general};
        vkCmdPipelineBarrier2(cmds[0], &dep);
        vkEndCommandBuffer(cmds[0]);
        VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &cmds[0]};
        ok = vkQueueSubmit(e.queue, 1, &si, VK_NULL_HANDLE) == VK_SUCCESS && vkQueueWaitIdle(e.queue) == VK_SUCCESS;
    }
    for (int s = 0; s < SLOTS && ok; ++s) {
        VkFenceCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, .flags = VK_FENCE_CREATE_SIGNALED_BIT};
        ok = vkCreateFence(e.device, &fi, NULL, &fences[s]) == VK_SUCCESS;
    }
    if (!ok) {
        fprintf(stderr, "example-engine: setting up the engine's objects failed\n");
        goto cleanup;
    }
    memcpy(rest.mapped, sv.positions, 12ull * sv.vertex_count);
    probe_ray probes[PROBES];
    make_probes(probes);

    roma_map_info info;
    roma_map_get_info(map, &info);
    uint32_t in_flight[SLOTS] = {UINT32_MAX, UINT32_MAX};
    float cell = info.trace_cell;
    int wrong = 0;
    uint32_t judged = 0;
    long rss_100 = 0;
    uint32_t outside_volume = 0;
    uint64_t device_100 = 0;
    for (uint32_t f = 0; f < frames + SLOTS; ++f) {
        uint32_t s = f % SLOTS;
        vkWaitForFences(e.device, 1, &fences[s], VK_TRUE, UINT64_MAX);
        if (in_flight[s] != UINT32_MAX) {
            int w = wrong_answers(probes, hits[s].mapped, box_centre[0] + box_offset(in_flight[s]), cell);
            /* The floor's AO (radius 0.3), averaged over 4 x 4 pixels (256 rays): in the
             * back-left corner the two walls hide much of the sky (about 0.4; in 88 of 10,000
             * frames the frame's jitter let rays through the corner and it read above 0.6),
             * in the open (around (0.5, 1.3)) nothing does (1.0 in every frame). */
            const float *aov = ao_readback[s].mapped;
            float corner = 0.0f, open = 0.0f;
            for (uint32_t dy = 0; dy < 4; ++dy)
                for (uint32_t dx = 0; dx < 4; ++dx) {
                    corner += aov[dy * GB_W + dx] / 16.0f; /* x, z in [-1, -0.875] */
                    open += aov[(uint32_t)((1.3f + 1.0f) / 3.0f * GB_H + dy) * GB_W +
                                (uint32_t)((0.5f + 1.0f) / 2.0f * GB_W) + dx] / 16.0f;
                }
            if (getenv("EXAMPLE_VERBOSE"))
                printf("frame %u: AO in the corner %.3f, in the open %.3f\n", in_flight[s], (double)corner, (double)open);
            if (!(corner < 0.8f) || !(open > 0.9f)) {
                fprintf(stderr, "frame %u: AO in the corner %.3f, in the open %.3f\n", in_flight[s], (double)corner,
                        (double)open);
                ++w;
            }
            /* The same averaged over the frames so far (at most 32): every floor pixel holds
             * min(frame + 1, 32) frames; the corner stays dark, the open stays open. */
            const float *acc = history_readback[s].mapped;
            float acc_corner = 0.0f, acc_open = 0.0f;
            uint32_t wrong_count = 0;
            for (uint32_t p = 0; p < GB_W * GB_H; ++p)
                wrong_count += acc[4 * p + 3] != (float)(in_flight[s] + 1 < 32 ? in_flight[s] + 1 : 32);
            for (uint32_t dy = 0; dy < 4; ++dy)
                for (uint32_t dx = 0; dx < 4; ++dx) {
                    acc_corner += acc[4 * (dy * GB_W + dx)] / 16.0f;
                    acc_open += acc[4 * ((uint32_t)((1.3f + 1.0f) / 3.0f * GB_H + dy) * GB_W +
                                         (uint32_t)((0.5f + 1.0f) / 2.0f * GB_W) + dx)] / 16.0f;
                }
            if (wrong_count || !(acc_corner < 0.8f) || !(acc_open > 0.9f)) {
                fprintf(stderr, "frame %u: averaged AO in the corner %.3f, in the open %.3f, %u pixels with the "
                        "wrong history length\n", in_flight[s], (double)acc_corner, (double)acc_open, wrong_count);
                ++w;
            }
            if (getenv("EXAMPLE_VERBOSE"))
                printf("frame %u: averaged AO in the corner %.3f, in the open %.3f\n", in_flight[s],
                       (double)acc_corner, (double)acc_open);
            if (w)
                fprintf(stderr, "frame %u: %d wrong probe answers\n", in_flight[s], w);
            wrong += w;
            ++judged;
            in_flight[s] = UINT32_MAX;
        }
        if (f == 100) {
            roma_context_info ci;
            roma_context_get_info(ctx, &ci);
            rss_100 = resident_kib(), device_100 = ci.device_memory_in_use;
        }
        if (f >= frames)
            continue;
        memcpy(rays[s].mapped, probes, sizeof probes);
        vkResetFences(e.device, 1, &fences[s]);
        vkResetCommandBuffer(cmds[s], 0);
        VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                       .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
        vkBeginCommandBuffer(cmds[s], &bi);
        /* 1. libroma skins the character; 2. the engine's animation places it and moves
         *    the box (a compute-to-compute barrier between the two); libroma's build opens
         *    with a barrier after every earlier command, so the positions need no other. */
        roma_animator_output skinned = {0};
        if (animator) {
            roma_animator_pose pose = {0, (float)f / 30.0f};
            if (roma_animator_record(animator, cmds[s], s, &pose, &skinned) != ROMA_SUCCESS)
                goto cleanup;
            VkMemoryBarrier2 skin_done = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2,
                                          .srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                          .srcAccessMask = VK_ACCESS_2_SHADER_WRITE_BIT,
                                          .dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                          .dstAccessMask = VK_ACCESS_2_SHADER_READ_BIT};
            VkDependencyInfo skin_dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .memoryBarrierCount = 1,
                                         .pMemoryBarriers = &skin_done};
            vkCmdPipelineBarrier2(cmds[s], &skin_dep);
            for (int a = 0; a < 3; ++a) /* the placed character stays inside the traced volume */
                if (skinned.bounds.min[a] * character_placement[3] + character_placement[a] < volume.min[a] ||
                    skinned.bounds.max[a] * character_placement[3] + character_placement[a] > volume.max[a])
                    ++outside_volume;
        }
        struct {
            VkDeviceAddress rest, positions, skinned;
            uint32_t vertex_count, object_first, character_first, character_count;
            float pad[2], offset[4], placement[4];
        } anim = {rest.address, positions.address, skinned.positions, sv.vertex_count, box_first, character_first,
                  character_count, {0, 0}, {box_offset(f), 0, 0, 0},
                  {character_placement[0], character_placement[1], character_placement[2], character_placement[3]}};
        vkCmdBindPipeline(cmds[s], VK_PIPELINE_BIND_POINT_COMPUTE, animate);
        vkCmdPushConstants(cmds[s], animate_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof anim, &anim);
        vkCmdDispatch(cmds[s], (sv.vertex_count + 63) / 64, 1, 1);
        /* 2. libroma's build from those positions. */
        roma_map_frame_desc fd = {.frame = f, .seed = 1, .jitter_grid = 1, .jitter_directions = 1, .slot = s,
                                  .volume = &volume, .gpu_positions = positions.address,
                                  .vertex_count = sv.vertex_count};
        if (roma_map_record_build(map, cmds[s], &fd, NULL) != ROMA_SUCCESS)
            goto cleanup;
        /* 3. The engine's probe rays (the build ends with a barrier that makes the maps
         *    readable by any later command). */
        roma_map_get_info(map, &info);
        cell = info.trace_cell;
        struct {
            VkDeviceAddress params, maps, rays, hits;
            uint32_t count, max_steps;
        } pp = {info.params_address, info.maps_address, rays[s].address, hits[s].address, PROBES, MAX_STEPS};
        vkCmdBindPipeline(cmds[s], VK_PIPELINE_BIND_POINT_COMPUTE, probe);
        vkCmdPushConstants(cmds[s], probe_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof pp, &pp);
        vkCmdDispatch(cmds[s], 1, 1, 1);
        /* 5. The floor G-buffer (after the last frame's readers of it: the build's opening
         *    barrier already orders them, this one says so), then libroma's AO on it. */
        memory_barrier(cmds[s], VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        struct {
            uint32_t size[2];
            float pad[2], area[4];
        } gp = {{GB_W, GB_H}, {0, 0}, {-1.0f, -1.0f, 1.0f, 2.0f}};
        vkCmdBindPipeline(cmds[s], VK_PIPELINE_BIND_POINT_COMPUTE, gb_pipeline);
        vkCmdBindDescriptorSets(cmds[s], VK_PIPELINE_BIND_POINT_COMPUTE, gb_layout, 0, 1, &gb_set, 0, NULL);
        vkCmdPushConstants(cmds[s], gb_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof gp, &gp);
        vkCmdDispatch(cmds[s], GB_W / 8, GB_H / 8, 1);
        memory_barrier(cmds[s], VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
        roma_ao_images images = {.width = GB_W, .height = GB_H, .position = gb_position.view,
                                 .normal = gb_normal.view, .output = ao_image.view,
                                 .input_layout = VK_IMAGE_LAYOUT_GENERAL};
        roma_ao_settings settings = {.samples = 16, .radius = AO_RADIUS, .seed = 1, .frame = f};
        if (roma_ao_effect_record(ao, cmds[s], s, map, &images, &settings) != ROMA_SUCCESS)
            goto cleanup;
        /* 6. The AO averaged over frames: this frame writes history[f % 2] and reads the
         *    other, which the previous frame wrote (the camera stands still: the zero
         *    matrix). The AO's writes and last frame's history, read by the effect. */
        memory_barrier(cmds[s], VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        const image *written = &history[f % 2], *previous = &history[(f + 1) % 2];
        roma_temporal_images ti = {.width = GB_W, .height = GB_H, .current = ao_image.view,
                                   .position = gb_position.view, .normal = gb_normal.view,
                                   .previous_position = gb_position.view, .history = previous->view,
                                   .accumulated = written->view, .input_layout = VK_IMAGE_LAYOUT_GENERAL};
        roma_temporal_settings ts = {.reset = f == 0, .frame = f};
        if (roma_temporal_effect_record(temporal, cmds[s], s, &ti, &ts) != ROMA_SUCCESS)
            goto cleanup;
        memory_barrier(cmds[s], VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferImageCopy back = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, .imageExtent = {GB_W, GB_H, 1}};
        vkCmdCopyImageToBuffer(cmds[s], ao_image.image, VK_IMAGE_LAYOUT_GENERAL, ao_readback[s].buffer, 1, &back);
        vkCmdCopyImageToBuffer(cmds[s], written->image, VK_IMAGE_LAYOUT_GENERAL, history_readback[s].buffer, 1, &back);
        VkMemoryBarrier2 to_host = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2,
                                    .srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                                    .srcAccessMask = VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                    .dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT,
                                    .dstAccessMask = VK_ACCESS_2_HOST_READ_BIT};
        VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .memoryBarrierCount = 1,
                                .pMemoryBarriers = &to_host};
        vkCmdPipelineBarrier2(cmds[s], &dep);
        vkEndCommandBuffer(cmds[s]);
        VkSubmitInfo submit = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1,
                               .pCommandBuffers = &cmds[s]};
        if (vkQueueSubmit(e.queue, 1, &submit, fences[s]) != VK_SUCCESS)
            goto cleanup;
        in_flight[s] = f;
    }
    roma_context_info ci;
    roma_context_get_info(ctx, &ci);
    printf("example-engine: %u frames%s, %d wrong probe answers of %u judged frames x %d rays, "
           "%u frames with the character outside the volume, %u validation messages; libroma submitted %llu "
           "times (object creation only)\n",
           frames, animator ? " with an animated character" : "", wrong, judged, PROBES, outside_volume,
           e.validation_messages, (unsigned long long)ci.queue_submits);
    if (frames > 100)
        printf("soak: resident memory %ld KiB at frame 100, %ld KiB at the end; libroma device memory %llu B at "
               "frame 100, %llu B at the end\n",
               rss_100, resident_kib(), (unsigned long long)device_100, (unsigned long long)ci.device_memory_in_use);
    status = wrong == 0 && judged == frames && outside_volume == 0 && e.validation_messages == 0 ? 0 : 1;
cleanup:
    vkDeviceWaitIdle(e.device);
    for (int s = 0; s < SLOTS; ++s) {
        if (fences[s])
            vkDestroyFence(e.device, fences[s], NULL);
        buffer_destroy(&e, &rays[s]);
        buffer_destroy(&e, &hits[s]);
    }
    if (pool)
        vkDestroyCommandPool(e.device, pool, NULL);
    if (animate)
        vkDestroyPipeline(e.device, animate, NULL);
    if (probe)
        vkDestroyPipeline(e.device, probe, NULL);
    if (animate_layout)
        vkDestroyPipelineLayout(e.device, animate_layout, NULL);
    if (probe_layout)
        vkDestroyPipelineLayout(e.device, probe_layout, NULL);
    roma_ao_effect_destroy(ao);
    if (gb_pipeline)
        vkDestroyPipeline(e.device, gb_pipeline, NULL);
    if (gb_layout)
        vkDestroyPipelineLayout(e.device, gb_layout, NULL);
    if (gb_pool)
        vkDestroyDescriptorPool(e.device, gb_pool, NULL);
    if (gb_set_layout)
        vkDestroyDescriptorSetLayout(e.device, gb_set_layout, NULL);
    image_destroy(&e, &gb_position);
    image_destroy(&e, &gb_normal);
    image_destroy(&e, &ao_image);
    image_destroy(&e, &history[0]);
    image_destroy(&e, &history[1]);
    roma_temporal_effect_destroy(temporal);
    for (int s = 0; s < SLOTS; ++s) {
        buffer_destroy(&e, &ao_readback[s]);
        buffer_destroy(&e, &history_readback[s]);
    }
    buffer_destroy(&e, &rest);
    buffer_destroy(&e, &positions);
done:
    roma_map_destroy(map);
    roma_animator_destroy(animator);
    roma_scene_destroy(character);
    roma_scene_destroy(scene);
    roma_context_destroy(ctx);
    if (e.device)
        vkDestroyDevice(e.device, NULL);
    if (e.messenger) {
        PFN_vkDestroyDebugUtilsMessengerEXT destroy =
            (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(e.instance, "vkDestroyDebugUtilsMessengerEXT");
        if (destroy)
            destroy(e.instance, e.messenger, NULL);
    }
    if (e.instance)
        vkDestroyInstance(e.instance, NULL);
    if (status == 0 && e.validation_messages)
        status = 1;
    return status;
}
