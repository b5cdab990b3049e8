#pragma once
// An output file written under a temporary name (path.tmp-PID) and renamed to its path by
// commit(); destroyed uncommitted, it removes the temporary file, so a refused or failed export
// leaves nothing behind.
#include <fstream>
#include <string>

namespace gonio {

class AtomicOutput {
  public:
    // Throws std::runtime_error if `path` exists and !overwrite, or the file cannot be created.
    AtomicOutput(std::string path, bool overwrite, bool binary);
    ~AtomicOutput();
    AtomicOutput(const AtomicOutput&) = delete;
    AtomicOutput& operator=(const AtomicOutput&) = delete;

    std::ofstream& stream() { return out_; }
    // Flushes, closes and renames; returns the file's size in bytes.
    long long commit();

  private:
    std::string path_, tmp_;
    std::ofstream out_;
    bool committed_ = false;
};

} // namespace gonio
