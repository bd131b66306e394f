// The only C++ in core/image: a thin adapter over OpenImageIO behind the C functions declared
// in image.h's SL_IMAGE_INTERNAL section, built as the module shadelab-oiio.so that
// oiio_module.c opens on first use (its one export: sl_oiio_module_api). Policy (path checks, size limits, channel layout,
// colour handling, error wording) lives in image.c; this file only talks to OIIO and turns
// exceptions and OIIO errors into messages.
#define SL_IMAGE_INTERNAL
extern "C" {
#include "image/image.h"
}

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

using namespace OIIO;

struct sl_oiio_input {
    std::unique_ptr<Filesystem::IOMemReader> proxy; // in-memory images: outlives `in`
    std::unique_ptr<ImageInput> in;
};

// OIIO messages can span lines and repeat the file name; keep them to one line.
static void set_err(char *err, size_t err_size, const std::string &msg) {
    if (!err || !err_size) return;
    std::string one;
    for (char c : msg) one += (c == '\n' || c == '\r') ? ' ' : c;
    while (!one.empty() && one.back() == ' ') one.pop_back();
    if (one.empty()) one = "unknown OpenImageIO error";
    std::snprintf(err, err_size, "%s", one.c_str());
}

static void copy_str(char *dst, size_t size, const std::string &s) {
    std::snprintf(dst, size, "%s", s.c_str());
}

static sl_oiio_input *open_any(const char *path, const void *data, size_t size, sl_oiio_info *info,
                               char *err, size_t err_size) {
    try {
        // Return the samples as stored: without this hint OIIO premultiplies the colour of
        // files that store unassociated alpha (PNG, many TIFFs) by alpha on read.
        ImageSpec config;
        config.attribute("oiio:UnassociatedAlpha", 1);
        std::unique_ptr<Filesystem::IOMemReader> proxy;
        if (data) {
            proxy.reset(new Filesystem::IOMemReader(data, size));
            void *ptr = proxy.get(); /* how OIIO 2.4's readers find a proxy (imageio.h, "oiio:ioproxy") */
            config.attribute("oiio:ioproxy", TypeDesc::PTR, &ptr);
        }
        auto in = ImageInput::open(path, &config, proxy.get());
        if (!in) {
            set_err(err, err_size, OIIO::geterror());
            return nullptr;
        }
        const ImageSpec &spec = in->spec();
        std::memset(info, 0, sizeof *info);
        info->width = spec.width;
        info->height = spec.height;
        info->depth = spec.depth;
        info->channels = spec.nchannels;
        info->alpha_channel = spec.alpha_channel;
        info->bits = (int)spec.format.size() * 8;
        info->is_float = spec.format.is_floating_point();
        info->deep = spec.deep;
        copy_str(info->format_name, sizeof info->format_name, in->format_name());
        copy_str(info->colorspace, sizeof info->colorspace,
                 spec.get_string_attribute("oiio:ColorSpace"));
        copy_str(info->description, sizeof info->description, spec.get_string_attribute("ImageDescription"));
        auto *h = new sl_oiio_input;
        h->proxy = std::move(proxy);
        h->in = std::move(in);
        return h;
    } catch (const std::exception &e) {
        set_err(err, err_size, std::string("OpenImageIO exception: ") + e.what());
    } catch (...) {
        set_err(err, err_size, "unknown exception in OpenImageIO");
    }
    return nullptr;
}

static sl_oiio_input *mod_open(const char *path, sl_oiio_info *info, char *err,
                                       size_t err_size) {
    return open_any(path, nullptr, 0, info, err, err_size);
}

// An image held in memory (an embedded glTF image): `name`'s extension picks the reader first.
static sl_oiio_input *mod_open_memory(const void *data, size_t size, const char *name,
                                              sl_oiio_info *info, char *err, size_t err_size) {
    return open_any(name, data, size, info, err, err_size);
}

