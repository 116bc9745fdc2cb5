/* libroma: glTF 2.0 loader over tinygltf 2.7 (the one C++ translation unit).
 *
 * tinygltf parses JSON and buffers; what it leaves unchecked (GLB chunk
 * lengths, accessor and buffer-view ranges, index ranges, node cycles,
 * accessor types) is checked here before a byte is read, because files are
 * untrusted. Errors travel as a Failure exception inside this file and every
 * exception stops at the C boundary. */
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <cerrno>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <new>
#include <set>
#include <string>
#include <vector>

#include "roma/gltf.h"
#include "util/log.h"

namespace {

struct Failure {
    roma_result code;
};

std::string vformat(const char *fmt, va_list args)
{
    char buf[1024];
    vsnprintf(buf, sizeof buf, fmt, args);
    return buf;
}

std::string format(const char *fmt, ...) ROMA_PRINTF(1, 2);
std::string format(const char *fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    std::string s = vformat(fmt, args);
    va_end(args);
    return s;
}

/* Column-major 4x4, double so deep hierarchies do not drift. */
struct Mat4 {
    double m[16];
};

Mat4 identity()
{
    Mat4 r = {};
    r.m[0] = r.m[5] = r.m[10] = r.m[15] = 1.0;
    return r;
}

Mat4 mul(const Mat4 &a, const Mat4 &b)
{
    Mat4 r;
    for (int c = 0; c < 4; ++c)
        for (int row = 0; row < 4; ++row) {
            double s = 0.0;
            for (int k = 0; k < 4; ++k)
                s += a.m[k * 4 + row] * b.m[c * 4 + k];
            r.m[c * 4 + row] = s;
        }
    return r;
}

void xform(const Mat4 &a, const double v[3], double w, double out[3])
{
    for (int r = 0; r < 3; ++r)
        out[r] = a.m[r] * v[0] + a.m[4 + r] * v[1] + a.m[8 + r] * v[2] + a.m[12 + r] * w;
}

void cross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

double det3(const Mat4 &a)
{
    double c[3];
    cross(a.m + 4, a.m + 8, c);
    return a.m[0] * c[0] + a.m[1] * c[1] + a.m[2] * c[2];
}

/* Normal transform: the cofactor matrix is det * inverse-transpose, so it
 * stays defined for singular matrices; the sign of det keeps normals facing
 * the same way under mirroring. Result normalised, or zero. */
void xform_normal(const Mat4 &a, const double n[3], double out[3])
{
    double c0[3], c1[3], c2[3];
    cross(a.m + 4, a.m + 8, c0);
    cross(a.m + 8, a.m + 0, c1);
    cross(a.m + 0, a.m + 4, c2);
    double s = det3(a) < 0.0 ? -1.0 : 1.0;
    for (int r = 0; r < 3; ++r)
        out[r] = s * (c0[r] * n[0] + c1[r] * n[1] + c2[r] * n[2]);
    double len = std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
    for (int r = 0; r < 3; ++r)
        out[r] = len > 0.0 && std::isfinite(len) ? out[r] / len : 0.0;
}

Mat4 from_trs(const double t[3], const double q[4], const double s[3])
{
    double x = q[0], y = q[1], z = q[2], w = q[3];
    Mat4 r = identity();
    const double rot[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),
                           2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                           2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y)};
    for (int c = 0; c < 3; ++c) {
        for (int row = 0; row < 3; ++row)
            r.m[c * 4 + row] = rot[c * 3 + row] * s[c];
        r.m[12 + c] = t[c];
    }
    return r;
}

/* TRS of a matrix node, for the animation data (spec: animated nodes use
 * TRS, so this only matters for joints given as matrices). */
void decompose(const Mat4 &a, float t[3], float q[4], float s[3])
{
    double sc[3], r[3][3];
    for (int c = 0; c < 3; ++c) {
        t[c] = (float)a.m[12 + c];
        sc[c] = std::sqrt(a.m[c * 4] * a.m[c * 4] + a.m[c * 4 + 1] * a.m[c * 4 + 1] +
                          a.m[c * 4 + 2] * a.m[c * 4 + 2]);
    }
    if (det3(a) < 0.0)
        sc[0] = -sc[0];
    q[0] = q[1] = q[2] = 0.0f;
    q[3] = 1.0f;
    for (int c = 0; c < 3; ++c)
        s[c] = (float)sc[c];
    if (sc[0] == 0.0 || sc[1] == 0.0 || sc[2] == 0.0)
        return;
    for (int c = 0; c < 3; ++c)
        for (int row = 0; row < 3; ++row)
            r[row][c] = a.m[c * 4 + row] / sc[c];
    double tr = r[0][0] + r[1][1] + r[2][2], x, y, z, w;
    if (tr > 0.0) {
        double k = std::sqrt(tr + 1.0) * 2.0;
        w = 0.25 * k, x = (r[2][1] - r[1][2]) / k, y = (r[0][2] - r[2][0]) / k, z = (r[1][0] - r[0][1]) / k;
    } else if (r[0][0] > r[1][1] && r[0][0] > r[2][2]) {
        double k = std::sqrt(1.0 + r[0][0] - r[1][1] - r[2][2]) * 2.0;
        w = (r[2][1] - r[1][2]) / k, x = 0.25 * k, y = (r[0][1] + r[1][0]) / k, z = (r[0][2] + r[2][0]) / k;
    } else if (r[1][1] > r[2][2]) {
        double k = std::sqrt(1.0 + r[1][1] - r[0][0] - r[2][2]) * 2.0;
        w = (r[0][2] - r[2][0]) / k, x = (r[0][1] + r[1][0]) / k, y = 0.25 * k, z = (r[1][2] + r[2][1]) / k;
    } else {
        double k = std::sqrt(1.0 + r[2][2] - r[0][0] - r[1][1]) * 2.0;
        w = (r[1][0] - r[0][1]) / k, x = (r[0][2] + r[2][0]) / k, y = (r[1][2] + r[2][1]) / k, z = 0.25 * k;
    }
    q[0] = (float)x, q[1] = (float)y, q[2] = (float)z, q[3] = (float)w;
}

/* A checked view of an accessor; data == nullptr means all zeros (no buffer view). */
struct Accessor {
    const unsigned char *data = nullptr;
    size_t count = 0, stride = 0, csize = 0;
    int ctype = 0, ncomp = 0;
    bool normalized = false;

    double get(size_t i, int c) const
    {
        if (!data)
            return 0.0;
        const unsigned char *p = data + i * stride + (size_t)c * csize;
        switch (ctype) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: {
            float f;
            memcpy(&f, p, 4);
            return f;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return normalized ? p[0] / 255.0 : p[0];
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            double v = (int8_t)p[0];
            return normalized ? std::fmax(v / 127.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v;
            memcpy(&v, p, 2);
            return normalized ? v / 65535.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            int16_t v;
            memcpy(&v, p, 2);
            return normalized ? std::fmax(v / 32767.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            uint32_t v;
            memcpy(&v, p, 4);
            return v;
        }
        default:
            return 0.0;
        }
    }
    uint32_t get_uint(size_t i) const { return (uint32_t)get(i, 0); }
};

const char *type_name(int type)
{
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "unknown";
    }
}

/* Allowed component types, as flags. */
enum : unsigned {
    C_FLOAT = 1, C_UBYTE = 2, C_USHORT = 4, C_UINT = 8, C_BYTE = 16, C_SHORT = 32,
    C_NORM = 64 /* integer types must be normalized */
};

