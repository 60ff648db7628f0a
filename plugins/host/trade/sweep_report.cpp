#include "plugins/host/trade/sweep_report.hpp"

#include <algorithm>
#include <limits>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/base/files/atomic_file.hpp"
#include "core/base/error.hpp"
#include "core/base/pareto.hpp"

namespace weft {

namespace {

std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", v);
    return text;
}

// A CSV field: quoted when it holds a comma, quote or line break.
std::string csvField(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

template <class Get>
std::set<std::string> unionOf(const std::vector<SweepResult>& results, Get get) {
    std::set<std::string> keys;
    for (const SweepResult& r : results) get(r, keys);
    return keys;
}

std::string varied(const SweepResult& r, const std::string& key) {
    for (const auto& [k, v] : r.run.varied)
        if (k == key) return v;
    return "";
}

std::string errorCells(const TradeError& e) {
    return number(e.rmse) + "," + number(e.relMse) + "," + number(e.psnr) + "," + number(e.ssim) + "," + number(e.maxAbs) + "," +
           number(e.flip);
}

nlohmann::ordered_json resultJson(const SweepResult& r, bool byTime, bool bySamples) {
    nlohmann::ordered_json j{{"run", r.run.index + 1}, {"technique", r.run.technique}, {"label", runLabel(r.run)}};
    for (const auto& [k, v] : r.run.varied) j["varied"][k] = v;
    if (!r.refused.empty()) return j["refused"] = r.refused, j;
    j["params"] = r.params;
    j["time_ms"] = {{"median", r.times.medianMs}, {"min", r.times.minMs}, {"max", r.times.maxMs}, {"repeats", r.repeatMs}};
    j["samples"] = r.samples;
    j["error"] = tradeErrorJson(r.error);
    j["front"] = {{"time", byTime}, {"samples", bySamples}};
    j["counters"] = nlohmann::ordered_json::object();
    for (const auto& [k, v] : r.counters) j["counters"][k] = v;
    return j;
}

SweepResult resultFromJson(const nlohmann::ordered_json& j) {
    SweepResult r;
    r.run.index = j.at("run").get<int>() - 1;
    r.run.technique = j.at("technique").get<std::string>();
    if (j.contains("varied"))
        for (const auto& [k, v] : j.at("varied").items()) r.run.varied.emplace_back(k, v.get<std::string>());
    if (j.contains("refused")) return r.refused = j.at("refused").get<std::string>(), r;
    r.params = j.at("params").get<std::string>();
    const auto& t = j.at("time_ms");
    r.times = {t.at("median").get<double>(), t.at("min").get<double>(), t.at("max").get<double>()};
    r.repeatMs = t.at("repeats").get<std::vector<double>>();
    r.samples = j.at("samples").get<std::int64_t>();
    const auto& e = j.at("error");
    const auto value = [&](const char* k) { return e.at(k).is_null() ? std::numeric_limits<double>::infinity() : e.at(k).get<double>(); };
    r.error = {value("rmse"), value("relmse"), value("psnr"), value("ssim"), value("maxabs"), value("flip")};
    for (const auto& [k, v] : j.at("counters").items()) r.counters[k] = v.get<std::int64_t>();
    return r;
}

}  // namespace

nlohmann::ordered_json tradeErrorJson(const TradeError& e) {
    return {{"rmse", e.rmse}, {"relmse", e.relMse}, {"psnr", e.psnr}, {"ssim", e.ssim}, {"maxabs", e.maxAbs}, {"flip", e.flip}};
}

void writeSweepRunJson(const std::string& path, const SweepRunFile& f) {
    nlohmann::ordered_json j{{"scene", f.info.scene},   {"reference", f.info.reference}, {"metric", tradeMetricName(f.info.metric)},
                             {"repeat", f.info.repeat}, {"of", f.runCount},            {"result", resultJson(f.result, false, false)}};
    writeTextAtomically(path, j.dump(2) + "\n", "sweep");
}

SweepRunFile readSweepRunJson(const std::string& path) {
    std::ifstream in(path);
    try {
        const nlohmann::ordered_json j = nlohmann::ordered_json::parse(in);
        SweepRunFile f{resultFromJson(j.at("result")), j.at("of").get<int>(), {}};
        f.info = {j.at("scene").get<std::string>(), j.at("reference").get<std::string>(),
                  parseTradeMetric(j.at("metric").get<std::string>()), j.at("repeat").get<int>()};
        return f;
    } catch (const nlohmann::json::exception&) {
        throw Error("'" + path + "': not a run of weft sweep --run (unreadable or a field is missing)");
    }
}

SweepFronts sweepFronts(const std::vector<SweepResult>& results, TradeMetric metric) {
    std::vector<std::pair<double, double>> time, samples;
    const double inf = std::numeric_limits<double>::infinity();
    for (const SweepResult& r : results) {  // a refused run costs everything: never on a front
        const bool shown = r.refused.empty();
        time.emplace_back(shown ? r.times.medianMs : inf, shown ? metricAsError(r.error, metric) : inf);
        samples.emplace_back(shown ? double(r.samples) : inf, shown ? metricAsError(r.error, metric) : inf);
    }
    SweepFronts f{std::vector<bool>(results.size()), std::vector<bool>(results.size())};
    for (std::size_t i : paretoFront(time)) f.byTime[i] = true;
    for (std::size_t i : paretoFront(samples)) f.bySamples[i] = true;
    return f;
}

void writeSweepCsv(const std::string& path, const std::vector<SweepResult>& results, const SweepFronts& fronts) {
    const auto keys = unionOf(results, [](const SweepResult& r, std::set<std::string>& s) {
        for (const auto& kv : r.run.varied) s.insert(kv.first);
    });
    const auto counters = unionOf(results, [](const SweepResult& r, std::set<std::string>& s) {
        for (const auto& kv : r.counters) s.insert(kv.first);
    });
    std::ostringstream os;
    os << "run,technique";
    for (const std::string& k : keys) os << "," << csvField(k);
    os << ",params,median_ms,min_ms,max_ms,samples,rmse,relmse,psnr,ssim,maxabs,flip,front_time,front_samples,refused";
    for (const std::string& c : counters) os << ",counters." << c;
    os << "\n";
    for (std::size_t i = 0; i < results.size(); ++i) {
        const SweepResult& r = results[i];
        os << r.run.index + 1 << "," << r.run.technique;
        for (const std::string& k : keys) os << "," << csvField(varied(r, k));
        if (!r.refused.empty()) {  // params, times, samples and the six errors empty; off both fronts; no counters
            os << std::string(11, ',') << ",0,0," << csvField(r.refused) << std::string(counters.size(), ',') << "\n";
            continue;
        }
        os << "," << csvField(r.params) << "," << number(r.times.medianMs) << "," << number(r.times.minMs) << ","
           << number(r.times.maxMs) << "," << r.samples << "," << errorCells(r.error) << "," << int(fronts.byTime[i]) << ","
           << int(fronts.bySamples[i]) << ",";
        for (const std::string& c : counters) {
            const auto it = r.counters.find(c);
            os << "," << (it == r.counters.end() ? 0 : it->second);
        }
        os << "\n";
    }
    writeTextAtomically(path, os.str(), "sweep");
}

void writeSweepJson(const std::string& path, const std::vector<SweepResult>& results, const SweepFronts& fronts,
                    const SweepReportInfo& info) {
    nlohmann::ordered_json j{{"scene", info.scene}, {"reference", info.reference}, {"metric", tradeMetricName(info.metric)},
                             {"repeat", info.repeat}, {"runs", nlohmann::ordered_json::array()}};
    for (std::size_t i = 0; i < results.size(); ++i) j["runs"].push_back(resultJson(results[i], fronts.byTime[i], fronts.bySamples[i]));
    writeTextAtomically(path, j.dump(2) + "\n", "sweep");
}

void writeSweepMarkdown(const std::string& path, const std::vector<SweepResult>& results, const SweepFronts& fronts,
                        const SweepReportInfo& info) {
    std::vector<std::size_t> order(results.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return results[a].times.medianMs < results[b].times.medianMs; });
    std::ostringstream os;
    os << "Sweep of `" << info.scene << "` against `" << info.reference << "`, median of " << info.repeat
       << " render(s); front: not beaten on both time and " << tradeMetricName(info.metric) << ".\n\n"
       << "| technique | settings | time (s) | samples | RMSE | relMSE | PSNR (dB) | SSIM | FLIP | front |\n"
       << "|---|---|---:|---:|---:|---:|---:|---:|---:|:---:|\n";
    std::string refused;
    for (std::size_t i : order) {
        const SweepResult& r = results[i];
        if (!r.refused.empty()) {
            refused += "- run " + std::to_string(r.run.index + 1) + ", " + r.run.technique + " " + runLabel(r.run) + ": " + r.refused + "\n";
            continue;
        }
        char row[512];
        std::snprintf(row, sizeof row, "| %s | %s | %.3g | %lld | %.4g | %.4g | %.2f | %.4f | %.4f | %s |\n", r.run.technique.c_str(),
                      runLabel(r.run).c_str(), r.times.medianMs / 1000, (long long)r.samples, r.error.rmse, r.error.relMse,
                      r.error.psnr, r.error.ssim, r.error.flip, fronts.byTime[i] ? "*" : "");
        os << row;
    }
    if (!refused.empty()) os << "\nSettings the technique refused:\n\n" << refused;
    writeTextAtomically(path, os.str(), "sweep");
}

}  // namespace weft
