#pragma once
// Outputs appear whole or not at all. Each is written under a temporary name, path.tmp-<pid>,
// and renamed into place when complete; an output of several files (a render's PNG and EXR, a
// surface's height map, normals and NDF maps) is renamed only when every one of them is written.
// The temporaries of a process killed mid-write (kill -9, a power cut) are removed by the next
// gonio that writes the same output.
#include <string>
#include <vector>

namespace gonio {

// path.tmp-<this process's id>.
std::string temporary_name(const std::string& path);

// Removes path.tmp-<pid> files whose process no longer runs; returns how many.
int remove_stale_temporaries(const std::string& path);

// Whether two paths name the same file (existing or not: compared as absolute, normalised paths,
// and by identity when both exist).
bool same_file(const std::string& a, const std::string& b);

class OutputSet {
  public:
    explicit OutputSet(bool overwrite) : overwrite_(overwrite) {}
    ~OutputSet(); // uncommitted: every temporary is removed
    OutputSet(const OutputSet&) = delete;
    OutputSet& operator=(const OutputSet&) = delete;

    // Adds `path` to the set and returns the temporary name to write it under. Throws
    // std::runtime_error naming the path if it exists (without overwrite) or is a directory.
    std::string add(const std::string& path);
    // Renames every temporary into place; a failure removes what it renamed and the rest.
    void commit();

  private:
    bool overwrite_;
    std::vector<std::pair<std::string, std::string>> files_; // (path, temporary)
    bool committed_ = false;
};

} // namespace gonio
