#include "gonio/run/unit.h"

#include "core/check.h"

#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace gonio {

UnitLayout::UnitLayout(const Config& cfg) {
    long long u = 0;
    for (const CaseConfig& c : cfg.cases) {
        first_.push_back(u);
        phi_count_.push_back(c.phi_i_deg.size());
        u += (long long)(c.theta_i_deg.size() * c.phi_i_deg.size());
    }
    first_.push_back(u);
}

long long UnitLayout::number(const UnitId& u) const {
    GONIO_DCHECK(u.case_index < cases() && u.phi_index < phi_count_[u.case_index]);
    return first_[u.case_index] +
           (long long)(u.theta_index * phi_count_[u.case_index] + u.phi_index);
}

UnitId UnitLayout::unit(long long number) const {
    GONIO_CHECK(number >= 0 && number < total());
    size_t c = 0;
    while (number >= first_[c + 1]) ++c;
    const size_t within = size_t(number - first_[c]);
    return {c, within / phi_count_[c], within % phi_count_[c]};
}

Shard parse_shard(const std::string& text) {
    Shard s;
    char slash = 0, rest = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &s.index, &slash, &s.count, &rest) != 3 ||
        slash != '/' || s.count < 1 || s.index < 0 || s.index >= s.count)
        throw std::invalid_argument("--shard " + text + ": expected i/N with 0 <= i < N");
    return s;
}

Shard shard_from_environment() {
    const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
    const char* count = std::getenv("SLURM_ARRAY_TASK_COUNT");
    if (!id || !count) return {};
    const char* min = std::getenv("SLURM_ARRAY_TASK_MIN");
    const int offset = min ? std::atoi(min) : 0;
    return parse_shard(std::to_string(std::atoi(id) - offset) + "/" + count);
}

namespace {
struct Writer {
    std::vector<char> out;
    template <class T>
    void put(const T& v) {
        const char* p = reinterpret_cast<const char*>(&v);
        out.insert(out.end(), p, p + sizeof(T));
    }
    void put(const std::string& s) {
        put(std::uint64_t(s.size()));
        out.insert(out.end(), s.begin(), s.end());
    }
    void put(const std::vector<double>& v) {
        put(std::uint64_t(v.size()));
        if (v.empty()) return; // its data() may be null
        const char* p = reinterpret_cast<const char*>(v.data());
        out.insert(out.end(), p, p + v.size() * sizeof(double));
    }
};
struct Reader {
    const std::vector<char>& in;
    size_t at = 0;
    void need(std::uint64_t n) {
        if (n > in.size() - at) throw std::runtime_error("a truncated unit message");
    }
    template <class T>
    void get(T& v) {
        need(sizeof(T));
        std::memcpy(&v, in.data() + at, sizeof(T));
        at += sizeof(T);
    }
    void get(bool& v) { // a byte that is 0 or 1: any other is a corrupt record, not a bool
        std::uint8_t b = 0;
        get(b);
        if (b > 1) throw std::runtime_error("a unit message with a corrupt flag");
        v = b == 1;
    }
    void get(std::string& s) {
        std::uint64_t n = 0;
        get(n);
        need(n);
        s.assign(in.data() + at, n);
        at += n;
    }
    void get(std::vector<double>& v) {
        std::uint64_t n = 0;
        get(n);
        need(n / sizeof(double) > in.size() ? in.size() + 1 : n * sizeof(double));
        v.resize(n);
        if (n > 0) std::memcpy(v.data(), in.data() + at, n * sizeof(double)); // (null when empty)
        at += n * sizeof(double);
    }
};
// Every field of a trace and of a model's record, in one order for both directions.
template <class IO, class Ledger>
void ledger_fields(IO& io, Ledger& l) {
    io(l.reflected), io(l.transmitted), io(l.absorbed), io(l.capped), io(l.lost), io(l.unaccounted);
}
template <class IO, class T>
void trace_fields(IO& io, T& t) {
    io(t.orders), io(t.cells), io(t.channels), io(t.rays), io(t.segments), io(t.energy);
    io(t.transmitted), io(t.seconds), io(t.batches), io(t.energy_stderr), io(t.transmitted_stderr);
    io(t.energy_batches), io(t.transmitted_batches), io(t.stop), io(t.rounds), io(t.achieved_error);
    for (auto* sums :
         {&t.energy_sums, &t.transmitted_sums, &t.sums_stderr, &t.transmitted_sums_stderr})
        io(sums->l1), io(sums->l2plus), io(sums->linf);
    ledger_fields(io, t.ledger);
    ledger_fields(io, t.ledger_stderr);
    ledger_fields(io, t.ledger_batches);
}
template <class IO, class M>
void model_fields(IO& io, M& m) {
    io(m.energy), io(m.seconds), io(m.relative_tolerance), io(m.batches), io(m.energy_batches);
    io(m.albedo_stderr), io(m.l1_energy), io(m.l1_albedo), io(m.l2_albedo), io(m.l2plus_albedo);
    io(m.l1_energy_batches), io(m.order_albedo), io(m.order_albedo_stderr);
    io(m.order_transmittance), io(m.order_transmittance_stderr);
}
template <class IO, class C>
void comparison_fields(IO& io, C& c) {
    io(c.model_albedo), io(c.relative_difference), io(c.relative_difference_stderr), io(c.sigmas);
    io(c.distance), io(c.distance_stderr), io(c.ratio), io(c.ratio_stderr);
}
// The fewest bytes one trace and one model's record take (their counts and sizes alone), so that
// a corrupt count is refused before anything is allocated for it.
constexpr std::uint64_t kMinTraceBytes = 41 * 8, kMinModelBytes = 12 * 8,
                        kMinComparisonBytes = 9 * 8;
template <class IO, class U, class Count>
void unit_fields(IO& io, U& u, Count& count) {
    count(u.members, kMinTraceBytes);
    for (auto& t : u.members) trace_fields(io, t);
    io(u.stop), io(u.passes), io(u.error), io(u.surface);
    count(u.models, kMinModelBytes);
    for (auto& m : u.models) model_fields(io, m);
    io(u.completed), io(u.surfaces);
    io(u.shares.l1_albedo), io(u.shares.l2plus_albedo), io(u.shares.linf_albedo);
    io(u.shares.l1_cells), io(u.shares.linf_cells);
    count(u.comparisons, kMinComparisonBytes);
    for (auto& c : u.comparisons) {
        comparison_fields(io, c);
        count(c.l2plus, kMinComparisonBytes);
        for (auto& l : c.l2plus) comparison_fields(io, l);
    }
}
} // namespace