unsigned component_flag(int ctype)
{
    switch (ctype) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return C_FLOAT;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return C_UBYTE;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return C_USHORT;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return C_UINT;
    case TINYGLTF_COMPONENT_TYPE_BYTE: return C_BYTE;
    case TINYGLTF_COMPONENT_TYPE_SHORT: return C_SHORT;
    default: return 0;
    }
}

struct Range {
    size_t v0, v1, t0, t1;
    bool has_normals;
};

class Loader {
public:
    Loader(const roma_logger *log, std::string file, uint32_t max_vertices, uint32_t max_triangles,
           uint32_t camera_index)
        : log_(log), file_(std::move(file)), max_vertices_(max_vertices), max_triangles_(max_triangles),
          camera_index_(camera_index)
    {
    }

    [[noreturn]] ROMA_PRINTF(3, 4) void fail(roma_result code, const char *fmt, ...)
    {
        va_list args;
        va_start(args, fmt);
        std::string msg = vformat(fmt, args);
        va_end(args);
        roma_log_error(log_, code, "%s: %s", file_.c_str(), msg.c_str());
        throw Failure{code};
    }
    ROMA_PRINTF(2, 3) void warn(const char *fmt, ...)
    {
        va_list args;
        va_start(args, fmt);
        std::string msg = vformat(fmt, args);
        va_end(args);
        roma_logf(log_, ROMA_LOG_WARNING, "%s: %s", file_.c_str(), msg.c_str());
    }

    roma_result load(const unsigned char *data, size_t size, const char *base_dir, roma_scene **out);

private:
    const roma_logger *log_;
    std::string file_;
    uint32_t max_vertices_, max_triangles_;
    uint32_t camera_index_;       /* roma_gltf_desc.camera_index */
    std::vector<roma_camera> cameras_; /* perspective cameras met in the walk, in order */
    uint64_t zero_elements_ = 0; /* read from accessors without a buffer view, every use counted */
    tinygltf::Model m_;

    std::vector<Mat4> world_;
    std::vector<int> parent_;
    std::vector<uint32_t> mat_map_;  /* glTF material -> roma material */
    uint32_t default_mat_ = UINT32_MAX;
    std::set<std::pair<int, int>> warned_prims_;
    bool warned_morph_ = false, warned_multi_weights_ = false;

    std::vector<float> pos_, nrm_;
    std::vector<uint32_t> idx_, tri_mat_;
    std::vector<roma_material> mats_;
    std::vector<roma_light> lights_;
    std::vector<Range> ranges_;

    bool keep_anim_ = false;
    std::vector<uint32_t> v_node_;
    std::vector<int32_t> v_skin_;
    std::vector<uint16_t> v_joints_;
    std::vector<float> v_weights_, v_rest_;
    std::vector<uint32_t> joint_nodes_, skin_first_;
    std::vector<float> inverse_binds_;

    void check_container(const unsigned char *data, size_t size, size_t *json_off, size_t *json_len,
                         size_t *glb_len);
    void check_json(const char *text, size_t len);
    void check_non_negative(const nlohmann::json &v);
    void parse(const unsigned char *data, size_t size, const char *base_dir);
    Accessor accessor(int index, const std::string &what, int type, unsigned allowed);
    std::string mesh_label(int mesh, size_t prim) const;
    void build_hierarchy();
    std::vector<int> scene_walk();
    void build_materials();
    void read_skins();
    void add_light(int node);
    void add_camera(int node);
    void add_primitive(int node, int mesh, size_t prim);
    void fill_missing_normals();
    void attach_animation(roma_scene *scene);
    roma_result finish(roma_scene **out);
};

std::string Loader::mesh_label(int mesh, size_t prim) const
{
    const std::string &name = m_.meshes[(size_t)mesh].name;
    return name.empty() ? format("mesh %d primitive %zu", mesh, prim)
                        : format("mesh %d '%s' primitive %zu", mesh, name.c_str(), prim);
}

/* GLB container checks tinygltf 2.7 lacks: it can read up to 8 bytes past
 * the end when the BIN chunk length is wrong. */
void Loader::check_container(const unsigned char *d, size_t size, size_t *json_off, size_t *json_len,
                             size_t *glb_len)
{
    auto u32 = [d](size_t off) {
        uint32_t v;
        memcpy(&v, d + off, 4);
        return v;
    };
    if (size < 20)
        fail(ROMA_ERROR_PARSE, "GLB file truncated: %zu bytes, the header needs 20", size);
    uint32_t version = u32(4), length = u32(8), json_chunk = u32(12);
    if (version != 2)
        fail(ROMA_ERROR_UNSUPPORTED, "GLB version %u (only glTF 2.0 is supported)", version);
    if (length > size)
        fail(ROMA_ERROR_PARSE, "GLB file truncated: header says %u bytes, file has %zu", length, size);
    if (length < size)
        warn("%zu bytes after the end of the GLB container ignored", size - length);
    if (u32(16) != 0x4E4F534Au)
        fail(ROMA_ERROR_PARSE, "GLB first chunk is not JSON");
    if (json_chunk == 0 || (uint64_t)json_chunk + 20 > length)
        fail(ROMA_ERROR_PARSE, "GLB JSON chunk length %u does not fit the %u-byte container", json_chunk,
             length);
    uint64_t end = 20 + (uint64_t)json_chunk;
    if (end < length) {
        if (end + 8 > length)
            fail(ROMA_ERROR_PARSE, "GLB truncated inside the second chunk header");
        uint32_t bin_len = u32((size_t)end), bin_type = u32((size_t)end + 4);
        if (end + 8 + bin_len > length)
            fail(ROMA_ERROR_PARSE, "GLB BIN chunk length %u runs past the end of the %u-byte container",
                 bin_len, length);
        if (bin_type != 0x004E4942u)
            fail(ROMA_ERROR_PARSE, "GLB second chunk is not BIN");
    }
    *json_off = 20;
    *json_len = json_chunk;
    *glb_len = length;
}

/* Indices, offsets, lengths and counts are never negative in glTF; tinygltf
 * quietly reads a negative one as "absent" (indices: -1 loads the primitive
 * unindexed, byteOffset: -36 as 0), so they are refused here. The depth is
 * bounded by check_json's nesting limit; "extras" belong to the author. */
void Loader::check_non_negative(const nlohmann::json &v)
{
    static const char *const keys[] = {"bufferView", "buffer",   "byteOffset", "byteLength", "byteStride",
                                       "count",      "indices",  "material",   "mesh",       "node",
                                       "camera",     "skin",     "source",     "sampler",    "scene",
                                       "input",      "output",   "light",      "texCoord",   "index",
                                       "skeleton",   "inverseBindMatrices", "mode"};
    static const char *const id_lists[] = {"nodes", "children", "joints", "attributes"};
    auto negative = [](const nlohmann::json &x) {
        return (x.is_number_integer() && !x.is_number_unsigned() && x.get<int64_t>() < 0) ||
               (x.is_number_float() && x.get<double>() < 0.0);
    };
    if (v.is_array()) {
        for (const auto &e : v)
            check_non_negative(e);
        return;
    }
    if (!v.is_object())
        return;
    for (auto it = v.begin(); it != v.end(); ++it) {
        const std::string &key = it.key();
        if (key == "extras")
            continue;
        for (const char *k : keys)
            if (key == k && negative(it.value()))
                fail(ROMA_ERROR_PARSE, "'%s' is negative (%s)", k, it.value().dump().c_str());
        for (const char *k : id_lists)
            if (key == k && (it.value().is_array() || it.value().is_object()))
                for (const auto &e : it.value())
                    if (negative(e))
                        fail(ROMA_ERROR_PARSE, "'%s' holds a negative index (%s)", k, e.dump().c_str());
        check_non_negative(it.value());
    }
}

