#pragma once
// An HDF5 file gonio writes whole: created under path.tmp-<pid> with checksummed object headers
// and chunks and a user block for the file's CRC-32; commit() seals every group under the root and
// the root (h5::seal), closes it, writes the checksum and renames it into place. Uncommitted, the
// temporary is removed. The result writer and gonio masking's writer share it.
#include "gonio/io/hdf5_handles.h"

#include <string>

namespace gonio {

class SealedFile {
  public:
    // Throws std::runtime_error naming the path if it exists (without overwrite), is a
    // directory, or cannot be created; `what` names the kind of file in the message.
    SealedFile(std::string path, bool overwrite, const std::string& what);
    ~SealedFile();
    SealedFile(const SealedFile&) = delete;
    SealedFile& operator=(const SealedFile&) = delete;

    operator hid_t() const { return file_; }
    const std::string& path() const { return path_; }
    void commit();

  private:
    std::string path_, tmp_path_;
    h5::Handle file_;
    bool committed_ = false;
};

} // namespace gonio
