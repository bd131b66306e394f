// envmap's image I/O for tools and tests (library envmap_io): a thin C adapter over
// OpenImageIO. The plugin does not link it: it reads through host->read_image (SDK 1.10), so
// that loading envmap.so does not load OpenImageIO's ~250 libraries. Reads any format OIIO
// reads as float RGBA; writes half-float EXR and 8-bit PNG with a description tag (the RGBE8
// marker). Every exception becomes an error message.
#include "envmap/io.h"
#include <shadelab/input.h>     /* sl_input_file_problem: the core's check */
#include <shadelab/shadelab.h> /* SL_IMAGE_MAX_PIXELS */

#include <OpenImageIO/imageio.h>
#include <OpenImageIO/strutil.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <strings.h>
#include <memory>
#include <string>
#include <vector>

using namespace OIIO;

static void set_err(char *err, size_t n, const std::string &msg) {
    if (!err || !n) return;
    std::string one;
    for (char c : msg) one += (c == '\n' || c == '\r') ? ' ' : c;
    if (one.empty()) one = "unknown OpenImageIO error";
    std::snprintf(err, n, "%s", one.c_str());
}

extern "C" bool em_io_load(const char *path, em_image *out, em_io_info *info, char *err, size_t n) {
    std::memset(out, 0, sizeof *out);
    std::memset(info, 0, sizeof *info);
    // OpenImageIO opens the path itself: a FIFO would block it, a device (/dev/zero, a symlink
    // to one) never ends. Only regular files are handed over, as the core's loader does.
    char why[160];
    if (sl_input_file_problem(path, why, sizeof why)) {
        std::snprintf(err, n, "%s: %s; refusing to read it", path, why);
        return false;
    }
    try {
        ImageSpec config;
        config.attribute("oiio:UnassociatedAlpha", 1); // RGBE keeps its exponent in alpha
        auto in = ImageInput::open(path, &config);
        if (!in) {
            set_err(err, n, std::string(path) + ": " + OIIO::geterror());
            return false;
        }
        const ImageSpec &spec = in->spec();
        if (spec.width < 1 || spec.height < 1 || spec.width > EM_IO_MAX_DIM || spec.height > EM_IO_MAX_DIM ||
            (long)spec.width * spec.height > SL_IMAGE_MAX_PIXELS || spec.nchannels < 1 || spec.depth > 1 || spec.deep) {
            std::snprintf(err, n,
                          "%s: %dx%d with %d channels (from its header) is not an image envmap can use (at most %d per "
                          "side and %ld Mpixel; refused before decoding)",
                          path, spec.width, spec.height, spec.nchannels, EM_IO_MAX_DIM, SL_IMAGE_MAX_PIXELS >> 20);
            return false;
        }
        info->bits = (int)spec.format.size() * 8;
        info->is_float = spec.format.is_floating_point();
        info->channels = spec.nchannels;
        std::snprintf(info->description, sizeof info->description, "%s",
                      spec.get_string_attribute("ImageDescription").c_str());
        info->srgb = !info->is_float && !Strutil::iequals(spec.get_string_attribute("oiio:ColorSpace"), "linear");
        std::snprintf(info->format, sizeof info->format, "%s", in->format_name());
        int ch = spec.nchannels < 4 ? spec.nchannels : 4;
        std::vector<float> raw((size_t)spec.width * spec.height * ch);
        if (!in->read_image(0, 0, 0, ch, TypeDesc::FLOAT, raw.data())) {
            set_err(err, n, std::string(path) + ": " + in->geterror());
            return false;
        }
        in->close();
        out->w = spec.width;
        out->h = spec.height;
        out->px = (float *)std::malloc((size_t)out->w * out->h * 4 * sizeof(float));
        for (size_t i = 0; i < (size_t)out->w * out->h; i++) {
            const float *s = &raw[i * ch];
            float *d = out->px + i * 4;
            if (ch <= 2) d[0] = d[1] = d[2] = s[0];
            else d[0] = s[0], d[1] = s[1], d[2] = s[2];
            d[3] = ch == 2 ? s[1] : ch == 4 ? s[3] : 1.0f;
        }
        return true;
    } catch (const std::exception &e) {
        set_err(err, n, std::string(path) + ": OpenImageIO exception: " + e.what());
    } catch (...) {
        set_err(err, n, std::string(path) + ": unknown exception in OpenImageIO");
    }
    return false;
}

static bool write_any(const char *path, const char *format, TypeDesc file_type, TypeDesc mem_type, const void *px,
                      int w, int h, int channels, const char *description, char *err, size_t n) {
    try {
        auto out = ImageOutput::create(format);
        if (!out) {
            set_err(err, n, std::string(path) + ": " + OIIO::geterror());
            return false;
        }
        ImageSpec spec(w, h, channels, file_type);
        if (channels == 4) spec.alpha_channel = 3;
        spec.attribute("oiio:UnassociatedAlpha", 1);
        if (description && *description) spec.attribute("ImageDescription", description);
        spec.attribute("Software", "shadelab envmap");
        // write to a temporary name and rename, so a failed write leaves an old file intact
        std::string tmp = std::string(path) + ".tmp." + format;
        if (!out->open(tmp, spec) || !out->write_image(mem_type, px)) {
            set_err(err, n, std::string(path) + ": " + out->geterror());
            out->close();
            std::remove(tmp.c_str());
            return false;
        }
        if (!out->close() || std::rename(tmp.c_str(), path) != 0) {
            set_err(err, n, std::string(path) + ": cannot write (" + out->geterror() + ")");
            std::remove(tmp.c_str());
            return false;
        }
        return true;
    } catch (const std::exception &e) {
        set_err(err, n, std::string(path) + ": OpenImageIO exception: " + e.what());
    } catch (...) {
        set_err(err, n, std::string(path) + ": unknown exception in OpenImageIO");
    }
    return false;
}

extern "C" bool em_io_write_exr(const char *path, const float *rgba, int w, int h, const char *description, char *err,
                                size_t n) {
    return write_any(path, "exr", TypeDesc::HALF, TypeDesc::FLOAT, rgba, w, h, 4, description, err, n);
}

extern "C" bool em_io_write_png8(const char *path, const unsigned char *rgba, int w, int h, const char *description,
                                 char *err, size_t n) {
    return write_any(path, "png", TypeDesc::UINT8, TypeDesc::UINT8, rgba, w, h, 4, description, err, n);
}

static bool io_read(void *ctx, const char *path, em_image *out, em_io_info *info, char *err, size_t n) {
    (void)ctx;
    return em_io_load(path, out, info, err, n);
}
extern "C" const em_reader em_io_reader = {io_read, nullptr};

extern "C" bool em_write_cube(const char *path, float *const faces[6], int size, char *err, size_t n) {
    em_image cross;
    em_faces_to_hcross(faces, size, &cross);
    size_t len = std::strlen(path);
    bool ok;
    if (len > 4 && !strcasecmp(path + len - 4, ".png")) {
        std::vector<unsigned char> b((size_t)cross.w * cross.h * 4);
        em_rgbe_encode_image(cross.px, (size_t)cross.w * cross.h, b.data());
        ok = em_io_write_png8(path, b.data(), cross.w, cross.h, EM_RGBE_TAG, err, n);
    } else if (len > 4 && !strcasecmp(path + len - 4, ".exr")) {
        ok = em_io_write_exr(path, cross.px, cross.w, cross.h, "shadelab cube (horizontal cross)", err, n);
    } else {
        std::snprintf(err, n, "%s: the output must be .exr (half float) or .png (RGBE8)", path);
        ok = false;
    }
    em_image_free(&cross);
    return ok;
}
