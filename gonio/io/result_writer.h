#pragma once
// The HDF5 result file (layout in the README, "Result file"). One file per run, one group per
// case; coordinates are HDF5 dimension scales with units; the config, program version, git hash,
// seed and command line are stored in the root attributes. The file is written under a temporary
// name and renamed when complete, so a failed run leaves nothing half-written.
#include "gonio/config/config.h"
#include "gonio/io/hdf5_handles.h"
#include "gonio/io/simulation_result.h"
#include "gonio/model/case_models.h"
#include "sensor/beckers_sensor.h"

#include <string>
#include <vector>

namespace gonio {

class ResultWriter {
  public:
    // Throws std::runtime_error if `path` exists and !overwrite.
    ResultWriter(std::string path, bool overwrite);
    ~ResultWriter(); // removes the temporary file unless commit() succeeded
    ResultWriter(const ResultWriter&) = delete;
    ResultWriter& operator=(const ResultWriter&) = delete;

    void write_run(const Config& cfg, const std::string& command_line);
    // `ndf_description` describes the case's distribution (its Ndf::describe()).
    void write_model_case(const CaseConfig& c, const std::string& ndf_description,
                          const BeckersSensor& sensor, const std::vector<ModelResult>& models);
    // The simulated BRDF per order, L1 / L2+ / L-infinity (and the BTDF of a transmissive
    // material on the lower sensor), the ledger, and the models on the same cells, each with
    // its comparison against the simulated quantity it models (albedos, relative difference,
    // per-cell relative L1 distance, ratio map); every simulated figure with its standard error
    // beside it (name_stderr).
    void write_simulation_case(const CaseConfig& c, const std::string& ndf_description,
                               const BeckersSensor& sensor, const SimulationResult& sim,
                               const std::vector<ModelResult>& models);
    // Wall time per phase, as attributes phase_<name>_seconds and the list `phases`: of a case
    // (its group), or of the whole run (case_name empty: the root).
    void write_timings(const std::string& case_name,
                       const std::vector<std::pair<std::string, double>>& phases);
    // Closes the file and renames it to its final path.
    void commit();

    static std::string conventions();

  private:
    struct CaseGroup;
    CaseGroup open_case(const CaseConfig& c, const std::string& ndf_description,
                        const BeckersSensor& sensor);
    void write_models(CaseGroup& g, const BeckersSensor& sensor,
                      const std::vector<ModelResult>& models);

    std::string path_, tmp_path_;
    h5::Handle file_;
    bool committed_ = false;
};

} // namespace gonio
