#include "gonio/run/unit_file.h"

#include "gonio/io/hdf5_handles.h"
#include "gonio_version.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <utility>

namespace gonio {

namespace {
// 3: every unit record checksummed (HDF5's Fletcher-32 filter, checked on every read).
constexpr const char* kFormat = "gonio-units 5";

void write_int(hid_t o, const char* name, long long v) {
    h5::write_int_attribute(o, name, v);
}
long long read_int(hid_t o, const char* name) {
    h5::Handle a(H5Aopen(o, name, H5P_DEFAULT), H5Aclose, name);
    long long v = 0;
    h5::check(H5Aread(a, H5T_NATIVE_LLONG, &v), name);
    return v;
}
} // namespace

UnitFileHeader run_identity(const Config& cfg, const std::string& command_line) {
    UnitFileHeader h;
    h.version = kVersion;
    h.git_hash = kGitHash;
    h.effective_toml = cfg.effective_toml;
    h.config_path = cfg.path;
    h.config_toml = cfg.text;
    for (const auto& ov : cfg.overrides) h.overrides += ov + "\n";
    h.command_line = command_line;
    h.seed = (long long)cfg.seed;
    h.units_total = UnitLayout(cfg).total();
    return h;
}

std::string UnitFileHeader::differs_from(const UnitFileHeader& o) const {
    if (version != o.version || git_hash != o.git_hash)
        return "gonio " + version + " (git " + git_hash + ") against gonio " + o.version +
               " (git " + o.git_hash + ")";
    if (seed != o.seed)
        return "seed " + std::to_string(seed) + " against " + std::to_string(o.seed);
    if (effective_toml != o.effective_toml) return "another effective config";
    if (units_total != o.units_total) return "another number of work units";
    return "";
}

UnitFileWriter::UnitFileWriter(const std::string& path, const UnitFileHeader& h, bool append)
    : path_(path) {
    h5::silence_errors();
    if (append) {
        file_ = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
        if (file_ < 0) throw std::runtime_error(path + ": cannot reopen the checkpoint");
        return;
    }
    file_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, h5::file_creation_with_checksum(),
                      h5::checksummed_file_access()); // object headers checksummed too
    if (file_ < 0)
        throw std::runtime_error(
            path +
            ": cannot create (an unwritable directory, or another gonio writing the same output)");
    const hid_t f = hid_t(file_);
    h5::write_string_attribute(f, "file_format", kFormat);
    h5::write_string_attribute(f, "gonio_version", h.version);
    h5::write_string_attribute(f, "git_hash", h.git_hash);
    h5::write_string_attribute(f, "config_effective_toml", h.effective_toml);
    h5::write_string_attribute(f, "config_path", h.config_path);
    h5::write_string_attribute(f, "config_toml", h.config_toml);
    h5::write_string_attribute(f, "config_overrides", h.overrides);
    h5::write_string_attribute(f, "command_line", h.command_line);
    h5::write_string_attribute(f, "shard", h.shard);
    write_int(f, "by_batches", h.by_batches);
    write_int(f, "seed", h.seed);
    write_int(f, "units_total", h.units_total);
    h5::seal(f, false); // the run's identity, checksummed
    H5Fflush(f, H5F_SCOPE_GLOBAL);
}

UnitFileWriter::~UnitFileWriter() {
    try {
        close();
    } catch (...) { // a destructor throws nothing: a write that failed was reported by close()
    }
}

void UnitFileWriter::stop_writer() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    changed_.notify_all();
    if (writer_.joinable()) writer_.join();
}

void UnitFileWriter::close() {
    stop_writer();
    if (file_ >= 0 && H5Fclose(hid_t(file_)) < 0)
        h5::discard_file(hid_t(file_)); // (its last flush failed: no id may stay open)
    file_ = -1;
    if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
}

void UnitFileWriter::discard() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        queue_.clear(); // nothing more is written
    }
    stop_writer();
    failure_ = nullptr;
    h5::discard_file(hid_t(file_));
    file_ = -1;
    std::error_code ec;
    std::filesystem::remove(path_, ec);
}

