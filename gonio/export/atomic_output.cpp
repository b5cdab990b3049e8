#include "gonio/export/atomic_output.h"

#include "core/output_files.h"

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <unistd.h>

namespace gonio {

AtomicOutput::AtomicOutput(std::string path, bool overwrite, bool binary)
    : path_(std::move(path)), tmp_(temporary_name(path_)) {
    if (std::filesystem::is_directory(path_)) throw std::runtime_error(path_ + ": is a directory");
    if (!overwrite && std::filesystem::exists(path_))
        throw std::runtime_error(path_ + ": exists; pass --overwrite to replace it");
    remove_stale_temporaries(path_);
    out_.open(tmp_, binary ? std::ios::binary | std::ios::trunc : std::ios::trunc);
    if (!out_) throw std::runtime_error(tmp_ + ": cannot create");
}

AtomicOutput::~AtomicOutput() {
    if (!committed_) {
        out_.close();
        std::remove(tmp_.c_str());
    }
}

long long AtomicOutput::commit() {
    out_.flush();
    if (!out_) throw std::runtime_error(tmp_ + ": write failed");
    out_.close();
    std::error_code ec;
    std::filesystem::rename(tmp_, path_, ec);
    if (ec)
        throw std::runtime_error("cannot rename " + tmp_ + " to " + path_ + ": " + ec.message());
    committed_ = true;
    return static_cast<long long>(std::filesystem::file_size(path_));
}

} // namespace gonio
