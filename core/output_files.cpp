#include "core/output_files.h"

#include <cerrno>
#include <csignal>
#include <filesystem>
#include <stdexcept>
#include <unistd.h>

namespace gonio {

namespace fs = std::filesystem;

std::string temporary_name(const std::string& path) {
    return path + ".tmp-" + std::to_string(::getpid());
}

int remove_stale_temporaries(const std::string& path) {
    const fs::path p(path);
    const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
    const std::string prefix = p.filename().string() + ".tmp-";
    std::error_code ec;
    int removed = 0;
    for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
        const std::string name = e.path().filename().string();
        if (name.rfind(prefix, 0) != 0) continue;
        const std::string digits = name.substr(prefix.size());
        if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos) continue;
        const long pid = std::stol(digits);
        // kill(pid, 0) fails with ESRCH when no such process exists: its file is an orphan.
        if (pid > 0 && pid != long(::getpid()) && ::kill(pid_t(pid), 0) != 0 && errno == ESRCH) {
            std::error_code rm;
            if (fs::remove(e.path(), rm)) ++removed;
        }
    }
    return removed;
}

bool same_file(const std::string& a, const std::string& b) {
    std::error_code ec;
    if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
    return fs::weakly_canonical(fs::absolute(a), ec) == fs::weakly_canonical(fs::absolute(b), ec);
}

std::string OutputSet::add(const std::string& path) {
    if (fs::is_directory(path)) throw std::runtime_error(path + ": is a directory");
    if (!overwrite_ && fs::exists(path))
        throw std::runtime_error(path + ": exists; pass --overwrite to replace it");
    remove_stale_temporaries(path);
    files_.emplace_back(path, temporary_name(path));
    return files_.back().second;
}

void OutputSet::commit() {
    for (const auto& [path, tmp] : files_)
        if (!fs::exists(tmp)) throw std::runtime_error(path + ": was not written");
    size_t done = 0;
    std::error_code ec;
    for (; done < files_.size(); ++done) {
        fs::rename(files_[done].second, files_[done].first, ec);
        if (ec) break;
    }
    if (ec) {
        const std::string why =
            files_[done].first + ": cannot be written in place: " + ec.message();
        std::error_code rm;
        for (size_t k = 0; k < done; ++k) fs::remove(files_[k].first, rm); // all or nothing
        throw std::runtime_error(why);
    }
    committed_ = true;
}

OutputSet::~OutputSet() {
    if (committed_) return;
    std::error_code ec;
    for (const auto& [path, tmp] : files_) fs::remove(tmp, ec);
}

} // namespace gonio