namespace {
// One unit's record, checksummed and flushed (so that it survives a kill).
void write_record(hid_t file, long long number, const UnitId& id, const std::vector<char>& bytes) {
    const std::string name = "unit_" + std::to_string(number);
    const hsize_t n = bytes.size();
    h5::Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose, "dataspace");
    if (H5Lexists(file, name.c_str(), H5P_DEFAULT) > 0)
        H5Ldelete(file, name.c_str(), H5P_DEFAULT); // a unit redone after a kill
    // Deflated in chunks (the maps are mostly zeros beyond the first orders), each
    // chunk with a Fletcher-32 checksum that HDF5 checks on reading: a flipped byte is refused.
    h5::Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "dataset creation property list");
    const hsize_t chunk = std::min<hsize_t>(std::max<hsize_t>(n, 1), hsize_t(1) << 20);
    h5::check(H5Pset_chunk(dcpl, 1, &chunk), "H5Pset_chunk");
    // Bytes shuffled first: the zeros and exponents of the doubles line up, and deflate then
    // takes a fraction of the time (the records were most of a spectral run's time).
    h5::check(H5Pset_shuffle(dcpl), "H5Pset_shuffle");
    h5::check(H5Pset_deflate(dcpl, 1), "H5Pset_deflate");
    h5::check(H5Pset_fletcher32(dcpl), "H5Pset_fletcher32");
    h5::Handle d(
        H5Dcreate2(file, name.c_str(), H5T_NATIVE_UINT8, space, H5P_DEFAULT, dcpl, H5P_DEFAULT),
        H5Dclose, ("create " + name).c_str());
    h5::check(H5Dwrite(d, H5T_NATIVE_UINT8, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()),
              ("write " + name).c_str());
    write_int(d, "unit", number);
    write_int(d, "case_index", (long long)id.case_index);
    write_int(d, "theta_index", (long long)id.theta_index);
    write_int(d, "phi_index", (long long)id.phi_index);
    write_int(d, "complete", 1); // last: a unit cut short by a kill is skipped on reading
    h5::check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush");
}
} // namespace

void UnitFileWriter::add(const NumberedUnit& u) {
    add(u.number, u.id, u.result);
}

void UnitFileWriter::add(long long number, const UnitId& id, const UnitResult& result) {
    Record r{number, id, serialise(result)};
    std::unique_lock<std::mutex> lock(mutex_);
    // One record queued at most: the trace waits for the disk only when it outruns it.
    changed_.wait(lock, [&] { return queue_.empty() || failure_; });
    if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
    queue_.push_back(std::move(r));
    if (!writer_.joinable())
        writer_ = std::thread([this] {
            h5::silence_errors(); // HDF5's error stack is per thread: its errors become ours
            write_queued();
        });
    lock.unlock();
    changed_.notify_all();
}

void UnitFileWriter::write_queued() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
        changed_.wait(lock, [&] { return !queue_.empty() || stopping_; });
        if (queue_.empty()) return; // stopping, and every record written
        Record r = std::move(queue_.front());
        queue_.pop_front();
        lock.unlock();
        changed_.notify_all(); // room for the next record
        std::exception_ptr failed;
        try {
            write_record(hid_t(file_), r.number, r.id, r.bytes);
        } catch (const std::exception& e) {
            failed = std::make_exception_ptr(std::runtime_error(path_ + ": " + e.what()));
        }
        lock.lock();
        if (failed) {
            failure_ = failed;
            queue_.clear();
            changed_.notify_all();
            return;
        }
    }
}

