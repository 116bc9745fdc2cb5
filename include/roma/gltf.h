/** @file
 * libroma: glTF 2.0 scene loading (separate target roma_gltf, C API over tinygltf).
 *
 * All mesh primitives of mode TRIANGLES (also strips and fans, converted) are
 * flattened into world space through the node hierarchy of the default scene
 * (or of every root node when the file names none). Per primitive: base
 * colour factor and emissive factor (times KHR_materials_emissive_strength).
 * KHR_lights_punctual lights are kept; every perspective camera met in the node walk is
 * listed (roma_scene_view.cameras) and the one roma_gltf_desc.camera_index names (the first
 * by default) becomes the scene's camera. Skins and animations are kept as roma_scene_animation_data; geometry
 * is the rest pose (skinned meshes are skinned with the rest-pose joints).
 * Morph targets are ignored (base mesh), with a warning. Textures are ignored.
 * Not supported (ROMA_ERROR_UNSUPPORTED): sparse accessors, and any required
 * extension other than KHR_lights_punctual, KHR_materials_emissive_strength
 * and KHR_texture_transform (so no Draco, meshopt or KHR_mesh_quantization).
 * NaN normals in a file (some exporters write them on zero-area faces) are
 * replaced by face normals with a warning rather than rejected.
 *
 * Errors never leave a partial scene: *out_scene is NULL on failure. The loaders keep no
 * state: any thread, any number at once. */
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

/** Loads a glTF 2.0 file into a new scene.
 *
 * @param path   a .gltf or .glb file (detected from content, not the name); external
 *               buffers are resolved relative to its directory.
 * @param desc   settings; may be NULL (the zero value: stderr, default limits, camera 0).
 * @param[out] out_scene  the new scene, owned by the caller (roma_scene_destroy); NULL on
 *               failure.
 * @return ROMA_SUCCESS;
 *   ROMA_ERROR_INVALID_ARGUMENT: NULL path or out_scene, a camera_index the file lacks;
 *   ROMA_ERROR_FILE_NOT_FOUND: path or an external buffer it names does not exist;
 *   ROMA_ERROR_IO: path cannot be opened or read;
 *   ROMA_ERROR_PARSE: malformed JSON or GLB container, an empty file;
 *   ROMA_ERROR_UNSUPPORTED: see the file comment, a file over max_vertices or max_triangles,
 *   a file of 4 GiB or more, a glTF version other than 2;
 *   ROMA_ERROR_INVALID_SCENE, ROMA_ERROR_EMPTY_SCENE: unusable data, as roma_scene_create;
 *   ROMA_ERROR_OUT_OF_HOST_MEMORY.
 * @par Threads
 * Any thread. */
ROMA_API roma_result roma_scene_load_gltf(const char *path, const roma_gltf_desc *desc,
                                          roma_scene **out_scene);

/** Loads a glTF 2.0 file (.gltf text or .glb) from memory. The data is not kept.
 *
 * @param data      the file's bytes; may be NULL only when size is 0 (then ROMA_ERROR_PARSE).
 * @param size      bytes at data.
 * @param base_dir  directory that resolves external buffers (may be NULL: external URIs are
 *                  then an error, ROMA_ERROR_FILE_NOT_FOUND).
 * @param desc      settings; may be NULL (the zero value).
 * @param[out] out_scene  the new scene, owned by the caller; NULL on failure.
 * @return the codes of roma_scene_load_gltf but ROMA_ERROR_IO (ROMA_ERROR_INVALID_ARGUMENT
 *         also for NULL data with a non-zero size).
 * @par Threads
 * Any thread. */
ROMA_API roma_result roma_scene_load_gltf_memory(const void *data, size_t size, const char *base_dir,
                                                 const roma_gltf_desc *desc, roma_scene **out_scene);

#ifdef __cplusplus
}
#endif

#endif /* ROMA_GLTF_H */