/* Own pass over the JSON before tinygltf: clear parse errors, a nesting
 * limit (tinygltf converts "extras" recursively), and extensionsRequired
 * checked before tinygltf trips over e.g. Draco accessors without views. */
void Loader::check_json(const char *text, size_t len)
{
    int depth = 0;
    bool in_string = false;
    for (size_t i = 0; i < len; ++i) {
        char c = text[i];
        if (in_string) {
            if (c == '\\')
                ++i;
            else if (c == '"')
                in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > 256)
                fail(ROMA_ERROR_PARSE, "JSON nested deeper than 256 levels");
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text, text + len);
    } catch (const nlohmann::json::exception &e) {
        fail(ROMA_ERROR_PARSE, "not valid JSON: %s", e.what());
    }
    if (!j.is_object())
        fail(ROMA_ERROR_PARSE, "JSON root is not an object");
    auto asset = j.find("asset");
    if (asset == j.end() || !asset->is_object() || !asset->contains("version") ||
        !(*asset)["version"].is_string())
        fail(ROMA_ERROR_PARSE, "missing asset.version");
    std::string version = (*asset)["version"].get<std::string>();
    if (version.empty() || version[0] != '2')
        fail(ROMA_ERROR_UNSUPPORTED, "glTF version %s (only 2.x is supported)", version.c_str());
    check_non_negative(j);
    static const char *const supported[] = {"KHR_lights_punctual", "KHR_materials_emissive_strength",
                                            "KHR_texture_transform"};
    auto req = j.find("extensionsRequired");
    if (req != j.end() && req->is_array())
        for (const auto &e : *req) {
            std::string name = e.is_string() ? e.get<std::string>() : std::string("(not a string)");
            bool ok = false;
            for (const char *s : supported)
                ok = ok || name == s;
            if (!ok)
                fail(ROMA_ERROR_UNSUPPORTED, "required extension %s is not supported", name.c_str());
        }
}

bool ignore_image(tinygltf::Image *, const int, std::string *, std::string *, int, int,
                  const unsigned char *, int, void *)
{
    return true; /* textures are not used */
}

bool no_file(const std::string &, void *)
{
    return false;
}

void Loader::parse(const unsigned char *data, size_t size, const char *base_dir)
{
    if (size == 0)
        fail(ROMA_ERROR_PARSE, "empty file");
    if (size > UINT32_MAX)
        fail(ROMA_ERROR_UNSUPPORTED, "files of 4 GiB or more are not supported");
    bool glb = size >= 4 && memcmp(data, "glTF", 4) == 0;
    size_t json_off = 0, json_len = size, glb_len = size;
    if (glb)
        check_container(data, size, &json_off, &json_len, &glb_len);
    check_json((const char *)data + json_off, json_len);

    tinygltf::TinyGLTF gltf;
    gltf.SetImageLoader(ignore_image, nullptr);
    if (!base_dir) {
        tinygltf::FsCallbacks fs = {no_file, tinygltf::ExpandFilePath, tinygltf::ReadWholeFile,
                                    tinygltf::WriteWholeFile, nullptr};
        gltf.SetFsCallbacks(fs);
    }
    std::string err, warn_text, dir = base_dir ? base_dir : "";
    bool ok = glb ? gltf.LoadBinaryFromMemory(&m_, &err, &warn_text, data, (unsigned)glb_len, dir)
                  : gltf.LoadASCIIFromString(&m_, &err, &warn_text, (const char *)data, (unsigned)size, dir);
    size_t start = 0;
    while (start < warn_text.size()) {
        size_t nl = warn_text.find('\n', start);
        std::string line = warn_text.substr(start, nl == std::string::npos ? std::string::npos : nl - start);
        if (!line.empty())
            warn("tinygltf: %s", line.c_str());
        start = nl == std::string::npos ? warn_text.size() : nl + 1;
    }
    while (!err.empty() && err.back() == '\n')
        err.pop_back();
    if (!ok) {
        bool missing = err.find("File not found") != std::string::npos;
        fail(missing ? ROMA_ERROR_FILE_NOT_FOUND : ROMA_ERROR_PARSE, "%s%s", err.c_str(),
             missing && !base_dir ? " (no base directory given for external files)" : "");
    }
    if (!err.empty())
        warn("tinygltf: %s", err.c_str());
}

Accessor Loader::accessor(int index, const std::string &what, int type, unsigned allowed)
{
    const char *w = what.c_str();
    if (index < 0 || (size_t)index >= m_.accessors.size())
        fail(ROMA_ERROR_INVALID_SCENE, "accessor %d (%s) does not exist", index, w);
    const tinygltf::Accessor &a = m_.accessors[(size_t)index];
    if (a.sparse.isSparse)
        fail(ROMA_ERROR_UNSUPPORTED, "accessor %d (%s) is sparse; sparse accessors are not supported", index, w);
    if (a.type != type)
        fail(ROMA_ERROR_INVALID_SCENE, "accessor %d (%s) has type %s, expected %s", index, w,
             type_name(a.type), type_name(type));
    unsigned flag = component_flag(a.componentType);
    bool int_ok = !(allowed & C_NORM) || a.normalized || flag == C_FLOAT;
    if (!(flag & allowed) || !int_ok)
        fail(ROMA_ERROR_INVALID_SCENE, "accessor %d (%s) has component type %d%s, not allowed here", index, w,
             a.componentType, a.normalized ? " (normalized)" : "");
    Accessor r;
    r.count = a.count;
    r.ctype = a.componentType;
    r.csize = (size_t)tinygltf::GetComponentSizeInBytes((uint32_t)a.componentType);
    r.ncomp = tinygltf::GetNumComponentsInType((uint32_t)a.type);
    r.normalized = a.normalized;
    uint64_t elem = (uint64_t)r.csize * (uint64_t)r.ncomp;
    if (a.bufferView < 0) {
        /* Spec: no buffer view means zeros. Nothing bounds the count by real
         * data then, and many uses of one such accessor add up, so the file
         * gets 2^24 of these elements in all instead of allocating for more. */
        zero_elements_ += a.count;
        if (zero_elements_ > (1u << 24))
            fail(ROMA_ERROR_INVALID_SCENE,
                 "accessor %d (%s): %zu elements without a buffer view, more than 2^24 such elements in all",
                 index, w, a.count);
        return r;
    }
    if ((size_t)a.bufferView >= m_.bufferViews.size())
        fail(ROMA_ERROR_INVALID_SCENE, "accessor %d (%s): buffer view %d does not exist", index, w, a.bufferView);
    const tinygltf::BufferView &bv = m_.bufferViews[(size_t)a.bufferView];
    if (bv.buffer < 0 || (size_t)bv.buffer >= m_.buffers.size())
        fail(ROMA_ERROR_INVALID_SCENE, "buffer view %d: buffer %d does not exist", a.bufferView, bv.buffer);
    const std::vector<unsigned char> &buf = m_.buffers[(size_t)bv.buffer].data;
    if (bv.byteOffset > buf.size() || bv.byteLength > buf.size() - bv.byteOffset)
        fail(ROMA_ERROR_INVALID_SCENE, "buffer view %d: range [%zu, %zu + %zu) past the end of buffer %d (%zu bytes)",
             a.bufferView, bv.byteOffset, bv.byteOffset, bv.byteLength, bv.buffer, buf.size());
    if (bv.byteStride && bv.byteStride < elem)
        fail(ROMA_ERROR_INVALID_SCENE, "accessor %d (%s): buffer view %d stride %zu is smaller than an element (%u bytes)",
             index, w, a.bufferView, bv.byteStride, (unsigned)elem);
    r.stride = bv.byteStride ? bv.byteStride : (size_t)elem;
    if (a.count) {
        /* byteOffset + stride * (count - 1) + elem <= byteLength, without overflow */
        uint64_t room = bv.byteLength;
        bool fits = a.byteOffset <= room && elem <= room - a.byteOffset &&
                    (uint64_t)(a.count - 1) <= (room - a.byteOffset - elem) / r.stride;
        if (!fits)
            fail(ROMA_ERROR_INVALID_SCENE,
                 "accessor %d (%s): %zu elements of %u bytes (stride %zu) from offset %zu run past the end "
                 "of buffer view %d (%zu bytes)",
                 index, w, a.count, (unsigned)elem, r.stride, a.byteOffset, a.bufferView, bv.byteLength);
    }
    r.data = buf.data() + bv.byteOffset + a.byteOffset;
    return r;
}

