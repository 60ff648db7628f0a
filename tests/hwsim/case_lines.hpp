#pragma once
// The CASE lines weft_mesa_check prints, and their parser (the cross-check
// tests, recorded runs of real GPUs in tests/hwsim/recorded/):
//   CASE name samples=N invocations=N written=N hash=N [fs_invocations=N clip_in=N clip_out=N]
// The bracketed pipeline statistics (ARB_pipeline_statistics_query) came
// later: a line without them still parses, their fields then read -1 as
// they do where the driver lacks the extension. Header-only, standard C++.
#include <cstdio>
#include <map>
#include <sstream>
#include <string>

#include "tests/hwsim/crosscheck_cases.hpp"

namespace weft::crosscheck {

inline std::string caseLine(const std::string& name, const Counts& c) {
    char line[320];
    std::snprintf(line, sizeof line, "CASE %s samples=%lld invocations=%lld written=%lld hash=%llu fs_invocations=%lld clip_in=%lld clip_out=%lld",
                  name.c_str(), c.samplesPassed, c.invocations, c.written, (unsigned long long)c.writtenHash, c.fsInvocations, c.clipIn,
                  c.clipOut);
    return line;
}

// Every CASE line of a run's output, by case name; other lines are skipped.
inline std::map<std::string, Counts> parseCaseLines(const std::string& output) {
    std::map<std::string, Counts> out;
    std::istringstream in(output);
    std::string line;
    while (std::getline(in, line)) {
        char name[64];
        Counts c;
        unsigned long long hash = 0;
        const int n = std::sscanf(line.c_str(), "CASE %63s samples=%lld invocations=%lld written=%lld hash=%llu fs_invocations=%lld clip_in=%lld clip_out=%lld",
                                  name, &c.samplesPassed, &c.invocations, &c.written, &hash, &c.fsInvocations, &c.clipIn, &c.clipOut);
        if (n != 5 && n != 8) continue;
        if (n == 5) c.fsInvocations = c.clipIn = c.clipOut = -1;
        c.writtenHash = hash;
        out[name] = c;
    }
    return out;
}

}  // namespace weft::crosscheck
