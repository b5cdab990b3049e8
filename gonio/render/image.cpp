#include "gonio/render/image.h"

#include "core/colour.h"

#include <ImfArray.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <png.h>
#include <stdexcept>
#include <unistd.h>

namespace gonio {

namespace {
std::string temporary(const std::string& path) {
    return path + ".tmp-" + std::to_string(::getpid());
}
void publish(const std::string& tmp, const std::string& path) {
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::remove(tmp.c_str());
        throw std::runtime_error("cannot rename " + tmp + " to " + path + ": " + ec.message());
    }
}
} // namespace

void write_png(const Image& image, const std::string& path) {
    const std::string tmp = temporary(path);
    FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw std::runtime_error(path + ": cannot create");
    std::vector<png_byte> row(size_t(image.width) * 3); // before setjmp: no destructor skipped
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        std::fclose(f);
        std::remove(tmp.c_str());
        throw std::runtime_error(path + ": libpng failed to write");
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, png_uint_32(image.width), png_uint_32(image.height), 8,
                 PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c)
                row[size_t(x) * 3 + c] =
                    png_byte(std::lround(255 * srgb_encode(image.at(x, y)[c])));
        png_write_row(png, row.data());
    }
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    if (std::fclose(f) != 0) {
        std::remove(tmp.c_str());
        throw std::runtime_error(path + ": write failed");
    }
    publish(tmp, path);
}

void write_exr(const Image& image, const std::string& path) {
    const std::string tmp = temporary(path);
    try {
        Imf::Header header(image.width, image.height);
        for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
        Imf::OutputFile out(tmp.c_str(), header);
        Imf::FrameBuffer fb;
        const size_t xs = 3 * sizeof(float), ys = xs * size_t(image.width);
        char* base = reinterpret_cast<char*>(const_cast<float*>(image.rgb.data()));
        fb.insert("R", Imf::Slice(Imf::FLOAT, base, xs, ys));
        fb.insert("G", Imf::Slice(Imf::FLOAT, base + sizeof(float), xs, ys));
        fb.insert("B", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), xs, ys));
        out.setFrameBuffer(fb);
        out.writePixels(image.height);
    } catch (const std::exception& e) {
        std::remove(tmp.c_str());
        throw std::runtime_error(path + ": " + e.what());
    }
    publish(tmp, path);
}

Image read_exr_rgb(const std::string& path) {
    if (!std::filesystem::exists(path)) throw std::runtime_error(path + ": no such file");
    try {
        Imf::InputFile in(path.c_str());
        const Imath::Box2i dw = in.header().dataWindow();
        const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
        Image img(w, h);
        const bool rgb = in.header().channels().findChannel("R") != nullptr;
        if (!rgb && !in.header().channels().findChannel("Y"))
            throw std::runtime_error("no R, G, B or Y channel");
        Imf::FrameBuffer fb;
        const long offset = long(dw.min.x) + long(dw.min.y) * long(w);
        std::vector<float> grey;
        if (rgb) {
            const size_t xs = 3 * sizeof(float), ys = xs * size_t(w);
            char* base = reinterpret_cast<char*>(img.rgb.data()) - offset * long(xs);
            const char* names[3] = {"R", "G", "B"};
            for (int c = 0; c < 3; ++c)
                fb.insert(names[c],
                          Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xs, ys, 1, 1, 0.0));
        } else { // one grey channel, repeated
            grey.assign(size_t(w) * size_t(h), 0.0f);
            char* base = reinterpret_cast<char*>(grey.data()) - offset * long(sizeof(float));
            fb.insert("Y", Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * size_t(w)));
        }
        in.setFrameBuffer(fb);
        in.readPixels(dw.min.y, dw.max.y);
        for (size_t k = 0; k < grey.size(); ++k)
            for (int c = 0; c < 3; ++c) img.rgb[3 * k + size_t(c)] = grey[k];
        for (float v : img.rgb)
            if (!std::isfinite(v)) throw std::runtime_error("a texel is not a finite number");
        return img;
    } catch (const std::exception& e) {
        throw std::runtime_error(path + ": not a readable OpenEXR image (" + e.what() + ")");
    }
}

} // namespace gonio