void Loader::build_hierarchy()
{
    size_t n = m_.nodes.size();
    parent_.assign(n, -1);
    for (size_t i = 0; i < n; ++i)
        for (int c : m_.nodes[i].children) {
            if (c < 0 || (size_t)c >= n)
                fail(ROMA_ERROR_INVALID_SCENE, "node %zu lists child %d, which does not exist", i, c);
            if ((size_t)c == i)
                fail(ROMA_ERROR_INVALID_SCENE, "node %zu lists itself as a child (cycle)", i);
            if (parent_[(size_t)c] >= 0)
                fail(ROMA_ERROR_INVALID_SCENE, "node %d has two parents (nodes %d and %zu); the node "
                     "hierarchy must be a tree", c, parent_[(size_t)c], i);
            parent_[(size_t)c] = (int)i;
        }

    std::vector<Mat4> local(n);
    for (size_t i = 0; i < n; ++i) {
        const tinygltf::Node &nd = m_.nodes[i];
        bool finite = true;
        for (const auto *v : {&nd.matrix, &nd.translation, &nd.rotation, &nd.scale})
            for (double x : *v)
                finite = finite && std::isfinite(x);
        if (!finite)
            fail(ROMA_ERROR_INVALID_SCENE, "node %zu has a NaN or infinite transform", i);
        if (nd.matrix.size() == 16) {
            std::copy(nd.matrix.begin(), nd.matrix.end(), local[i].m);
            continue;
        }
        if (!nd.matrix.empty() || (!nd.translation.empty() && nd.translation.size() != 3) ||
            (!nd.rotation.empty() && nd.rotation.size() != 4) || (!nd.scale.empty() && nd.scale.size() != 3))
            fail(ROMA_ERROR_INVALID_SCENE, "node %zu: matrix/translation/rotation/scale of the wrong length", i);
        double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
        std::copy(nd.translation.begin(), nd.translation.end(), t);
        std::copy(nd.rotation.begin(), nd.rotation.end(), q);
        std::copy(nd.scale.begin(), nd.scale.end(), s);
        double ql = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        if (ql > 0.0)
            for (double &x : q)
                x /= ql;
        local[i] = from_trs(t, q, s);
    }

    /* Iterative walk from the roots: no recursion, and since every node has
     * at most one parent, nodes left unvisited sit on a cycle. */
    world_.assign(n, identity());
    std::vector<char> seen(n, 0);
    std::vector<size_t> stack;
    for (size_t i = 0; i < n; ++i)
        if (parent_[i] < 0)
            stack.push_back(i);
    while (!stack.empty()) {
        size_t v = stack.back();
        stack.pop_back();
        seen[v] = 1;
        world_[v] = parent_[v] < 0 ? local[v] : mul(world_[(size_t)parent_[v]], local[v]);
        for (int c : m_.nodes[v].children)
            stack.push_back((size_t)c);
    }
    for (size_t i = 0; i < n; ++i)
        if (!seen[i])
            fail(ROMA_ERROR_INVALID_SCENE, "node %zu is part of a cycle in the node hierarchy", i);
}

/* Nodes of the default scene (or of all roots when there is no scene), in
 * depth-first document order, each once. */
std::vector<int> Loader::scene_walk()
{
    std::vector<int> roots;
    if (!m_.scenes.empty()) {
        int s = m_.defaultScene >= 0 ? m_.defaultScene : 0;
        if ((size_t)s >= m_.scenes.size())
            fail(ROMA_ERROR_INVALID_SCENE, "default scene %d does not exist", s);
        roots = m_.scenes[(size_t)s].nodes;
    } else {
        for (size_t i = 0; i < m_.nodes.size(); ++i)
            if (parent_[i] < 0)
                roots.push_back((int)i);
    }
    std::vector<int> order, stack;
    std::vector<char> seen(m_.nodes.size(), 0);
    for (auto r = roots.rbegin(); r != roots.rend(); ++r) {
        if (*r < 0 || (size_t)*r >= m_.nodes.size())
            fail(ROMA_ERROR_INVALID_SCENE, "scene lists node %d, which does not exist", *r);
        stack.push_back(*r);
    }
    while (!stack.empty()) {
        int v = stack.back();
        stack.pop_back();
        if (seen[(size_t)v])
            continue;
        seen[(size_t)v] = 1;
        order.push_back(v);
        const auto &ch = m_.nodes[(size_t)v].children;
        for (auto c = ch.rbegin(); c != ch.rend(); ++c)
            stack.push_back(*c);
    }
    return order;
}

void Loader::build_materials()
{
    bool textured = false;
    for (const tinygltf::Material &mt : m_.materials) {
        roma_material r = {};
        const auto &bc = mt.pbrMetallicRoughness.baseColorFactor;
        double strength = 1.0;
        auto ext = mt.extensions.find("KHR_materials_emissive_strength");
        if (ext != mt.extensions.end() && ext->second.IsObject() && ext->second.Has("emissiveStrength") &&
            ext->second.Get("emissiveStrength").IsNumber())
            strength = ext->second.Get("emissiveStrength").GetNumberAsDouble();
        for (int c = 0; c < 3; ++c) {
            r.base_color[c] = bc.size() == 4 ? (float)bc[(size_t)c] : 1.0f;
            r.emission[c] = mt.emissiveFactor.size() == 3 ? (float)(mt.emissiveFactor[(size_t)c] * strength) : 0.0f;
        }
        textured = textured || mt.pbrMetallicRoughness.baseColorTexture.index >= 0 ||
                   mt.emissiveTexture.index >= 0;
        mat_map_.push_back((uint32_t)mats_.size());
        mats_.push_back(r);
    }
    if (textured)
        roma_logf(log_, ROMA_LOG_INFO, "%s: textures are ignored; materials use their constant factors",
                  file_.c_str());
}

