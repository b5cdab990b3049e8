#include "gonio/io/sealed_file.h"

#include "core/output_files.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace gonio {

SealedFile::SealedFile(std::string path, bool overwrite, const std::string& what)
    : path_(std::move(path)) {
    h5::silence_errors();
    if (!overwrite && std::filesystem::exists(path_))
        throw std::runtime_error(path_ + ": exists; pass --overwrite to replace it");
    if (std::filesystem::is_directory(path_))
        throw std::runtime_error(path_ + ": is a directory, not " + what);
    remove_stale_temporaries(path_); // of gonio processes that were killed writing it
    tmp_path_ = temporary_name(path_);
    try {
        // Track link creation order so readers list the groups in the order written, not by
        // name; leave the user block for the file's checksum.
        h5::Handle fcpl = h5::file_creation_with_checksum();
        h5::check(H5Pset_link_creation_order(fcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
                  "H5Pset_link_creation_order");
        // Every object's header and every chunk checksummed: a damaged file is refused on reading.
        const h5::Handle fapl = h5::checksummed_file_access();
        file_ = h5::Handle(H5Fcreate(tmp_path_.c_str(), H5F_ACC_TRUNC, fcpl, fapl), H5Fclose,
                           "create the file");
    } catch (const std::exception& e) {
        throw std::runtime_error(path_ + ": " + e.what());
    }
}

SealedFile::~SealedFile() {
    if (!committed_) {
        h5::discard_file(file_.get());
        file_.release();
        std::remove(tmp_path_.c_str());
    }
}

void SealedFile::commit() {
    // Sealed last: every group's datasets and attributes, then the root's (h5::seal).
    H5G_info_t info;
    h5::check(H5Gget_info(file_, &info), "H5Gget_info");
    for (hsize_t k = 0; k < info.nlinks; ++k) {
        const std::string name = h5::link_name(file_, H5_INDEX_CRT_ORDER, k);
        h5::Handle group(H5Gopen2(file_, name.c_str(), H5P_DEFAULT), H5Gclose, "open group");
        h5::seal(group, true);
    }
    h5::seal(file_, false);
    h5::check(H5Fflush(file_, H5F_SCOPE_GLOBAL), "flush");
    const herr_t closed = H5Fclose(file_.get());
    file_.release();
    h5::check(closed, "close");
    h5::write_file_checksum(tmp_path_);
    std::error_code ec;
    std::filesystem::rename(tmp_path_, path_, ec);
    if (ec) throw std::runtime_error("cannot rename " + tmp_path_ + " to it: " + ec.message());
    committed_ = true;
}

} // namespace gonio
