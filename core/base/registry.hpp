#pragma once
// A registry of named things (techniques, oracles, pattern generators).
// Entries register themselves at start-up from their own .cpp file through a
// Registrar; lookups of unknown names list the valid ones.
#include <map>
#include <string>
#include <vector>

#include "core/base/error.hpp"

namespace weft {

template <class Entry>
class NamedRegistry {
public:
    explicit NamedRegistry(std::string kind) : kind_(std::move(kind)) {}

    void add(Entry entry) {
        const std::string name = entry.name;
        if (entries_.count(name)) throw Error(kind_ + " '" + name + "' is registered twice");
        entries_.emplace(name, std::move(entry));
    }
    bool has(const std::string& name) const { return entries_.count(name) > 0; }
    const Entry& get(const std::string& name) const {
        auto it = entries_.find(name);
        if (it == entries_.end()) throw Error("unknown " + kind_ + " '" + name + "' (known: " + names() + ")");
        return it->second;
    }
    std::vector<const Entry*> all() const {
        std::vector<const Entry*> out;
        for (const auto& [name, entry] : entries_) out.push_back(&entry);
        return out;
    }
    std::string names() const {
        std::string out;
        for (const auto& [name, entry] : entries_) out += (out.empty() ? "" : ", ") + name;
        return out.empty() ? "none" : out;
    }

private:
    std::string kind_;
    std::map<std::string, Entry> entries_;
};

}  // namespace weft
