/** @file
 * libroma: glTF 2.0 scene loading (separate target roma_gltf, C API over tinygltf).
 *
 * All mesh primitives of mode TRIANGLES (also strips and fans, converted) are
 * flattened into world space through the node hierarchy of the default scene
 * (or of every root node when the file names none). Per primitive: base
 * colour factor and emissive factor (times KHR_materials_emissive_strength).
 * KHR_lights_punctual lights and the first camera met in the node walk are
 * kept. Skins and animations are kept as roma_scene_animation_data; geometry
 * is the rest pose (skinned meshes are skinned with the rest-pose joints).
 * Morph targets are ignored (base mesh), with a warning. Textures are ignored.
 * Not supported (ROMA_ERROR_UNSUPPORTED): sparse accessors, and any required
 * extension other than KHR_lights_punctual, KHR_materials_emissive_strength
 * and KHR_texture_transform (so no Draco, meshopt or KHR_mesh_quantization).
 * NaN normals in a file (some exporters write them on zero-area faces) are
 * replaced by face normals with a warning rather than rejected.
 *
 * Errors never leave a partial scene: *out_scene is NULL on failure. */
#ifndef ROMA_GLTF_H
#define ROMA_GLTF_H

#include "roma/api.h"

#include <stddef.h>
#include <stdint.h>

#include "roma/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Settings of the glTF loader; the zero value is the default. */
typedef struct roma_gltf_desc {
    roma_logger logger; /**< where the loader's warnings and errors go; zero: stderr */
    /** Limits on the flattened scene, checked before anything is allocated for it
     * (instancing and accessors without data can make a few hundred bytes of
     * glTF describe gigabytes): a file over either is ROMA_ERROR_UNSUPPORTED.
     * 0 = ROMA_GLTF_DEFAULT_MAX_VERTICES / ROMA_GLTF_DEFAULT_MAX_TRIANGLES. */
    uint32_t max_vertices;
    uint32_t max_triangles; /**< see max_vertices */
    /** Which perspective camera, in the order the default scene's nodes are visited, becomes the
     * scene's camera: 0 = the first. A file with fewer is ROMA_ERROR_INVALID_ARGUMENT (the
     * message gives how many it has); a file with none and 0 gives a scene without camera. */
    uint32_t camera_index;
} roma_gltf_desc;

/** Default of roma_gltf_desc.max_vertices. */
#define ROMA_GLTF_DEFAULT_MAX_VERTICES (1u << 25)
/** Default of roma_gltf_desc.max_triangles. */
#define ROMA_GLTF_DEFAULT_MAX_TRIANGLES (1u << 25)

/** path ends in .gltf or .glb (detected from content, not the name). desc may be NULL. */
ROMA_API roma_result roma_scene_load_gltf(const char *path, const roma_gltf_desc *desc,
                                          roma_scene **out_scene);

/** From memory. base_dir resolves external buffers (may be NULL: external URIs are
 * then an error). The data is not kept. */
ROMA_API roma_result roma_scene_load_gltf_memory(const void *data, size_t size, const char *base_dir,
                                                 const roma_gltf_desc *desc, roma_scene **out_scene);

#ifdef __cplusplus
}
#endif

#endif /**< ROMA_GLTF_H */
