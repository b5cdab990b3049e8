#include "heightfield/exr_io.h"

#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <unistd.h>

namespace gonio {

namespace {

void add_attributes(Imf::Header& header, const ExrAttributes& attrs) {
    for (const auto& [k, v] : attrs.text) header.insert(k, Imf::StringAttribute(v));
    for (const auto& [k, v] : attrs.numbers) header.insert(k, Imf::DoubleAttribute(v));
}

// Writes through a temporary file, renamed when complete.
template <class Fill>
void write_atomically(const std::string& path, Fill fill) {
    const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
    try {
        fill(tmp);
    } catch (const std::exception& e) {
        std::remove(tmp.c_str());
        throw std::runtime_error(path + ": cannot write EXR: " + e.what());
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::remove(tmp.c_str());
        throw std::runtime_error(path + ": cannot write EXR: " + ec.message());
    }
}

} // namespace

void write_channels_exr(const std::string& path, int width, int height,
                        const std::vector<std::string>& names,
                        const std::vector<std::vector<float>>& channels,
                        const ExrAttributes& attrs) {
    write_atomically(path, [&](const std::string& tmp) {
        Imf::Header header(width, height);
        for (const auto& name : names) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
        add_attributes(header, attrs);
        Imf::OutputFile file(tmp.c_str(), header);
        Imf::FrameBuffer fb;
        for (size_t c = 0; c < names.size(); ++c)
            fb.insert(names[c], Imf::Slice(Imf::FLOAT, (char*)channels[c].data(), sizeof(float),
                                           sizeof(float) * size_t(width)));
        file.setFrameBuffer(fb);
        file.writePixels(height);
    });
}

void write_height_exr(const std::string& path, const HeightField& s, const ExrAttributes& attrs) {
    ExrAttributes all = attrs;
    all.numbers["gonio_spacing"] = s.spacing;
    write_channels_exr(path, s.n, s.n, {"Y"}, {s.h}, all);
}

HeightField read_height_exr(const std::string& path, ExrAttributes* attrs) {
    if (!std::filesystem::exists(path)) throw std::runtime_error(path + ": no such height map");
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
        if (w != h)
            throw std::runtime_error("the height map must be square (it is " + std::to_string(w) +
                                     " x " + std::to_string(h) + ")");
        if (w < 2) throw std::runtime_error("the height map must be at least 2 x 2");
        std::string channel;
        for (const char* name : {"Y", "Z", "H", "R"})
            if (file.header().channels().findChannel(name)) {
                channel = name;
                break;
            }
        if (channel.empty()) throw std::runtime_error("no channel named Y, Z, H or R");
        HeightField s(w, 1.0);
        Imf::FrameBuffer fb;
        char* base = (char*)(s.h.data() - dw.min.x - size_t(dw.min.y) * w);
        fb.insert(channel, Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * size_t(w)));
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        for (auto it = file.header().begin(); it != file.header().end(); ++it) {
            const std::string name = it.name();
            if (const auto* d = dynamic_cast<const Imf::DoubleAttribute*>(&it.attribute())) {
                if (name == "gonio_spacing") s.spacing = d->value();
                if (attrs) attrs->numbers[name] = d->value();
            } else if (const auto* t = dynamic_cast<const Imf::StringAttribute*>(&it.attribute())) {
                if (attrs) attrs->text[name] = t->value();
            }
        }
        if (!(s.spacing > 0)) throw std::runtime_error("gonio_spacing must be > 0");
        for (float v : s.h)
            if (!std::isfinite(v))
                throw std::runtime_error("the height map holds NaN or infinite values");
        return s;
    } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        if (what.rfind(path, 0) == 0) throw;
        throw std::runtime_error(path + ": cannot read height map: " + what);
    } catch (const std::exception& e) {
        throw std::runtime_error(path + ": cannot read height map: " + e.what());
    }
}

} // namespace gonio
