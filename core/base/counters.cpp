#include "core/base/counters.hpp"

#include <algorithm>
#include <cstdio>

namespace weft {

void Counters::add(std::string_view name, std::int64_t n) {
    CounterMap& local = perThread_.local();
    auto it = local.find(name);
    if (it == local.end()) local.emplace(std::string(name), n);
    else it->second += n;
}

CounterMap Counters::merged() const {
    CounterMap sum;
    for (const CounterMap& local : perThread_)
        for (const auto& [name, n] : local) sum[name] += n;
    return sum;
}

std::int64_t Counters::total(std::string_view name) const {
    std::int64_t sum = 0;
    for (const CounterMap& local : perThread_)
        if (auto it = local.find(name); it != local.end()) sum += it->second;
    return sum;
}

std::string Counters::table(const CounterMap& counters) {
    std::size_t width = 7;
    for (const auto& entry : counters) width = std::max(width, entry.first.size());
    std::string out;
    char line[256];
    for (const auto& [name, n] : counters) {
        std::snprintf(line, sizeof line, "  %-*s %16lld\n", static_cast<int>(width), name.c_str(),
                      static_cast<long long>(n));
        out += line;
    }
    return out;
}

}  // namespace weft
