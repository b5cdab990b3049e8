#include "heightfield/exr_io.h"

#include "heightfield/frankot_chellappa.h"

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
#include <zlib.h>

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
    all.text["gonio_heights_crc32"] = heights_checksum(s); // checked when the map is read
    write_channels_exr(path, s.n, s.n, {"Y"}, {s.h}, all);
}

std::string heights_checksum(const HeightField& s) {
    uLong crc = crc32(0L, Z_NULL, 0);
    crc = crc32(crc, reinterpret_cast<const Bytef*>(s.h.data()), uInt(s.h.size() * sizeof(float)));
    crc = crc32(crc, reinterpret_cast<const Bytef*>(&s.spacing), uInt(sizeof(double)));
    char text[16];
    std::snprintf(text, sizeof text, "%08lx", static_cast<unsigned long>(crc));
    return text;
}

std::string height_map_problem(const HeightField& s) {
    const double period = s.n * s.spacing;
    float lo = s.h[0], hi = s.h[0];
    for (float v : s.h) {
        if (!std::isfinite(v)) return "the height map holds NaN or infinite values";
        lo = std::min(lo, v), hi = std::max(hi, v);
    }
    // A patch far taller than it is wide is no surface to trace (its rays would cross the
    // patch's walls without end); heights far from 0 leave no float precision for its slopes.
    char text[200];
    if (double(hi) - double(lo) > kMaxReliefOverPeriod * period) {
        std::snprintf(text, sizeof text,
                      "its relief (%.3g) is more than %g times its period (%.3g): absurd for its "
                      "size",
                      double(hi) - double(lo), kMaxReliefOverPeriod, period);
        return text;
    }
    if (std::max(std::abs(double(lo)), std::abs(double(hi))) > 1e6 * period) {
        std::snprintf(text, sizeof text,
                      "its heights reach %.3g, a million times its period (%.3g): level it first",
                      std::max(std::abs(double(lo)), std::abs(double(hi))), period);
        return text;
    }
    return "";
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
        const Imf::ChannelList& ch = file.header().channels();
        if (ch.findChannel("R") && ch.findChannel("G") && ch.findChannel("B") &&
            !ch.findChannel("Y") && !ch.findChannel("Z") && !ch.findChannel("H")) {
            // A normal map: (R, G, B) is the unit normal (x, y, z) of each texel; its slopes are
            // integrated into heights by least squares (Frankot-Chellappa, R19 Eq. 20-21), whose
            // forward differences -- the triangles' slopes -- then reproduce an integrable map.
            std::vector<float> nx(size_t(w) * w), ny(nx.size()), nz(nx.size());
            Imf::FrameBuffer fb;
            const size_t offset = size_t(dw.min.x) + size_t(dw.min.y) * w;
            for (auto [name, v] : {std::pair{"R", &nx}, {"G", &ny}, {"B", &nz}})
                fb.insert(name, Imf::Slice(Imf::FLOAT, (char*)(v->data() - offset), sizeof(float),
                                           sizeof(float) * size_t(w)));
            file.setFrameBuffer(fb);
            file.readPixels(dw.min.y, dw.max.y);
            std::vector<float> p(nx.size()), q(nx.size());
            for (size_t k = 0; k < nx.size(); ++k) {
                if (!(nz[k] > 0) || !std::isfinite(nx[k]) || !std::isfinite(ny[k]))
                    throw std::runtime_error("a normal map's normals must point up (B > 0)");
                p[k] = -nx[k] / nz[k], q[k] = -ny[k] / nz[k];
            }
            HeightField s(w, 1.0);
            FrankotChellappa(w, 1).integrate(p, q, s.h);
            if (attrs) attrs->text["gonio_source"] = "normal map";
            if (const std::string why = height_map_problem(s); !why.empty())
                throw std::runtime_error(why);
            return s;
        }
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
        ExrAttributes read; // every attribute, the checksum's included
        for (auto it = file.header().begin(); it != file.header().end(); ++it) {
            const std::string name = it.name();
            if (const auto* d = dynamic_cast<const Imf::DoubleAttribute*>(&it.attribute())) {
                if (name == "gonio_spacing") s.spacing = d->value();
                read.numbers[name] = d->value();
            } else if (const auto* t = dynamic_cast<const Imf::StringAttribute*>(&it.attribute())) {
                read.text[name] = t->value();
            }
        }
        if (attrs) *attrs = read;
        if (!(s.spacing > 0) || !std::isfinite(s.spacing))
            throw std::runtime_error("gonio_spacing must be finite and > 0");
        // A map gonio wrote (attributes gonio_* other than the spacing anyone may give) carries
        // its heights' checksum; one whose checksum is missing or wrong is damaged.
        bool gonio_wrote = false;
        for (const auto& [k, v] : read.text) gonio_wrote = gonio_wrote || k.rfind("gonio_", 0) == 0;
        for (const auto& [k, v] : read.numbers)
            gonio_wrote = gonio_wrote || (k.rfind("gonio_", 0) == 0 && k != "gonio_spacing");
        const auto crc = read.text.find("gonio_heights_crc32");
        if (gonio_wrote && crc == read.text.end())
            throw std::runtime_error("a map gonio wrote, without the checksum of its heights "
                                     "(damaged, or written before maps carried one: make it "
                                     "again with gonio surface)");
        if (gonio_wrote && crc->second != heights_checksum(s))
            throw std::runtime_error("its heights do not match the checksum gonio wrote with them "
                                     "(the file is damaged)");
        if (const std::string why = height_map_problem(s); !why.empty())
            throw std::runtime_error(why);
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

namespace gonio {

void write_normal_exr(const std::string& path, const HeightField& surface,
                      const ExrAttributes& attrs) {
    const int n = surface.n;
    std::vector<std::vector<float>> rgb(3, std::vector<float>(size_t(n) * n));
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const Vec3 m = HeightField::normal_of_slopes(surface.p(x, y), surface.q(x, y));
            const size_t k = size_t(y) * n + x;
            rgb[0][k] = float(m.x), rgb[1][k] = float(m.y), rgb[2][k] = float(m.z);
        }
    write_channels_exr(path, n, n, {"R", "G", "B"}, rgb, attrs);
}

} // namespace gonio
