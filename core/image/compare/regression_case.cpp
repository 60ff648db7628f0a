#include "core/image/compare/regression_case.hpp"

#include "core/base/error.hpp"
#include "core/base/files/input_file.hpp"
#include "core/base/files/json_doc.hpp"

namespace weft {

namespace {

double ruleValue(const JsonDoc& doc, const char* key, double def) {
    const auto& rule = doc.root().value("rule", nlohmann::json::object());
    if (!rule.contains(key)) return def;
    if (!rule[key].is_number() || rule[key].get<double>() < 0)
        throw Error(doc.where(std::string("/rule/") + key) + ": rule." + key + " must be a number >= 0");
    return rule[key].get<double>();
}

std::string text(const JsonDoc& doc, const char* key, bool required) {
    const auto& root = doc.root();
    if (!root.contains(key)) {
        if (required) throw Error(doc.where("") + ": a regression case needs '" + key + "'");
        return "";
    }
    if (!root[key].is_string()) throw Error(doc.where(std::string("/") + key) + ": '" + key + "' must be a string");
    return root[key].get<std::string>();
}

}  // namespace

RegressionCase readRegressionCase(const std::string& path) {
    requireRegularFile(path, "regression case");  // a FIFO would block the read forever
    const JsonDoc doc = JsonDoc::load(path);
    if (!doc.root().is_object()) throw Error(path + ": a regression case must be a JSON object");
    RegressionCase c;
    c.input = text(doc, "input", true);
    c.technique = text(doc, "technique", true);
    c.resolution = text(doc, "resolution", true);
    if (doc.root().contains("spp")) {
        if (!doc.root()["spp"].is_number_integer() || doc.root()["spp"].get<int>() < 1)
            throw Error(doc.where("/spp") + ": spp must be an integer >= 1");
        c.spp = doc.root()["spp"].get<int>();
    }
    for (const auto& s : doc.root().value("set", nlohmann::json::array())) {
        if (!s.is_string()) throw Error(doc.where("/set") + ": set must be a list of \"key=value\" strings");
        c.sets.push_back(s.get<std::string>());
    }
    c.rule = {ruleValue(doc, "threshold", 0.004), ruleValue(doc, "fail_fraction", 0.02), ruleValue(doc, "hard_fail", 0.012)};
    return c;
}

}  // namespace weft