namespace {
// The bytes serialise() writes, counted first: one allocation of the record instead of a
// vector doubling (and copying) its way to hundreds of megabytes.
struct Sizer {
    std::uint64_t bytes = 0;
    template <class T>
    void put(const T&) {
        bytes += sizeof(T);
    }
    void put(const std::string& s) { bytes += sizeof(std::uint64_t) + s.size(); }
    void put(const std::vector<double>& v) {
        bytes += sizeof(std::uint64_t) + v.size() * sizeof(double);
    }
};
} // namespace

std::vector<char> serialise(const UnitResult& u) {
    Sizer size;
    auto measure = [&](const auto& v) { size.put(v); };
    auto measure_count = [&](const auto& v, std::uint64_t) { size.put(std::uint64_t(v.size())); };
    unit_fields(measure, u, measure_count);
    Writer w;
    w.out.reserve(size.bytes);
    auto io = [&](const auto& v) { w.put(v); };
    auto count = [&](const auto& v, std::uint64_t) { w.put(std::uint64_t(v.size())); };
    unit_fields(io, u, count);
    return std::move(w.out);
}

UnitResult deserialise(const std::vector<char>& bytes) {
    Reader r{bytes};
    auto io = [&](auto& v) { r.get(v); };
    auto count = [&](auto& v, std::uint64_t least) {
        std::uint64_t n = 0;
        r.get(n);
        r.need(n > (bytes.size() - r.at) / least ? bytes.size() + 1 : n * least);
        v.resize(n);
    };
    UnitResult u;
    unit_fields(io, u, count);
    if (r.at != bytes.size()) throw std::runtime_error("a unit message with trailing bytes");
    auto known = [](StopReason s) { return size_t(s) < enum_count<StopReason>(); };
    bool valid = known(u.stop);
    for (const TraceResult& t : u.members) valid = valid && known(t.stop);
    if (!valid) throw std::runtime_error("a unit message with an unknown stop reason");
    return u;
}

} // namespace gonio
