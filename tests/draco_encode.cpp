// The test's own Draco encoder (Debian's libdraco behind one C function), so that
// test_gltf_compressed.c can write a KHR_draco_mesh_compression file itself.
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <cstdlib>
#include <cstring>

extern "C" unsigned char *sl_test_draco_encode(const float *pos, const float *nrm, const float *uv, const unsigned *idx,
                                               int faces, int ids[3], size_t *size) {
    draco::TriangleSoupMeshBuilder b;
    b.Start(faces);
    const int att[3] = {b.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32),
                        b.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32),
                        b.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32)};
    const float *data[3] = {pos, nrm, uv};
    const int comps[3] = {3, 3, 2};
    for (int f = 0; f < faces; f++)
        for (int a = 0; a < 3; a++)
            b.SetAttributeValuesForFace(att[a], draco::FaceIndex(f), data[a] + comps[a] * idx[3 * f],
                                        data[a] + comps[a] * idx[3 * f + 1], data[a] + comps[a] * idx[3 * f + 2]);
    std::unique_ptr<draco::Mesh> mesh = b.Finalize();
    if (!mesh) return nullptr;
    for (int a = 0; a < 3; a++) ids[a] = static_cast<int>(mesh->attribute(att[a])->unique_id());
    draco::Encoder encoder; // no quantization: the values come back exactly
    draco::EncoderBuffer out;
    if (!encoder.EncodeMeshToBuffer(*mesh, &out).ok()) return nullptr;
    unsigned char *bytes = static_cast<unsigned char *>(std::malloc(out.size()));
    if (bytes) std::memcpy(bytes, out.data(), out.size());
    *size = out.size();
    return bytes;
}