void Loader::read_skins()
{
    for (size_t s = 0; s < m_.skins.size(); ++s) {
        const tinygltf::Skin &sk = m_.skins[s];
        skin_first_.push_back((uint32_t)joint_nodes_.size());
        Accessor ibm;
        if (sk.inverseBindMatrices >= 0) {
            ibm = accessor(sk.inverseBindMatrices, format("inverse bind matrices of skin %zu", s),
                           TINYGLTF_TYPE_MAT4, C_FLOAT);
            if (ibm.count < sk.joints.size())
                fail(ROMA_ERROR_INVALID_SCENE, "skin %zu has %zu joints but %zu inverse bind matrices", s,
                     sk.joints.size(), ibm.count);
        }
        for (size_t j = 0; j < sk.joints.size(); ++j) {
            int node = sk.joints[j];
            if (node < 0 || (size_t)node >= m_.nodes.size())
                fail(ROMA_ERROR_INVALID_SCENE, "skin %zu joint %zu refers to node %d, which does not exist", s,
                     j, node);
            joint_nodes_.push_back((uint32_t)node);
            for (int k = 0; k < 16; ++k) {
                double v = sk.inverseBindMatrices >= 0 ? ibm.get(j, k) : (k % 5 == 0 ? 1.0 : 0.0);
                if (!std::isfinite(v))
                    fail(ROMA_ERROR_INVALID_SCENE, "skin %zu: inverse bind matrix %zu is not finite", s, j);
                inverse_binds_.push_back((float)v);
            }
        }
    }
}

void Loader::add_camera(int node)
{
    int ci = m_.nodes[(size_t)node].camera;
    if (ci < 0)
        return;
    if ((size_t)ci >= m_.cameras.size())
        fail(ROMA_ERROR_INVALID_SCENE, "node %d refers to camera %d, which does not exist", node, ci);
    const tinygltf::Camera &c = m_.cameras[(size_t)ci];
    if (c.type != "perspective") {
        roma_logf(log_, ROMA_LOG_INFO, "%s: %s camera %d skipped (only perspective cameras are used)",
                  file_.c_str(), c.type.c_str(), ci);
        return;
    }
    const Mat4 &w = world_[(size_t)node];
    const double o[3] = {0, 0, 0}, fwd[3] = {0, 0, -1}, up[3] = {0, 1, 0};
    double eye[3], f[3], u[3];
    xform(w, o, 1.0, eye);
    xform(w, fwd, 0.0, f);
    xform(w, up, 0.0, u);
    double fl = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    double ul = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    if (!(fl > 0.0) || !(ul > 0.0) || !std::isfinite(fl) || !std::isfinite(ul)) {
        warn("camera node %d has a degenerate transform; camera skipped", node);
        return;
    }
    roma_camera cam = {};
    for (int k = 0; k < 3; ++k) {
        cam.eye[k] = (float)eye[k];
        cam.target[k] = (float)(eye[k] + f[k] / fl);
        cam.up[k] = (float)(u[k] / ul);
    }
    double yfov = c.perspective.yfov;
    cam.fovy_deg = yfov > 0.0 && yfov < 3.14159 ? (float)(yfov * 180.0 / 3.14159265358979323846) : 0.0f;
    cameras_.push_back(cam); /* every one listed; camera_index picks the scene's camera */
}

void Loader::add_light(int node)
{
    const auto &ext = m_.nodes[(size_t)node].extensions;
    auto it = ext.find("KHR_lights_punctual");
    if (it == ext.end() || !it->second.IsObject() || !it->second.Has("light"))
        return;
    const tinygltf::Value &v = it->second.Get("light");
    int li = v.IsNumber() ? v.GetNumberAsInt() : -1;
    if (li < 0 || (size_t)li >= m_.lights.size())
        fail(ROMA_ERROR_INVALID_SCENE, "node %d refers to light %d, which does not exist", node, li);
    const tinygltf::Light &l = m_.lights[(size_t)li];
    roma_light r = {};
    if (l.type == "point")
        r.type = ROMA_LIGHT_POINT;
    else if (l.type == "spot")
        r.type = ROMA_LIGHT_SPOT;
    else if (l.type == "directional")
        r.type = ROMA_LIGHT_DIRECTIONAL;
    else {
        warn("light %d has unknown type '%s'; skipped", li, l.type.c_str());
        return;
    }
    const Mat4 &w = world_[(size_t)node];
    const double o[3] = {0, 0, 0}, fwd[3] = {0, 0, -1};
    double p[3], d[3];
    xform(w, o, 1.0, p);
    xform(w, fwd, 0.0, d);
    double dl = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int k = 0; k < 3; ++k) {
        r.position[k] = (float)p[k];
        r.direction[k] = dl > 0.0 ? (float)(d[k] / dl) : 0.0f;
        r.color[k] = l.color.size() == 3 ? (float)l.color[(size_t)k] : 1.0f;
    }
    r.intensity = (float)l.intensity;
    r.range = (float)l.range;
    if (r.type == ROMA_LIGHT_SPOT) {
        r.inner_cone_angle = (float)l.spot.innerConeAngle;
        r.outer_cone_angle = (float)l.spot.outerConeAngle;
    }
    lights_.push_back(r);
}

