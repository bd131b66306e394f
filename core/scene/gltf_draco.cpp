// The Draco decoder (Debian's libdraco) behind the C table of gltf_draco.h: the module
// shadelab-draco.so, opened by the glTF reader on the first KHR_draco_mesh_compression primitive.
#include "scene/gltf_draco.h"

#include <draco/compression/decode.h>
#include <draco/mesh/mesh.h>
#include <cstdio>
#include <memory>
#include <new>

namespace {

void *decode(const unsigned char *data, size_t size, int *points, int *faces, char *err, size_t n) {
    try {
        draco::DecoderBuffer buffer;
        buffer.Init(reinterpret_cast<const char *>(data), size);
        auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
        if (!type.ok() || type.value() != draco::TRIANGULAR_MESH) {
            std::snprintf(err, n, "not a Draco triangle mesh%s%s", type.ok() ? "" : ": ",
                          type.ok() ? "" : type.status().error_msg());
            return nullptr;
        }
        draco::Decoder decoder;
        auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
        if (!decoded.ok()) {
            std::snprintf(err, n, "Draco: %s", decoded.status().error_msg());
            return nullptr;
        }
        std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
        if (mesh->num_points() > (1u << 26) || mesh->num_faces() > (1u << 26)) {
            std::snprintf(err, n, "Draco mesh of %u points and %u faces: over 2^26", mesh->num_points(), mesh->num_faces());
            return nullptr;
        }
        *points = static_cast<int>(mesh->num_points());
        *faces = static_cast<int>(mesh->num_faces());
        return mesh.release();
    } catch (const std::bad_alloc &) {
        std::snprintf(err, n, "out of memory decoding Draco data");
        return nullptr;
    }
}

void indices(const void *m, uint32_t *out) {
    const auto *mesh = static_cast<const draco::Mesh *>(m);
    for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
        for (int k = 0; k < 3; k++) *out++ = mesh->face(f)[k].value();
}

bool attribute(const void *m, int unique_id, int comps, float *out) {
    const auto *mesh = static_cast<const draco::Mesh *>(m);
    const draco::PointAttribute *a = mesh->GetAttributeByUniqueId(static_cast<uint32_t>(unique_id));
    if (!a || a->num_components() < comps) return false;
    for (draco::PointIndex p(0); p < mesh->num_points(); ++p)
        if (!a->ConvertValue<float>(a->mapped_index(p), static_cast<int8_t>(comps), out + static_cast<size_t>(p.value()) * comps))
            return false;
    return true;
}

void release(void *m) { delete static_cast<draco::Mesh *>(m); }

const sl_draco_api api = {sizeof(sl_draco_api), decode, indices, attribute, release};

} // namespace

extern "C" __attribute__((visibility("default"))) const sl_draco_api *sl_draco_module_api(void) { return &api; }
