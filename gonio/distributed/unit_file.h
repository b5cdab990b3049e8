#pragma once
// A file of finished work units: a shard's part (`gonio run --shard i/N`, put together by
// `gonio merge`) or a running job's checkpoint (`gonio run --resume`). HDF5, format
// "gonio-units 1": the run's identity in root attributes (gonio version and git hash, seed,
// effective config, shard), one opaque dataset per unit holding its traces exactly
// (work_units.h), with its case and incidence as attributes.
#include "gonio/distributed/work_units.h"

#include <string>
#include <vector>

namespace gonio {

struct UnitFileHeader {
    std::string version, git_hash, effective_toml, config_path, config_toml, overrides;
    std::string command_line, shard = "0/1";
    bool by_batches = false; // a single-incidence job's shard: a share of the batches
    long long seed = 0, units_total = 0;
    // What must agree between parts of one job (or a checkpoint and the run resuming it); empty
    // when they do, else the first difference.
    std::string differs_from(const UnitFileHeader& other) const;
};

struct StoredUnit {
    long long unit = 0;
    size_t case_index = 0, theta_index = 0, phi_index = 0;
    UnitTraces traces;
};

class UnitFileWriter {
  public:
    // Creates `path` (or, with `append`, opens an existing file of the same run to add units).
    UnitFileWriter(const std::string& path, const UnitFileHeader& header, bool append);
    ~UnitFileWriter();
    UnitFileWriter(const UnitFileWriter&) = delete;
    UnitFileWriter& operator=(const UnitFileWriter&) = delete;
    // Adds a unit and flushes the file, so that it survives a kill.
    void add(const StoredUnit& u);
    void close();

  private:
    std::string path_;
    long long file_ = -1; // hid_t
};

// Throws std::runtime_error naming the file if it is not a unit file.
std::vector<StoredUnit> read_unit_file(const std::string& path, UnitFileHeader* header);

} // namespace gonio
