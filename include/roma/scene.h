/** @file
 * libroma: triangle scenes.
 *
 * A roma_scene is an immutable, world-space triangle soup with per-triangle
 * materials, punctual lights, area lights (emissive triangles) and an optional
 * camera. It is built from caller arrays (roma_scene_create), from a glTF file
 * (roma/gltf.h) or from a built-in generator (roma_scene_create_builtin).
 * Every builder validates all of its input first and either returns a complete
 * scene or nothing: on failure *out_scene is NULL.
 *
 * All surfaces are two-sided Lambertian reflectors.
 *
 * Threads: a scene is immutable, so any number of threads may read it (views, maps, effects)
 * at once; roma_scene_set_animation_data and roma_scene_destroy need it to themselves. */
#ifndef ROMA_SCENE_H
#define ROMA_SCENE_H

#include "roma/api.h"

#include <stddef.h>
#include <stdint.h>

#include "roma/camera.h"
#include "roma/result.h"

#ifdef __cplusplus
extern "C" {
#endif

/** An immutable triangle scene with materials, lights, camera and animation data (opaque). Safe to
 * read from several threads; destroyed by one. */
typedef struct roma_scene roma_scene;

/** A diffuse material. */
typedef struct roma_material {
    float base_color[3]; /**< linear albedo in [0,1] */
    float emission[3];   /**< emitted radiance, linear; non-zero makes the triangles area lights */
} roma_material;

/** Kinds of punctual light (glTF KHR_lights_punctual). */
typedef enum roma_light_type {
    ROMA_LIGHT_POINT = 1,   /**< emits from position in every direction */
    ROMA_LIGHT_SPOT,        /**< emits from position inside a cone around direction */
    ROMA_LIGHT_DIRECTIONAL  /**< parallel light along direction (the sun) */
} roma_light_type;

/** A punctual light. Units follow KHR_lights_punctual: intensity is in candela (W/sr after
 * multiplying by color) for point and spot lights, in lux (W/m^2) for
 * directional lights. */
typedef struct roma_light {
    roma_light_type type; /**< point, spot or directional */
    float position[3];      /**< world space; unused for directional lights */
    float direction[3];     /**< world space, unit: where the light points (spot, directional) */
    float color[3];         /**< linear RGB */
    float intensity; /**< candela (point, spot) or lux (directional), as KHR_lights_punctual */
    float range;            /**< 0 = unlimited; otherwise the glTF-recommended window applies */
    float inner_cone_angle; /**< radians, spot lights only */
    float outer_cone_angle; /**< radians, spot lights only; 0 means pi/4 */
} roma_light;

/** Arrays roma_scene_create validates and copies (the caller keeps ownership). */
typedef struct roma_scene_desc {
    const float *positions;           /**< 3 floats per vertex, world space */
    const float *normals;             /**< optional, 3 per vertex; computed from faces when NULL */
    uint32_t vertex_count; /**< vertices */
    const uint32_t *indices;          /**< 3 per triangle */
    uint32_t triangle_count; /**< triangles */
    const uint32_t *triangle_materials; /**< optional, one per triangle; NULL = material 0 */
    const roma_material *materials;   /**< optional; NULL = one grey material (albedo 0.8) */
    uint32_t material_count; /**< materials */
    const roma_light *lights;         /**< optional punctual lights */
    uint32_t light_count; /**< lights */
    const roma_camera *camera;        /**< optional: the scene's camera */
    /** Optional: the viewpoints the scene offers (a glTF file's perspective cameras, in the
     * order roma_gltf_desc.camera_index counts them), for a viewer to list; copied. */
    const roma_camera *cameras;
    uint32_t camera_count; /**< entries of cameras */
    const char *name;                 /**< optional, copied; shown in logs and stats */
    roma_logger logger; /**< where validation messages go; zero: stderr */
} roma_scene_desc;

/** Creates a scene: validates and copies the arrays. Rejects: NULL/zero arrays, indices >=
 * vertex_count, material indices >= material_count, NaN/Inf positions, normals, light or camera data,
 * negative colours, base colours above 1, spot cones outside 0 <= inner <= outer <= pi/2,
 * zero light directions (spot, directional), no triangle with non-zero area
 * (ROMA_ERROR_EMPTY_SCENE).
 * Zero-area triangles are kept in the arrays (they hit nothing) and counted in
 * roma_scene_view.degenerate_triangle_count; "zero area" includes slivers whose
 * squared cross product is below 1e-14 |e1|^2 |e2|^2 (sine of the angle < 1e-7).
 * Given normals of zero length fall back to the face normals, with a warning. Light
 * directions are normalised and a spot light's outer_cone_angle of 0 becomes pi/4.
 *
 * @param desc  the arrays and settings; nothing of it is kept (the caller keeps ownership).
 * @param[out] out_scene  the new scene; NULL on failure. Destroy it with roma_scene_destroy.
 * @return ROMA_SUCCESS;
 *   ROMA_ERROR_INVALID_ARGUMENT: NULL desc or out_scene, a NULL array with a non-zero count;
 *   ROMA_ERROR_EMPTY_SCENE: no triangles, or none with non-zero area;
 *   ROMA_ERROR_INVALID_SCENE: out-of-range indices, non-finite or out-of-range values, an
 *   unknown light type, a zero light direction, a bad spot cone;
 *   ROMA_ERROR_OUT_OF_HOST_MEMORY.
 * @par Threads
 * Any thread (touches only its arguments). */
ROMA_API roma_result roma_scene_create(const roma_scene_desc *desc, roma_scene **out_scene);

/** Frees a scene and its arrays (views of it become invalid). Maps, effects and animators made
 * from it copied what they need and do not depend on it.
 *
 * @param scene  the scene, or NULL (nothing is done).
 * @par Threads
 * No other thread may use the scene during or after the call. */
ROMA_API void roma_scene_destroy(roma_scene *scene);

/* Built-in test scenes: roma/builtin_scenes.h (library roma_tools). */

/* --- Data kept for animation (glTF skins and animations); rest pose is what
 *     the triangle arrays hold. All arrays may be empty. --- */

/** A node of the glTF hierarchy at rest. */
typedef struct roma_scene_node {
    int32_t parent;          /**< index into nodes, -1 for roots */
    int32_t skin;            /**< index into skins, -1 if none */
    float translation[3];    /**< local TRS at rest */
    float rotation[4];       /**< quaternion x, y, z, w */
    float scale[3]; /**< rest scale */
    float world[16];         /**< column-major world matrix at rest */
} roma_scene_node;

/** A skin: a range of joints. */
typedef struct roma_scene_skin {
    uint32_t first_joint;    /**< range into roma_scene_animation_data.joint_nodes and inverse_binds */
    uint32_t joint_count; /**< joints of the skin (entries of joint_nodes from first_joint) */
} roma_scene_skin;

/** What an animation channel drives. */
typedef enum roma_anim_path {
    ROMA_ANIM_TRANSLATION = 1, /**< the node's translation (3 floats) */
    ROMA_ANIM_ROTATION,        /**< the node's rotation quaternion x, y, z, w (4 floats) */
    ROMA_ANIM_SCALE,           /**< the node's scale (3 floats) */
    ROMA_ANIM_WEIGHTS          /**< morph target weights (kept, not played) */
} roma_anim_path;

/** How an animation channel interpolates its keys. */
typedef enum roma_anim_interp {
    ROMA_ANIM_LINEAR = 0,  /**< linear between keys (rotations: spherical) */
    ROMA_ANIM_STEP,        /**< the previous key's value */
    ROMA_ANIM_CUBICSPLINE  /**< cubic Hermite spline with in and out tangents per key */
} roma_anim_interp;

/** One animation channel: a node's translation, rotation or scale over key times. */
typedef struct roma_scene_anim_channel {
    uint32_t animation;      /**< index of the clip this channel belongs to */
    uint32_t node; /**< the animated node */
    roma_anim_path path; /**< translation, rotation or scale */
    roma_anim_interp interpolation; /**< step, linear or cubic spline */
    uint32_t key_count; /**< keys in times (and values) */
    uint32_t components;     /**< floats per element: 3 (translation, scale), 4 (rotation), or
                                the morph target count (weights);
                                the channel's values are key_count elements, or 3 * key_count
                                for CUBICSPLINE (in-tangent, value, out-tangent per key) */
    uint32_t first_time;     /**< offset into roma_scene_animation_data.times */
    uint32_t first_value;    /**< offset into roma_scene_animation_data.values */
} roma_scene_anim_channel;

/** The skins and animations a glTF file carries, for roma_animator and roma_scene_pose. */
typedef struct roma_scene_animation_data {
    const roma_scene_node *nodes; /**< the node hierarchy */
    uint32_t node_count; /**< entries of nodes */
    const roma_scene_skin *skins; /**< skins */
    uint32_t skin_count; /**< entries of skins */
    const uint32_t *joint_nodes;       /**< per skin joint: node index */
    const float *inverse_binds;        /**< per skin joint: column-major 4x4 */
    uint32_t joint_total; /**< entries of joint_nodes and inverse_binds */
    /** Per vertex of the flattened scene (vertex_count entries each, or NULL when no vertex is skinned): */
    const uint32_t *vertex_node;       /**< node that instanced the vertex */
    const int32_t *vertex_skin;        /**< skin index or -1 */
    const uint16_t *vertex_joints;     /**< 4 per vertex, index within the skin */
    const float *vertex_weights;       /**< 4 per vertex */
    const float *vertex_rest_local;    /**< 3 per vertex: position in mesh space before any transform */
    const roma_scene_anim_channel *channels; /**< animation channels of every clip */
    uint32_t channel_count; /**< entries of channels */
    uint32_t animation_count; /**< clips */
    const char *const *animation_names; /**< animation_count names ("" when unnamed), or NULL */
    const float *times; /**< key times of every channel, seconds */
    const float *values; /**< key values of every channel */
} roma_scene_animation_data;

/** Read-only view of a scene; pointers stay valid until roma_scene_destroy (those of
 * animation until roma_scene_set_animation_data replaces the data). */
typedef struct roma_scene_view {
    const char *name; /**< the scene's name */
    const float *positions;           /**< 3 per vertex */
    const float *normals;             /**< 3 per vertex, unit length (zero for unused vertices and
                                         for those with neither a usable given normal nor a
                                         triangle of non-zero area) */
    uint32_t vertex_count; /**< vertices */
    const uint32_t *indices;          /**< 3 per triangle */
    uint32_t triangle_count; /**< triangles */
    uint32_t degenerate_triangle_count; /**< triangles of zero area (kept, never hit) */
    const uint32_t *triangle_materials; /**< one per triangle */
    const roma_material *materials; /**< material_count materials */
    uint32_t material_count; /**< materials */
    const roma_light *lights; /**< light_count punctual lights */
    uint32_t light_count; /**< lights */
    const uint32_t *emissive_triangles; /**< triangles whose material emits and whose area > 0 */
    uint32_t emissive_triangle_count; /**< entries of emissive_triangles */
    int has_camera; /**< 1 when the scene carries a camera */
    roma_camera camera; /**< valid when has_camera */
    const roma_camera *cameras; /**< the viewpoints the scene offers (roma_scene_desc.cameras) */
    uint32_t camera_count; /**< entries of cameras (0: none listed) */
    float bounds_min[3]; /**< lowest corner over the vertices referenced by triangles */
    float bounds_max[3]; /**< highest corner over the vertices referenced by triangles */
    roma_scene_animation_data animation; /**< skins and animations (empty for static scenes) */
} roma_scene_view;

/** A read-only view of the scene's arrays (no copy).
 *
 * @param scene          the scene.
 * @param[out] out_view  the view; its pointers belong to the scene. Zeroed on failure.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for NULL arguments (*out_view zeroed).
 * @par Threads
 * Any thread, concurrently with other readers. */
ROMA_API roma_result roma_scene_get_view(const roma_scene *scene, roma_scene_view *out_view);

/** Attaches animation data, replacing the scene's (the old arrays are freed). Animation data
 * is attached by loaders after the geometry is validated; the scene copies the arrays
 * (per-vertex ones are vertex_count entries, each optional). Rejects out-of-range
 * node/skin/joint indices, parent cycles, bad channels, negative weights and non-finite
 * floats. Intended for loaders; engines rarely need it. A failure keeps the previous data.
 *
 * @param scene   the scene to change.
 * @param data    the data; copied, the caller keeps ownership.
 * @param logger  where messages go; NULL: stderr (warnings and errors).
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL scene or data, or a NULL array
 *         with a non-zero count; ROMA_ERROR_INVALID_SCENE for invalid data;
 *         ROMA_ERROR_OUT_OF_HOST_MEMORY.
 * @par Threads
 * The one call that changes a scene: no other thread may use the scene meanwhile, and views
 * taken before see freed animation arrays. */
ROMA_API roma_result roma_scene_set_animation_data(roma_scene *scene,
                                                   const roma_scene_animation_data *data,
                                                   const roma_logger *logger);

/** Camera to use when none is given: the scene's own, or one framing the bounds
 * (roma_camera_frame_bounds).
 *
 * @param scene   the scene; NULL leaves *out_camera zeroed.
 * @param aspect  image width / height, for framing the bounds.
 * @param[out] out_camera  the camera; NULL: nothing is done.
 * @par Threads
 * Any thread, concurrently with other readers. */
ROMA_API void roma_scene_default_camera(const roma_scene *scene, float aspect, roma_camera *out_camera);

#ifdef __cplusplus
}
#endif

#endif /* ROMA_SCENE_H */
