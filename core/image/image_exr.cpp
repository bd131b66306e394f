// The OpenEXR C++ adapter (the module shadelab-exr.so, opened on first use by image_modules.c): the
// compressions OpenEXRCore 3.1 cannot decode (DWAA/DWAB: "not yet implemented, please use C++
// library"; B44/B44A on float channels, which it decodes wrongly), for the files image_native.c has
// checked and accepted otherwise. It reads the channels it is given, as stored (half or float),
// interleaved, and image_native.c converts them as it does its own. OpenImageIO decodes these
// files with this same library, so the values are its values (tests/test_image_native.c compares
// them); without this module they went through OpenImageIO, whose ~250 libraries take 0.2-0.4 s
// to load (the head scene's blender-data environment is DWAB). Every C++ exception is caught and
// reported as an error; image_native.c then leaves the file to OpenImageIO.
#define SL_IMAGE_INTERNAL
extern "C" {
#include "image/image.h"
}

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImathBox.h>

#include <cstdio>
#include <cstring>
#include <exception>
#include <stdexcept>

namespace {

// An encoded file held in memory (an EXR embedded in a .glb or a data: URI).
class MemoryStream : public Imf::IStream {
  public:
    MemoryStream(const void *data, size_t size, const char *name)
        : Imf::IStream(name), data_(static_cast<const char *>(data)), size_(size) {}
    bool read(char c[], int n) override {
        if (n < 0 || pos_ > size_ || static_cast<uint64_t>(n) > size_ - pos_) throw std::runtime_error("truncated file");
        std::memcpy(c, data_ + pos_, static_cast<size_t>(n));
        pos_ += static_cast<uint64_t>(n);
        return pos_ < size_;
    }
    uint64_t tellg() override { return pos_; }
    void seekg(uint64_t pos) override { pos_ = pos; }
    void clear() override {}

  private:
    const char *data_;
    uint64_t size_, pos_ = 0;
};

bool read_channels(Imf::InputFile &file, int x0, int y0, int w, int h, int nch, const char *const *names, bool half,
                   void *out) {
    const Imath::Box2i dw = file.header().dataWindow();
    if (dw.min.x != x0 || dw.min.y != y0 || dw.max.x - dw.min.x + 1 != w || dw.max.y - dw.min.y + 1 != h) return false;
    const size_t bpe = half ? 2 : 4, xs = bpe * static_cast<size_t>(nch), ys = xs * static_cast<size_t>(w);
    // the slices' base is the address of pixel (0, 0), which the data window may not contain
    char *base = static_cast<char *>(out) - static_cast<ptrdiff_t>(x0) * static_cast<ptrdiff_t>(xs) -
                 static_cast<ptrdiff_t>(y0) * static_cast<ptrdiff_t>(ys);
    Imf::FrameBuffer fb;
    for (int i = 0; i < nch; i++)
        fb.insert(names[i], Imf::Slice(half ? Imf::HALF : Imf::FLOAT, base + bpe * static_cast<size_t>(i), xs, ys));
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    return true;
}

bool mod_read(const char *path, const void *data, size_t size, int x0, int y0, int w, int h, int nch,
              const char *const *names, bool half, void *out, char *err, size_t n) {
    try {
        if (data) {
            MemoryStream stream(data, size, path);
            Imf::InputFile file(stream);
            return read_channels(file, x0, y0, w, h, nch, names, half, out);
        }
        Imf::InputFile file(path);
        return read_channels(file, x0, y0, w, h, nch, names, half, out);
    } catch (const std::exception &e) {
        if (err && n) std::snprintf(err, n, "%s", e.what());
    } catch (...) {
        if (err && n) std::snprintf(err, n, "unknown error in OpenEXR");
    }
    return false;
}

} // namespace

extern "C" __attribute__((visibility("default"))) const sl_exr_api *sl_exr_module_api(void) {
    static const sl_exr_api api = {sizeof(sl_exr_api), mod_read};
    return &api;
}
