#pragma once
// Counters: named 64-bit event counts (fragments, volume samples, rays...).
// Each thread adds to its own map; merge() sums them, so totals do not depend
// on how work was scheduled. Hot loops count in locals and add once per tile.
#include <cstdint>
#include <map>
#include <string>
#include <string_view>

#include <tbb/enumerable_thread_specific.h>

namespace weft {

using CounterMap = std::map<std::string, std::int64_t, std::less<>>;

class Counters {
public:
    void add(std::string_view name, std::int64_t n);
    // Sum over all threads, by name (sorted).
    CounterMap merged() const;
    std::int64_t total(std::string_view name) const;
    // A two-column table, one counter a line.
    static std::string table(const CounterMap& counters);

private:
    tbb::enumerable_thread_specific<CounterMap> perThread_;
};

}  // namespace weft
