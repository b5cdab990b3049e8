#pragma once
// The HDF5 result file, format "gonio-result 2" (layout in docs/result-file.md). One file
// per run, one group per case; one dimension scale per axis (theta_i, phi_i, order, cell,
// channel), the cell geometry and wavelengths as variables along cell and channel named in each
// data variable's `coordinates` attribute (netCDF style: xarray opens a case as it is); the
// config, program version, git hash, seed and command line are stored in the root attributes.
// The writer only serialises: every figure comes computed, as named arrays. The file is written
// under a temporary name and renamed when complete, so a failed run leaves nothing half-written.
// Its methods' errors do not name the file: the caller does (write_result).
#include "gonio/config/config.h"
#include "gonio/io/hdf5_handles.h"
#include "gonio/io/model_result.h"
#include "gonio/io/sealed_file.h"
#include "gonio/io/simulation_result.h"
#include "sensor/beckers_sensor.h"

#include <string>
#include <utility>
#include <vector>

namespace gonio {

// The run's provenance, the root attributes every file gonio writes from a config carries:
// file_format, gonio_version, git_hash, command_line, seed, config_path, config_effective_toml.
void write_provenance(hid_t file, const std::string& format, const Config& cfg,
                      const std::string& command_line);

class ResultWriter {
  public:
    // Throws std::runtime_error if `path` exists and !overwrite.
    ResultWriter(std::string path, bool overwrite);
    ~ResultWriter() = default; // the temporary file is removed unless commit() succeeded
    ResultWriter(const ResultWriter&) = delete;
    ResultWriter& operator=(const ResultWriter&) = delete;

    void write_run(const Config& cfg, const std::string& command_line);
    // How the run was executed (root string attributes mpi_ranks, threads_per_rank and, for a
    // merge, merged_parts): provenance, not data.
    void write_execution(int ranks, int threads_per_rank, int merged_parts = 0);
    // The memory estimated before the run and this process's peak, in bytes.
    void write_memory(double estimate_bytes, double peak_bytes);
    void write_model_case(const CaseConfig& c, const BeckersSensor& sensor,
                          const std::string& ndf_description,
                          const std::vector<ModelResult>& models);
    // The simulated BRDF per order, L1 / L2+ / L-infinity (and the BTDF of a transmissive
    // material on the lower sensor), the ledger, and the models on the same cells, each with
    // its comparison against the simulated quantity it models (albedos, relative difference,
    // per-cell relative L1 distance, ratio map); every simulated figure with its standard error
    // beside it (name_stderr).
    void write_simulation_case(const CaseConfig& c, const BeckersSensor& sensor,
                               const std::string& ndf_description, const SimulationResult& sim,
                               const std::vector<ModelResult>& models);
    // Wall time per phase, in order: attributes phase_<name>_seconds and the list `phases` on the
    // case's group (written before), or on the root with an empty case name.
    void write_timings(const std::string& case_name_or_empty,
                       const std::vector<std::pair<std::string, double>>& phase_seconds);
    // Closes the file and renames it to its final path.
    void commit();
    const std::string& path() const { return file_.path(); }

    static std::string conventions();

  private:
    struct CaseGroup;
    CaseGroup open_case(const CaseConfig& c, const BeckersSensor& sensor,
                        const std::string& ndf_description);
    // `tolerance`: the configured quadrature tolerance; a model that reached less is marked.
    void write_models(CaseGroup& g, const std::vector<ModelResult>& models, double tolerance);

    SealedFile file_;
};

} // namespace gonio