static bool mod_read(sl_oiio_input *h, int chbegin, int chend, float *out, char *err,
                             size_t err_size) {
    try {
        if (h->in->read_image(0, 0, chbegin, chend, TypeDesc::FLOAT, out)) {
            /* a reader that recovered (libjpeg fills a truncated file with grey) still reports why */
            if (err && err_size) err[0] = 0;
            if (h->in->has_error()) set_err(err, err_size, h->in->geterror());
            return true;
        }
        set_err(err, err_size, h->in->geterror());
    } catch (const std::exception &e) {
        set_err(err, err_size, std::string("OpenImageIO exception: ") + e.what());
    } catch (...) {
        set_err(err, err_size, "unknown exception in OpenImageIO");
    }
    return false;
}

static void mod_close(sl_oiio_input *h) {
    if (!h) return;
    try {
        h->in->close();
    } catch (...) {
    }
    delete h;
}

static bool mod_write(const char *path, const char *format,
                              const unsigned char *pixels8, const float *pixelsf, int width,
                              int height, int channels, const char *file_type,
                              int jpeg_quality, char *err, size_t err_size) {
    try {
        auto out = ImageOutput::create(format);
        if (!out) {
            set_err(err, err_size, OIIO::geterror());
            return false;
        }
        ImageSpec spec(width, height, channels, TypeDesc(file_type));
        if (channels == 4) spec.alpha_channel = 3;
        // Our pixels are unassociated (straight) alpha; without this OIIO divides colour by
        // alpha when writing formats that store straight alpha (PNG).
        spec.attribute("oiio:UnassociatedAlpha", 1);
        if (jpeg_quality > 0) spec.attribute("Compression", "jpeg:" + std::to_string(jpeg_quality));
        if (std::strcmp(format, "png") == 0 || std::strcmp(format, "jpeg") == 0)
            spec.attribute("oiio:ColorSpace", "sRGB");
        else
            spec.attribute("oiio:ColorSpace", "Linear");
        if (!out->open(path, spec)) {
            set_err(err, err_size, out->geterror());
            return false;
        }
        bool ok = pixels8 ? out->write_image(TypeDesc::UINT8, pixels8)
                          : out->write_image(TypeDesc::FLOAT, pixelsf);
        std::string msg = ok ? std::string() : out->geterror();
        bool closed = out->close();
        if (!ok || !closed) {
            set_err(err, err_size, ok ? out->geterror() : msg);
            return false;
        }
        return true;
    } catch (const std::exception &e) {
        set_err(err, err_size, std::string("OpenImageIO exception: ") + e.what());
    } catch (...) {
        set_err(err, err_size, "unknown exception in OpenImageIO");
    }
    return false;
}

// "extension_list" reads like "tiff:tif,tiff;jpeg:jpg,jpe,jpeg;...".
static bool mod_extension_known(const char *ext) {
    try {
        std::string list = OIIO::get_string_attribute("extension_list");
        size_t pos = 0;
        while (pos < list.size()) {
            size_t end = list.find(';', pos);
            if (end == std::string::npos) end = list.size();
            std::string entry = list.substr(pos, end - pos);
            size_t colon = entry.find(':');
            std::string exts = colon == std::string::npos ? entry : entry.substr(colon + 1);
            size_t p = 0;
            while (p <= exts.size()) {
                size_t c = exts.find(',', p);
                if (c == std::string::npos) c = exts.size();
                if (exts.compare(p, c - p, ext) == 0 && c - p == std::strlen(ext)) return true;
                p = c + 1;
            }
            pos = end + 1;
        }
    } catch (...) {
    }
    return false;
}

extern "C" __attribute__((visibility("default"))) const sl_oiio_api *sl_oiio_module_api(void) {
    static const sl_oiio_api api = {sizeof(sl_oiio_api), mod_open,  mod_open_memory,     mod_read,
                                    mod_close,           mod_write, mod_extension_known};
    return &api;
}
