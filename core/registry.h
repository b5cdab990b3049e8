#pragma once
// Looking a component up by name in its registry (trace backends, export formats, surface
// generators, ...): each is a struct with a `name`, listed once.
#include <stdexcept>
#include <string>
#include <vector>

namespace gonio {

// The entry called `name`; throws std::invalid_argument naming what it is and the allowed names.
template <class T>
const T& find_named(const std::vector<const T*>& all, const std::string& name, const char* what) {
    std::string names;
    for (const T* t : all) {
        if (name == t->name) return *t;
        names += (names.empty() ? "" : ", ") + std::string(t->name);
    }
    throw std::invalid_argument("unknown " + std::string(what) + " '" + name +
                                "' (allowed: " + names + ")");
}

} // namespace gonio
