#pragma once
// Counters: named 64-bit event counts (fragments, volume samples, rays...).
// Each counter is declared once, at namespace scope in the file that counts
// it, as a Counter (name and meaning); declaring it registers it, so `weft
// help counters` lists them all, and Counters::add takes the handle, so a
// misspelt name does not compile. A family counted per index (one per
// pyramid level) is an IndexedCounter: "volume.samples.level" + N.
//
// Each thread adds to its own map; merge() sums them, so totals do not depend
// on how work was scheduled. Hot loops count in locals and add once per tile.
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

namespace weft {

using CounterMap = std::map<std::string, std::int64_t, std::less<>>;

class Counter {
public:
    Counter(const char* name, const char* doc);
    Counter(const Counter&) = delete;
    Counter& operator=(const Counter&) = delete;
    std::string_view name() const { return name_; }
    std::string_view doc() const { return doc_; }

private:
    const char* name_;
    const char* doc_;
};

// Names prefix + index ("volume.samples.level3"); listed as "prefix<N>".
class IndexedCounter {
public:
    IndexedCounter(const char* prefix, const char* doc);
    IndexedCounter(const IndexedCounter&) = delete;
    IndexedCounter& operator=(const IndexedCounter&) = delete;
    std::string name(int index) const { return prefix_ + std::to_string(index); }
    std::string_view prefix() const { return prefix_; }
    std::string_view doc() const { return doc_; }

private:
    const char* prefix_;
    const char* doc_;
};

// Every declared counter, sorted by name: (name, meaning); an indexed one as "prefix<N>".
std::vector<std::pair<std::string, std::string>> declaredCounters();
// The list as a Markdown table (docs/usage.md, `weft help counters --markdown`).
std::string declaredCountersMarkdown();

// Counted by several techniques: declared once here.
extern const Counter kRaysCamera, kRaysShadow, kRaysSurface, kVolumeSamples, kVolumeLookups, kSlices, kCompositeOps;

class Counters {
public:
    void add(const Counter& counter, std::int64_t n) { addNamed(counter.name(), n); }
    void add(const IndexedCounter& counter, int index, std::int64_t n) { addNamed(counter.name(index), n); }
    // Sum over all threads, by name (sorted).
    CounterMap merged() const;
    std::int64_t total(std::string_view name) const;
    // A two-column table, one counter a line.
    static std::string table(const CounterMap& counters);

private:
    void addNamed(std::string_view name, std::int64_t n);
    tbb::enumerable_thread_specific<CounterMap> perThread_;
};

}  // namespace weft
