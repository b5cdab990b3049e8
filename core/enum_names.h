#pragma once
// One name table per enum: what the enum is called in files, configs and on the command line.
// An enum E declares, beside itself,
//     template <> struct EnumNames<E> {
//         static constexpr const char* what = "stop reason";
//         static constexpr const char* names[] = {"rays", "target", ...}; // in enum order
//     };
// and name_of(e), enum_named<E>(text) and enum_names<E>() come from it. Strings are used only at
// the edges (files, configs, the command line); inside gonio the enum is.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace gonio {

template <class E>
struct EnumNames; // specialised beside each enum

template <class E>
constexpr std::size_t enum_count() {
    return sizeof(EnumNames<E>::names) / sizeof(EnumNames<E>::names[0]);
}

template <class E, class = decltype(EnumNames<E>::names)>
const char* name_of(E e) {
    return EnumNames<E>::names[std::size_t(e)];
}

template <class E>
std::vector<std::string> enum_names() {
    return {std::begin(EnumNames<E>::names), std::end(EnumNames<E>::names)};
}

// The enum of a name; throws std::invalid_argument naming what it is and the allowed names.
template <class E>
E enum_named(const std::string& name) {
    for (std::size_t k = 0; k < enum_count<E>(); ++k)
        if (name == EnumNames<E>::names[k]) return E(k);
    std::string allowed;
    for (std::size_t k = 0; k < enum_count<E>(); ++k)
        allowed += (k ? ", " : "") + std::string(EnumNames<E>::names[k]);
    throw std::invalid_argument("unknown " + std::string(EnumNames<E>::what) + " '" + name +
                                "' (allowed: " + allowed + ")");
}

} // namespace gonio
