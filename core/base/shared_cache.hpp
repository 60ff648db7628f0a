#pragma once
// A process-wide cache of work derived from inputs known by a key (oracle
// fields, raymarch's empty-space skippers): the most recently used entries,
// each keeping alive whatever its key names by address, so that the
// address is not reused by other inputs while the entry stands.
// Thread-safe; an entry is built outside the lock, so two requests that
// miss at once both build (the same value).
#include <cstddef>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace weft {

template <class Value>
class SharedCache {
public:
    explicit SharedCache(std::size_t capacity) : capacity_(capacity) {}

    struct Found {
        Value value;
        bool reused = false;  // found in the cache, not built by this call
    };

    // The value of `key`, or build() kept with `keepAlive`.
    template <class Build>
    Found get(const std::string& key, const Build& build, std::vector<std::shared_ptr<const void>> keepAlive) {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            for (auto it = entries_.begin(); it != entries_.end(); ++it)
                if (it->key == key) {
                    entries_.splice(entries_.begin(), entries_, it);
                    return {it->value, true};
                }
        }
        Value value = build();
        std::lock_guard<std::mutex> lock(mutex_);
        entries_.push_front({key, value, std::move(keepAlive)});
        while (entries_.size() > capacity_) entries_.pop_back();
        return {std::move(value), false};
    }

    void clear() {
        std::lock_guard<std::mutex> lock(mutex_);
        entries_.clear();
    }

private:
    struct Entry {
        std::string key;
        Value value;
        std::vector<std::shared_ptr<const void>> keepAlive;
    };
    std::size_t capacity_;
    std::mutex mutex_;
    std::list<Entry> entries_;  // most recently used first
};

}  // namespace weft