namespace {
// Opens a unit file, saying so when another process holds it (HDF5 locks what it writes).
h5::Handle open_unit_file(const std::string& path, unsigned flags) {
    const hid_t f = H5Fopen(path.c_str(), flags, H5P_DEFAULT);
    if (f >= 0) return h5::Handle(f, H5Fclose, "open");
    const std::string why = h5::reason();
    if (why.find("lock") != std::string::npos || why.find("unavailable") != std::string::npos)
        throw std::runtime_error("in use by another process (a gonio still writing it?)");
    throw std::runtime_error("cannot open (" + why + ")");
}

// One unit's record: a 1-D byte dataset whose checksum holds, and its place.
NumberedUnit read_unit(hid_t f, const std::string& name) {
    h5::Handle d(H5Dopen2(f, name.c_str(), H5P_DEFAULT), H5Dclose, ("open " + name).c_str());
    h5::Handle space(H5Dget_space(d), H5Sclose, "dataspace");
    h5::Handle type(H5Dget_type(d), H5Tclose, "datatype");
    if (H5Sget_simple_extent_ndims(space) != 1 || H5Tget_class(type) != H5T_INTEGER ||
        H5Tget_size(type) != 1)
        throw std::runtime_error(name + ": not a unit record (a 1-D array of bytes)");
    hsize_t n = 0;
    H5Sget_simple_extent_dims(space, &n, nullptr);
    std::vector<char> bytes(n);
    if (n > 0 && H5Dread(d, H5T_NATIVE_UINT8, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()) < 0)
        throw std::runtime_error(name + ": cannot be read (" + h5::reason() +
                                 "): the record is damaged");
    NumberedUnit u;
    u.number = read_int(d, "unit");
    u.id.case_index = size_t(read_int(d, "case_index"));
    u.id.theta_index = size_t(read_int(d, "theta_index"));
    u.id.phi_index = size_t(read_int(d, "phi_index"));
    try {
        u.result = deserialise(bytes);
    } catch (const std::exception& e) {
        throw std::runtime_error(name + ": " + e.what());
    }
    return u;
}

std::vector<NumberedUnit> read_units(const std::string& path, UnitFileHeader* header) {
    const h5::Handle f = open_unit_file(path, H5F_ACC_RDONLY);
    h5::check_seal(f);
    if (H5Aexists(f, "file_format") <= 0 || h5::read_string_attribute(f, "file_format") != kFormat)
        throw std::runtime_error(std::string("not a unit file of this gonio (") + kFormat +
                                 ": a part of `gonio run --shard` or a checkpoint)");
    UnitFileHeader h;
    h.version = h5::read_string_attribute(f, "gonio_version");
    h.git_hash = h5::read_string_attribute(f, "git_hash");
    h.effective_toml = h5::read_string_attribute(f, "config_effective_toml");
    h.config_path = h5::read_string_attribute(f, "config_path");
    h.config_toml = h5::read_string_attribute(f, "config_toml");
    h.overrides = h5::read_string_attribute(f, "config_overrides");
    h.command_line = h5::read_string_attribute(f, "command_line");
    h.shard = h5::read_string_attribute(f, "shard");
    h.by_batches = H5Aexists(f, "by_batches") > 0 && read_int(f, "by_batches") != 0;
    h.seed = read_int(f, "seed");
    h.units_total = read_int(f, "units_total");
    if (header) *header = h;
    std::vector<NumberedUnit> units;
    H5G_info_t info;
    h5::check(H5Gget_info(f, &info), "H5Gget_info");
    for (hsize_t k = 0; k < info.nlinks; ++k) {
        const std::string name = h5::link_name(f, H5_INDEX_NAME, k);
        if (name.rfind("unit_", 0) != 0) continue;
        {
            h5::Handle d(H5Dopen2(f, name.c_str(), H5P_DEFAULT), H5Dclose, name.c_str());
            if (H5Aexists(d, "complete") <= 0) continue; // written when the process was killed
        }
        units.push_back(read_unit(f, name));
    }
    return units;
}
} // namespace

std::vector<NumberedUnit> read_unit_file(const std::string& path, UnitFileHeader* header) {
    h5::silence_errors();
    if (!std::filesystem::exists(path)) throw std::runtime_error(path + ": no such file");
    try {
        h5::check_file_checksum(path); // a part's (a checkpoint grows: it has none)
        if (H5Fis_hdf5(path.c_str()) <= 0) throw std::runtime_error("not an HDF5 file");
        return read_units(path, header);
    } catch (const std::exception& e) {
        throw std::runtime_error(path + ": " + e.what());
    }
}

