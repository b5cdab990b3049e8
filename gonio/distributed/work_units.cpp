#include "gonio/distributed/work_units.h"

#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace gonio {

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
    void need(size_t n) {
        if (at + n > in.size()) throw std::runtime_error("a truncated unit message");
    }
    template <class T>
    void get(T& v) {
        need(sizeof(T));
        std::memcpy(&v, in.data() + at, sizeof(T));
        at += sizeof(T);
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
        need(n * sizeof(double));
        v.resize(n);
        if (n > 0) std::memcpy(v.data(), in.data() + at, n * sizeof(double)); // (null when empty)
        at += n * sizeof(double);
    }
};
// Every field of a trace, in one order for both directions.
template <class IO, class Ledger>
void ledger_fields(IO& io, Ledger& l) {
    io(l.reflected), io(l.transmitted), io(l.absorbed), io(l.capped), io(l.lost), io(l.unaccounted);
}
template <class IO, class T>
void trace_fields(IO& io, T& t) {
    io(t.orders), io(t.cells), io(t.channels), io(t.rays), io(t.segments), io(t.energy);
    io(t.transmitted), io(t.seconds), io(t.batches), io(t.energy_stderr), io(t.transmitted_stderr);
    io(t.energy_batches), io(t.transmitted_batches), io(t.stop), io(t.rounds), io(t.achieved_error);
    ledger_fields(io, t.ledger);
    ledger_fields(io, t.ledger_stderr);
    ledger_fields(io, t.ledger_batches);
}
} // namespace

std::vector<char> serialise(const UnitTraces& u) {
    Writer w;
    auto io = [&](const auto& v) { w.put(v); };
    w.put(std::uint64_t(u.members.size()));
    for (const TraceResult& t : u.members) trace_fields(io, t);
    w.put(u.stop);
    w.put(u.passes);
    w.put(u.error);
    w.put(u.surface);
    return std::move(w.out);
}

UnitTraces deserialise(const std::vector<char>& bytes) {
    Reader r{bytes};
    auto io = [&](auto& v) { r.get(v); };
    UnitTraces u;
    std::uint64_t n = 0;
    r.get(n);
    u.members.resize(n);
    for (TraceResult& t : u.members) trace_fields(io, t);
    r.get(u.stop);
    r.get(u.passes);
    r.get(u.error);
    r.get(u.surface);
    return u;
}

} // namespace gonio