void Loader::add_primitive(int node, int mesh, size_t pi)
{
    const tinygltf::Primitive &prim = m_.meshes[(size_t)mesh].primitives[pi];
    std::string label = mesh_label(mesh, pi);
    bool first_time = warned_prims_.insert({mesh, (int)pi}).second;
    int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode > TINYGLTF_MODE_TRIANGLE_FAN)
        fail(ROMA_ERROR_INVALID_SCENE, "%s has invalid mode %d", label.c_str(), mode);
    if (mode < TINYGLTF_MODE_TRIANGLES) {
        static const char *const names[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP"};
        if (first_time)
            warn("%s skipped: mode %s is not triangles", label.c_str(), names[mode]);
        return;
    }
    if (!prim.targets.empty() && !warned_morph_) {
        warned_morph_ = true;
        warn("morph targets ignored (%s): the base mesh is used", label.c_str());
    }
    auto pos_it = prim.attributes.find("POSITION");
    if (pos_it == prim.attributes.end()) {
        if (first_time)
            warn("%s skipped: no POSITION attribute", label.c_str());
        return;
    }
    Accessor P = accessor(pos_it->second, "POSITION of " + label, TINYGLTF_TYPE_VEC3, C_FLOAT);
    auto attr = [&](const char *name, int type, unsigned allowed, Accessor *out) {
        auto it = prim.attributes.find(name);
        if (it == prim.attributes.end())
            return false;
        *out = accessor(it->second, std::string(name) + " of " + label, type, allowed);
        if (out->count != P.count)
            fail(ROMA_ERROR_INVALID_SCENE, "%s: %s has %zu elements but POSITION has %zu", label.c_str(), name,
                 out->count, P.count);
        return true;
    };
    size_t vertex_total = pos_.size() / 3;
    if (P.count > max_vertices_ - vertex_total)
        fail(ROMA_ERROR_UNSUPPORTED,
             "%s adds %zu vertices to %zu: more than %u in the flattened scene (roma_gltf_desc.max_vertices)",
             label.c_str(), P.count, vertex_total, max_vertices_);
    Accessor N, J, W;
    bool has_n = attr("NORMAL", TINYGLTF_TYPE_VEC3, C_FLOAT, &N);

    const tinygltf::Node &nd = m_.nodes[(size_t)node];
    bool skinned = false;
    if (nd.skin >= 0) {
        if ((size_t)nd.skin >= m_.skins.size())
            fail(ROMA_ERROR_INVALID_SCENE, "node %d refers to skin %d, which does not exist", node, nd.skin);
        bool has_j = attr("JOINTS_0", TINYGLTF_TYPE_VEC4, C_UBYTE | C_USHORT, &J);
        bool has_w = attr("WEIGHTS_0", TINYGLTF_TYPE_VEC4, C_FLOAT | C_UBYTE | C_USHORT | C_NORM, &W);
        skinned = has_j && has_w;
        if (!skinned && first_time)
            warn("%s: node %d has a skin but no JOINTS_0/WEIGHTS_0; drawn unskinned", label.c_str(), node);
        if (skinned && prim.attributes.count("JOINTS_1") && !warned_multi_weights_) {
            warned_multi_weights_ = true;
            warn("%s: JOINTS_1/WEIGHTS_1 ignored (4 influences per vertex are used)", label.c_str());
        }
    }

    /* Index list, then triangles (strips and fans converted); the triangle
     * limit is checked before either is allocated. */
    auto check_triangles = [&](size_t indices) {
        size_t adds = mode == TINYGLTF_MODE_TRIANGLES ? indices / 3 : indices > 2 ? indices - 2 : 0;
        size_t total = idx_.size() / 3;
        if (adds > max_triangles_ - total)
            fail(ROMA_ERROR_UNSUPPORTED,
                 "%s adds %zu triangles to %zu: more than %u in the flattened scene "
                 "(roma_gltf_desc.max_triangles)",
                 label.c_str(), adds, total, max_triangles_);
    };
    std::vector<uint32_t> list;
    if (prim.indices >= 0) {
        Accessor I = accessor(prim.indices, "indices of " + label, TINYGLTF_TYPE_SCALAR, C_UBYTE | C_USHORT | C_UINT);
        check_triangles(I.count);
        list.resize(I.count);
        for (size_t i = 0; i < I.count; ++i) {
            list[i] = I.get_uint(i);
            if (list[i] >= P.count)
                fail(ROMA_ERROR_INVALID_SCENE, "%s: index %u at position %zu is out of range (%zu vertices)",
                     label.c_str(), list[i], i, P.count);
        }
    } else {
        check_triangles(P.count);
        list.resize(P.count);
        for (size_t i = 0; i < P.count; ++i)
            list[i] = (uint32_t)i;
    }
    std::vector<uint32_t> tris;
    size_t n = list.size();
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (n % 3 && first_time)
            warn("%s: %zu trailing indices ignored (not a multiple of 3)", label.c_str(), n % 3);
        tris.assign(list.begin(), list.begin() + (std::ptrdiff_t)(n - n % 3));
    } else {
        for (size_t i = 0; i + 2 < n; ++i) {
            if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) /* keep the winding of every other triangle */
                tris.insert(tris.end(), {list[i], list[i + 1 + i % 2], list[i + 2 - i % 2]});
            else
                tris.insert(tris.end(), {list[i + 1], list[i + 2], list[0]});
        }
    }
    if (tris.empty())
        return;

    size_t base = pos_.size() / 3; /* the limits above keep every index within 32 bits */
    const Mat4 &w = world_[(size_t)node];
    uint32_t skin_first = skinned ? skin_first_[(size_t)nd.skin] : 0;
    uint32_t skin_joints = skinned ? (uint32_t)m_.skins[(size_t)nd.skin].joints.size() : 0;
    size_t bad_normals = 0;
    for (size_t v = 0; v < P.count; ++v) {
        double p[3] = {P.get(v, 0), P.get(v, 1), P.get(v, 2)}, nrm[3] = {0, 0, 0}, wp[3], wn[3] = {0, 0, 0};
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
            fail(ROMA_ERROR_INVALID_SCENE, "accessor %d (POSITION of %s): vertex %zu is NaN or infinite",
                 pos_it->second, label.c_str(), v);
        if (has_n) {
            nrm[0] = N.get(v, 0), nrm[1] = N.get(v, 1), nrm[2] = N.get(v, 2);
            if (!std::isfinite(nrm[0]) || !std::isfinite(nrm[1]) || !std::isfinite(nrm[2])) {
                nrm[0] = nrm[1] = nrm[2] = 0.0; /* roma_scene_create replaces zero normals by face normals */
                ++bad_normals;
            }
        }
        Mat4 xf = w;
        uint16_t joints[4] = {0, 0, 0, 0};
        float weights[4] = {0, 0, 0, 0};
        if (skinned) {
            /* Rest pose: blend joint world * inverse bind; the mesh node's own transform is not used. */
            double sum = 0.0, wt[4];
            for (int k = 0; k < 4; ++k) {
                double j = J.get(v, k);
                wt[k] = W.get(v, k);
                if (j >= skin_joints)
                    fail(ROMA_ERROR_INVALID_SCENE, "%s: vertex %zu uses joint %g of a %u-joint skin", label.c_str(),
                         v, j, skin_joints);
                if (!(wt[k] >= 0.0) || !std::isfinite(wt[k]))
                    fail(ROMA_ERROR_INVALID_SCENE, "%s: vertex %zu has an invalid skin weight", label.c_str(), v);
                joints[k] = (uint16_t)j;
                sum += wt[k];
            }
            if (sum > 0.0) {
                Mat4 blend = {};
                for (int k = 0; k < 4; ++k) {
                    weights[k] = (float)(wt[k] / sum);
                    if (wt[k] == 0.0)
                        continue;
                    Mat4 ibm;
                    const float *src = &inverse_binds_[(size_t)(skin_first + joints[k]) * 16];
                    std::copy(src, src + 16, ibm.m);
                    Mat4 jm = mul(world_[joint_nodes_[skin_first + joints[k]]], ibm);
                    for (int e = 0; e < 16; ++e)
                        blend.m[e] += jm.m[e] * (wt[k] / sum);
                }
                xf = blend;
            }
        }
        xform(xf, p, 1.0, wp);
        if (has_n)
            xform_normal(xf, nrm, wn);
        for (int k = 0; k < 3; ++k) {
            pos_.push_back((float)wp[k]);
            nrm_.push_back((float)wn[k]);
        }
        if (keep_anim_) {
            v_node_.push_back((uint32_t)node);
            v_skin_.push_back(skinned ? nd.skin : -1);
            v_joints_.insert(v_joints_.end(), joints, joints + 4);
            v_weights_.insert(v_weights_.end(), weights, weights + 4);
            for (int k = 0; k < 3; ++k)
                v_rest_.push_back((float)p[k]);
        }
    }

    /* Exporters write NaN normals on vertices of zero-area faces (tabletop.gltf does). */
    if (bad_normals && first_time)
        warn("%s: %zu NaN or infinite normals; face normals used there", label.c_str(), bad_normals);

    uint32_t mat;
    if (prim.material >= 0) {
        if ((size_t)prim.material >= mat_map_.size())
            fail(ROMA_ERROR_INVALID_SCENE, "%s refers to material %d, which does not exist", label.c_str(),
                 prim.material);
        mat = mat_map_[(size_t)prim.material];
    } else {
        if (default_mat_ == UINT32_MAX) {
            default_mat_ = (uint32_t)mats_.size();
            mats_.push_back(roma_material{{0.8f, 0.8f, 0.8f}, {0.0f, 0.0f, 0.0f}});
        }
        mat = default_mat_;
    }
    /* A mirroring transform turns the faces inside out; swap to keep them outward. */
    bool flip = !skinned && det3(w) < 0.0;
    size_t t0 = idx_.size() / 3;
    for (size_t t = 0; t < tris.size(); t += 3) {
        idx_.push_back((uint32_t)base + tris[t]);
        idx_.push_back((uint32_t)base + tris[t + (flip ? 2 : 1)]);
        idx_.push_back((uint32_t)base + tris[t + (flip ? 1 : 2)]);
        tri_mat_.push_back(mat);
    }
    ranges_.push_back(Range{base, base + P.count, t0, idx_.size() / 3, has_n});
}