namespace {
// What is wrong with a trace of case c (every array against the layout), or "".
std::string trace_problem(const TraceResult& t, const CaseConfig& c) {
    const size_t cells = size_t(c.sensor_cells), nc = size_t(c.channels());
    const size_t orders = size_t(c.trace.orders) + 1, map = orders * cells * nc;
    if (t.orders != int(orders) || t.cells != int(cells) || t.channels != int(nc))
        return "a trace of another layout (orders, cells or channels)";
    if (t.batches < 1 || t.batches > 1 << 20) return "a trace with no batches";
    const size_t B = size_t(t.batches);
    const bool transmits = c.material.transmits;
    auto fits = [](const std::vector<double>& v, size_t n) { return v.size() == n; };
    // Per-order batches travel only with a batch shard's units.
    const bool per_order = !t.energy_batches.empty();
    bool ok = fits(t.energy, map) && fits(t.energy_stderr, map) &&
              fits(t.energy_batches, per_order ? B * map : 0) &&
              fits(t.transmitted, transmits ? map : 0) &&
              fits(t.transmitted_stderr, transmits ? map : 0) &&
              fits(t.transmitted_batches, per_order && transmits ? B * map : 0);
    // The order sums per batch, or (a completed unit's) their errors alone.
    const bool sums = !t.energy_sums.empty();
    for (const OrderSums* s :
         {&t.energy_sums, &t.transmitted_sums, &t.sums_stderr, &t.transmitted_sums_stderr}) {
        const bool lower = s == &t.transmitted_sums || s == &t.transmitted_sums_stderr;
        const bool batches = s == &t.energy_sums || s == &t.transmitted_sums;
        const size_t n = (lower && !transmits) || batches != sums ? 0
                         : batches                                ? B * cells * nc
                                                                  : cells * nc;
        ok = ok && fits(s->l1, n) && fits(s->l2plus, n) && fits(s->linf, n);
    }
    for (const EnergyLedger* l : {&t.ledger, &t.ledger_stderr, &t.ledger_batches}) {
        const size_t b = l == &t.ledger_batches ? B : 1;
        ok = ok && fits(l->reflected, b * orders * nc) &&
             fits(l->transmitted, transmits ? b * orders * nc : 0) && fits(l->absorbed, b * nc) &&
             fits(l->capped, b * nc) && fits(l->lost, b * nc) && fits(l->unaccounted, b * nc);
    }
    return ok ? "" : "a trace whose arrays do not fit its layout";
}

// What is wrong with a model's record at one incidence, or "".
std::string model_problem(const ModelIncidence& m, size_t cells, size_t nc) {
    if (m.energy.size() != cells * nc) return "a model whose arrays do not fit the case";
    if (m.batches < 0 || m.batches > 1 << 20) return "a model with a bad batch count";
    if (m.has_orders() && m.l1_energy.size() != cells * nc)
        return "a model whose single scattering does not fit the case";
    if (!m.monte_carlo()) return "";
    const size_t orders = ModelIncidence::kOrderBins * nc;
    const bool transmits = !m.order_transmittance.empty();
    const bool ok = m.energy_batches.size() == size_t(m.batches) * cells * nc &&
                    m.l1_energy.size() == cells * nc && m.albedo_stderr.size() == nc &&
                    m.l1_albedo.size() == nc && m.l2_albedo.size() == nc &&
                    m.l2plus_albedo.size() == nc &&
                    m.l1_energy_batches.size() == m.energy_batches.size() &&
                    m.order_albedo.size() == orders && m.order_albedo_stderr.size() == orders &&
                    (!transmits || m.order_transmittance.size() == orders) &&
                    m.order_transmittance_stderr.size() == m.order_transmittance.size();
    return ok ? "" : "a Monte Carlo model whose arrays do not fit the case";
}

// What is wrong with a unit of case c, or "".
// What is wrong with a comparison's arrays, or "".
std::string comparison_problem(const Comparison& x, size_t cells, size_t nc, bool l2plus_allowed) {
    bool ok = true;
    for (const std::vector<double>* v :
         {&x.model_albedo, &x.relative_difference, &x.relative_difference_stderr, &x.sigmas,
          &x.distance, &x.distance_stderr})
        ok = ok && v->size() == nc;
    ok = ok && x.ratio.size() == cells * nc && x.ratio_stderr.size() == cells * nc;
    ok = ok && (x.l2plus.empty() || (l2plus_allowed && x.l2plus.size() == 1));
    if (ok && !x.l2plus.empty()) return comparison_problem(x.l2plus[0], cells, nc, false);
    return ok ? "" : "a comparison whose arrays do not fit the case";
}

std::string unit_problem(const UnitResult& u, const CaseConfig& c, bool batch_shard) {
    const size_t surfaces = u.members.size(), cells = size_t(c.sensor_cells),
                 nc = size_t(c.channels());
    if (u.completed ? surfaces != 1 : (c.surface.realisations == 1 ? surfaces != 1 : surfaces < 2))
        return std::to_string(surfaces) + " traces for " + std::to_string(c.surface.realisations) +
               " surface(s)";
    if (u.completed != !batch_shard) return "a unit completed where it should not be, or not";
    if (u.surfaces < 1 || (c.surface.realisations == 1 && u.surfaces != 1))
        return "a unit of " + std::to_string(u.surfaces) + " surfaces";
    if (u.completed) {
        if (u.comparisons.size() != u.models.size())
            return std::to_string(u.comparisons.size()) + " comparisons for " +
                   std::to_string(u.models.size()) + " models";
        for (const Comparison& x : u.comparisons)
            if (const std::string why = comparison_problem(x, cells, nc, true); !why.empty())
                return why;
        const SurfaceShares& sh = u.shares;
        const size_t n = c.surface.realisations > 1 ? nc : 0;
        for (const std::vector<double>* v :
             {&sh.l1_albedo, &sh.l2plus_albedo, &sh.linf_albedo, &sh.l1_cells, &sh.linf_cells})
            if (v->size() != n) return "a unit whose surface shares do not fit the case";
        if (!u.members[0].energy_batches.empty()) return "a completed unit with its batches";
    } else if (!u.comparisons.empty()) {
        return "comparisons in a unit still to be completed";
    }
    if (size_t(u.stop) >= enum_count<StopReason>()) return "an unknown stop reason";
    for (const TraceResult& t : u.members)
        if (const std::string why = trace_problem(t, c); !why.empty()) return why;
    if (u.models.size() != c.model.models.size() && !(batch_shard && u.models.empty()))
        return std::to_string(u.models.size()) + " models for the case's " +
               std::to_string(c.model.models.size());
    for (size_t k = 0; k < u.models.size(); ++k) {
        if (const std::string why =
                model_problem(u.models[k], size_t(c.sensor_cells), size_t(c.channels()));
            !why.empty())
            return why;
        if (u.models[k].monte_carlo() != c.model.models[k].monte_carlo)
            return "model " + c.model.models[k].name + " of another kind";
    }
    return "";
}
} // namespace

void check_unit(const NumberedUnit& u, const Config& cfg, const std::string& file,
                bool batch_shard) {
    const std::string which = file + ": unit " + std::to_string(u.number);
    const UnitId& id = u.id;
    if (id.case_index >= cfg.cases.size() ||
        id.theta_index >= cfg.cases[id.case_index].theta_i_deg.size() ||
        id.phi_index >= cfg.cases[id.case_index].phi_i_deg.size() ||
        UnitLayout(cfg).number(id) != u.number)
        throw std::runtime_error(which + ": no such incidence in the run's config");
    if (const std::string why = unit_problem(u.result, cfg.cases[id.case_index], batch_shard);
        !why.empty())
        throw std::runtime_error(which + ": " + why);
}

void check_units(const std::vector<NumberedUnit>& units, const Config& cfg, const std::string& file,
                 bool batch_shard) {
    for (const NumberedUnit& u : units) check_unit(u, cfg, file, batch_shard);
}

} // namespace gonio
