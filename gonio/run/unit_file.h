#pragma once
// A file of finished work units: a shard's part (`gonio run --shard i/N`, put together by
// `gonio merge`) or a running job's checkpoint (`gonio run --resume`). HDF5, format
// "gonio-units 5": the run's identity in root attributes (gonio version and git hash, seed,
// effective config, shard), one opaque dataset per unit holding its result exactly (unit.h:
// traces and models), with its number, case and incidence as attributes.
#include "gonio/config/config.h"
#include "gonio/run/unit.h"

#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
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

// The identity of a run of `cfg` (every unit of the config; shard "0/1").
UnitFileHeader run_identity(const Config& cfg, const std::string& command_line);

// Records are written by a thread of the writer's own, so that a finished unit is written while
// the next one traces: add() serialises the unit (the caller may then free it) and queues its
// bytes, waiting only while another record is still queued. Each record is flushed when written,
// so a kill -9 loses at most the units in flight; a write's failure is thrown by the next add()
// or by close().
class UnitFileWriter {
  public:
    // Creates `path` (or, with `append`, opens an existing file of the same run to add units).
    UnitFileWriter(const std::string& path, const UnitFileHeader& header, bool append);
    ~UnitFileWriter();
    UnitFileWriter(const UnitFileWriter&) = delete;
    UnitFileWriter& operator=(const UnitFileWriter&) = delete;
    // Queues a unit for writing (and flushing, so that it survives a kill).
    void add(const NumberedUnit& u);
    // The same without a copy of the result.
    void add(long long number, const UnitId& id, const UnitResult& result);
    // Writes what is queued and closes the file; throws if a write failed.
    void close();
    // Closes and removes the file (a run that failed leaves no unit file behind).
    void discard();

  private:
    struct Record {
        long long number = 0;
        UnitId id;
        std::vector<char> bytes;
    };
    void write_queued(); // the writer thread
    void stop_writer();  // waits for the queue to empty and the thread to end
    std::string path_;
    long long file_ = -1; // hid_t
    std::thread writer_;
    std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<Record> queue_;
    bool stopping_ = false;
    std::exception_ptr failure_;
};

// Throws std::runtime_error naming the file if it is not a unit file.
std::vector<NumberedUnit> read_unit_file(const std::string& path, UnitFileHeader* header);

// Checks that every unit read from `file` belongs to a run of `cfg`: its place and number, its
// traces' layout (orders, cells, channels, batches, one per surface) and its models'. Throws
// std::runtime_error naming the file and the unit. `batch_shard`: a shard of a single-incidence
// job's batches (its models may be absent).
void check_units(const std::vector<NumberedUnit>& units, const Config& cfg, const std::string& file,
                 bool batch_shard = false);
void check_unit(const NumberedUnit& unit, const Config& cfg, const std::string& file,
                bool batch_shard = false);

} // namespace gonio