/* roma_scene_create computes normals only for a scene without any, so
 * primitives without normals next to ones with them get area-weighted
 * normals here, per primitive instance. */
void Loader::fill_missing_normals()
{
    for (const Range &r : ranges_) {
        if (r.has_normals)
            continue;
        for (size_t t = r.t0; t < r.t1; ++t) {
            const uint32_t *tri = &idx_[3 * t];
            double e[2][3], c[3];
            for (int k = 0; k < 3; ++k) {
                e[0][k] = (double)pos_[3 * (size_t)tri[1] + k] - pos_[3 * (size_t)tri[0] + k];
                e[1][k] = (double)pos_[3 * (size_t)tri[2] + k] - pos_[3 * (size_t)tri[0] + k];
            }
            cross(e[0], e[1], c);
            for (int v = 0; v < 3; ++v)
                for (int k = 0; k < 3; ++k)
                    nrm_[3 * (size_t)tri[v] + k] += (float)c[k];
        }
        for (size_t v = r.v0; v < r.v1; ++v) {
            float *n = &nrm_[3 * v];
            double len = std::sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
            for (int k = 0; k < 3; ++k)
                n[k] = len > 0.0 ? (float)(n[k] / len) : 0.0f;
        }
    }
}

void Loader::attach_animation(roma_scene *scene)
{
    std::vector<roma_scene_node> nodes(m_.nodes.size());
    for (size_t i = 0; i < nodes.size(); ++i) {
        const tinygltf::Node &nd = m_.nodes[i];
        roma_scene_node &sn = nodes[i];
        sn.parent = parent_[i];
        sn.skin = nd.skin >= 0 && (size_t)nd.skin < m_.skins.size() ? nd.skin : -1;
        if (nd.matrix.size() == 16) {
            Mat4 local;
            std::copy(nd.matrix.begin(), nd.matrix.end(), local.m);
            decompose(local, sn.translation, sn.rotation, sn.scale);
        } else {
            const float t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
            std::copy(t, t + 3, sn.translation);
            std::copy(q, q + 4, sn.rotation);
            std::copy(s, s + 3, sn.scale);
            for (size_t k = 0; k < nd.translation.size(); ++k)
                sn.translation[k] = (float)nd.translation[k];
            for (size_t k = 0; k < nd.rotation.size(); ++k)
                sn.rotation[k] = (float)nd.rotation[k];
            for (size_t k = 0; k < nd.scale.size(); ++k)
                sn.scale[k] = (float)nd.scale[k];
        }
        for (int k = 0; k < 16; ++k)
            sn.world[k] = (float)world_[i].m[k];
    }
    std::vector<roma_scene_skin> skins;
    for (size_t s = 0; s < m_.skins.size(); ++s)
        skins.push_back(roma_scene_skin{skin_first_[s], (uint32_t)m_.skins[s].joints.size()});

    std::vector<roma_scene_anim_channel> channels;
    std::vector<float> times, values;
    std::map<int, uint32_t> time_at, value_at; /* channels often share sampler accessors */
    bool warned_weights = false;
    for (size_t a = 0; a < m_.animations.size(); ++a) {
        const tinygltf::Animation &an = m_.animations[a];
        for (size_t c = 0; c < an.channels.size(); ++c) {
            const tinygltf::AnimationChannel &ch = an.channels[c];
            std::string what = format("animation %zu channel %zu", a, c);
            roma_scene_anim_channel rc = {};
            rc.animation = (uint32_t)a;
            if (ch.target_path == "weights") {
                if (!warned_weights)
                    warn("%s: morph target weight animation ignored", what.c_str());
                warned_weights = true;
                continue;
            }
            if (ch.target_node < 0) /* targets something an extension owns */
                continue;
            if ((size_t)ch.target_node >= m_.nodes.size())
                fail(ROMA_ERROR_INVALID_SCENE, "%s targets node %d, which does not exist", what.c_str(),
                     ch.target_node);
            rc.node = (uint32_t)ch.target_node;
            if (ch.target_path == "translation")
                rc.path = ROMA_ANIM_TRANSLATION, rc.components = 3;
            else if (ch.target_path == "rotation")
                rc.path = ROMA_ANIM_ROTATION, rc.components = 4;
            else if (ch.target_path == "scale")
                rc.path = ROMA_ANIM_SCALE, rc.components = 3;
            else
                fail(ROMA_ERROR_INVALID_SCENE, "%s has unknown path '%s'", what.c_str(), ch.target_path.c_str());
            if (ch.sampler < 0 || (size_t)ch.sampler >= an.samplers.size())
                fail(ROMA_ERROR_INVALID_SCENE, "%s uses sampler %d, which does not exist", what.c_str(),
                     ch.sampler);
            const tinygltf::AnimationSampler &sm = an.samplers[(size_t)ch.sampler];
            if (sm.interpolation == "LINEAR")
                rc.interpolation = ROMA_ANIM_LINEAR;
            else if (sm.interpolation == "STEP")
                rc.interpolation = ROMA_ANIM_STEP;
            else if (sm.interpolation == "CUBICSPLINE")
                rc.interpolation = ROMA_ANIM_CUBICSPLINE;
            else
                fail(ROMA_ERROR_INVALID_SCENE, "%s has unknown interpolation '%s'", what.c_str(),
                     sm.interpolation.c_str());
            Accessor in = accessor(sm.input, "input of " + what, TINYGLTF_TYPE_SCALAR, C_FLOAT);
            unsigned out_types = rc.path == ROMA_ANIM_ROTATION
                                     ? C_FLOAT | C_BYTE | C_UBYTE | C_SHORT | C_USHORT | C_NORM
                                     : C_FLOAT;
            Accessor outp = accessor(sm.output, "output of " + what,
                                     rc.components == 4 ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3, out_types);
            size_t per_key = rc.interpolation == ROMA_ANIM_CUBICSPLINE ? 3 : 1;
            if (in.count == 0 || in.count > UINT32_MAX / 16 || outp.count != in.count * per_key)
                fail(ROMA_ERROR_INVALID_SCENE, "%s: %zu keys but %zu output values", what.c_str(), in.count,
                     outp.count);
            rc.key_count = (uint32_t)in.count;
            auto t = time_at.find(sm.input);
            if (t == time_at.end()) {
                t = time_at.emplace(sm.input, (uint32_t)times.size()).first;
                for (size_t k = 0; k < in.count; ++k)
                    times.push_back((float)in.get(k, 0));
            }
            rc.first_time = t->second;
            auto v = value_at.find(sm.output);
            if (v == value_at.end()) {
                v = value_at.emplace(sm.output, (uint32_t)values.size()).first;
                for (size_t k = 0; k < outp.count; ++k)
                    for (int e = 0; e < (int)rc.components; ++e)
                        values.push_back((float)outp.get(k, e));
            }
            rc.first_value = v->second;
            channels.push_back(rc);
        }
    }

    roma_scene_animation_data ad = {};
    ad.nodes = nodes.data();
    ad.node_count = (uint32_t)nodes.size();
    ad.skins = skins.data();
    ad.skin_count = (uint32_t)skins.size();
    ad.joint_nodes = joint_nodes_.data();
    ad.inverse_binds = inverse_binds_.data();
    ad.joint_total = (uint32_t)joint_nodes_.size();
    ad.vertex_node = v_node_.data();
    ad.vertex_skin = v_skin_.data();
    ad.vertex_joints = v_joints_.data();
    ad.vertex_weights = v_weights_.data();
    ad.vertex_rest_local = v_rest_.data();
    ad.channels = channels.data();
    ad.channel_count = (uint32_t)channels.size();
    ad.animation_count = (uint32_t)m_.animations.size();
    std::vector<const char *> names;
    for (const tinygltf::Animation &an : m_.animations)
        names.push_back(an.name.c_str());
    ad.animation_names = names.empty() ? nullptr : names.data();
    ad.times = times.data();
    ad.values = values.data();
    roma_result r = roma_scene_set_animation_data(scene, &ad, log_);
    if (r != ROMA_SUCCESS)
        throw Failure{r}; /* already logged */
}

roma_result Loader::finish(roma_scene **out)
{
    bool any_normals = false;
    for (const Range &r : ranges_)
        any_normals = any_normals || r.has_normals;
    if (any_normals)
        fill_missing_normals();

    std::string name = file_;
    size_t slash = name.find_last_of('/');
    if (slash != std::string::npos)
        name = name.substr(slash + 1);
    roma_scene_desc desc = {};
    desc.positions = pos_.data();
    desc.normals = any_normals ? nrm_.data() : nullptr;
    desc.vertex_count = (uint32_t)(pos_.size() / 3);
    desc.indices = idx_.data();
    desc.triangle_count = (uint32_t)(idx_.size() / 3);
    desc.triangle_materials = tri_mat_.data();
    desc.materials = mats_.data();
    desc.material_count = (uint32_t)mats_.size();
    desc.lights = lights_.data();
    desc.light_count = (uint32_t)lights_.size();
    desc.camera = camera_index_ < cameras_.size() ? &cameras_[camera_index_] : nullptr;
    desc.cameras = cameras_.data();
    desc.camera_count = (uint32_t)cameras_.size();
    desc.name = name.c_str();
    if (log_)
        desc.logger = *log_;
    roma_scene *scene = nullptr;
    roma_result r = roma_scene_create(&desc, &scene); /* logs its own error, naming the file */
    if (r != ROMA_SUCCESS)
        return r;
    if (keep_anim_) {
        /* Attached after the geometry is validated; any failure still leaves no scene. */
        try {
            attach_animation(scene);
        } catch (...) {
            roma_scene_destroy(scene);
            throw;
        }
    }
    *out = scene;
    return ROMA_SUCCESS;
}

roma_result Loader::load(const unsigned char *data, size_t size, const char *base_dir, roma_scene **out)
{
    parse(data, size, base_dir);
    keep_anim_ = !m_.skins.empty() || !m_.animations.empty();
    build_hierarchy();
    build_materials();
    read_skins();
    std::vector<int> walk = scene_walk();
    for (int node : walk) {
        add_camera(node);
        add_light(node);
        int mesh = m_.nodes[(size_t)node].mesh;
        if (mesh < 0)
            continue;
        if ((size_t)mesh >= m_.meshes.size())
            fail(ROMA_ERROR_INVALID_SCENE, "node %d refers to mesh %d, which does not exist", node, mesh);
        for (size_t p = 0; p < m_.meshes[(size_t)mesh].primitives.size(); ++p)
            add_primitive(node, mesh, p);
    }
    if (idx_.empty())
        fail(ROMA_ERROR_EMPTY_SCENE, "no triangles in the default scene");
    uint32_t seen = (uint32_t)cameras_.size();
    if (camera_index_ > 0 && camera_index_ >= seen)
        fail(ROMA_ERROR_INVALID_ARGUMENT, "camera %u asked for (roma_gltf_desc.camera_index), the file has %u "
             "perspective camera%s (0 to %d)", camera_index_, seen, seen == 1 ? "" : "s", (int)seen - 1);
    return finish(out);
}

roma_result load_guarded(const unsigned char *data, size_t size, const char *base_dir, const char *label,
                         const roma_gltf_desc *desc, roma_scene **out)
{
    const roma_logger *log = desc ? &desc->logger : nullptr;
    uint32_t max_vertices = desc && desc->max_vertices ? desc->max_vertices : ROMA_GLTF_DEFAULT_MAX_VERTICES;
    uint32_t max_triangles = desc && desc->max_triangles ? desc->max_triangles : ROMA_GLTF_DEFAULT_MAX_TRIANGLES;
    uint32_t camera_index = desc ? desc->camera_index : 0;
    try {
        Loader loader(log, label, max_vertices, max_triangles, camera_index);
        return loader.load(data, size, base_dir, out);
    } catch (const Failure &f) {
        return f.code;
    } catch (const std::bad_alloc &) {
        return roma_fail(log, ROMA_ERROR_OUT_OF_HOST_MEMORY, "%s: out of host memory", label);
    } catch (const std::exception &e) {
        return roma_fail(log, ROMA_ERROR_PARSE, "%s: %s", label, e.what());
    } catch (...) {
        return roma_fail(log, ROMA_ERROR_PARSE, "%s: unexpected failure while loading", label);
    }
}

} // namespace

extern "C" roma_result roma_scene_load_gltf(const char *path, const roma_gltf_desc *desc, roma_scene **out_scene)
{
    const roma_logger *log = desc ? &desc->logger : nullptr;
    if (out_scene)
        *out_scene = nullptr;
    if (!path || !out_scene)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_scene_load_gltf: path and out_scene must not be NULL");
    try {
        FILE *f = fopen(path, "rb");
        if (!f) {
            int e = errno;
            return roma_fail(log, e == ENOENT || e == ENOTDIR ? ROMA_ERROR_FILE_NOT_FOUND : ROMA_ERROR_IO,
                             "%s: cannot open: %s", path, strerror(e));
        }
        std::vector<unsigned char> data;
        unsigned char chunk[65536];
        size_t got;
        while ((got = fread(chunk, 1, sizeof chunk, f)) > 0)
            data.insert(data.end(), chunk, chunk + got);
        bool bad = ferror(f) != 0;
        fclose(f);
        if (bad)
            return roma_fail(log, ROMA_ERROR_IO, "%s: read error", path);
        std::string dir = path;
        size_t slash = dir.find_last_of('/');
        dir = slash == std::string::npos ? std::string(".") : dir.substr(0, slash + 1);
        return load_guarded(data.data(), data.size(), dir.c_str(), path, desc, out_scene);
    } catch (const std::bad_alloc &) {
        return roma_fail(log, ROMA_ERROR_OUT_OF_HOST_MEMORY, "%s: out of host memory", path);
    } catch (...) {
        return roma_fail(log, ROMA_ERROR_IO, "%s: unexpected failure while reading", path);
    }
}

extern "C" roma_result roma_scene_load_gltf_memory(const void *data, size_t size, const char *base_dir,
                                                   const roma_gltf_desc *desc, roma_scene **out_scene)
{
    const roma_logger *log = desc ? &desc->logger : nullptr;
    if (out_scene)
        *out_scene = nullptr;
    if ((!data && size) || !out_scene)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_scene_load_gltf_memory: data and out_scene must not be NULL");
    static const unsigned char empty = 0;
    return load_guarded(data ? (const unsigned char *)data : &empty, size, base_dir, "(memory)", desc,
                        out_scene);
}
