#include "core/base/options/params.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "core/base/error.hpp"
#include "core/base/options/param_value.hpp"

namespace weft {

const char* paramTypeName(ParamType type) {
    switch (type) {
        case ParamType::Int: return "int";
        case ParamType::Float: return "float";
        case ParamType::Bool: return "bool";
        case ParamType::String: return "string";
        case ParamType::Enum: return "enum";
    }
    return "?";
}

std::string formatNumber(double v) {
    char buf[64];
    auto res = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, res.ptr);
}

static std::string joinChoices(const std::vector<std::string>& choices) {
    std::string out;
    for (const auto& c : choices) out += (out.empty() ? "" : "|") + c;
    return out;
}

std::string ParamSpec::allowedText() const {
    switch (type) {
        case ParamType::Bool: return "true|false";
        case ParamType::Enum: return "one of " + joinChoices(choices);
        case ParamType::String: return "text";
        default: break;
    }
    const bool lo = std::isfinite(min), hi = std::isfinite(max);
    if (lo && hi) return "[" + formatNumber(min) + ", " + formatNumber(max) + "]";
    if (lo) return ">= " + formatNumber(min);
    if (hi) return "<= " + formatNumber(max);
    return "any";
}

std::string ParamSpec::allowedMarkdown() const {
    std::string out;
    switch (type) {
        case ParamType::Bool: return "`true`, `false`";
        case ParamType::Enum:
            for (const auto& c : choices) out += (out.empty() ? "`" : ", `") + c + "`";
            return out;
        case ParamType::String: return "text";
        default: return allowedText();
    }
}

ParamSpec floatParam(std::string name, double def, double min, double max, std::string doc) {
    return {std::move(name), ParamType::Float, formatNumber(def), min, max, {}, std::move(doc)};
}
ParamSpec intParam(std::string name, std::int64_t def, std::int64_t min, std::int64_t max, std::string doc) {
    return {std::move(name), ParamType::Int, std::to_string(def), double(min), double(max), {}, std::move(doc)};
}
ParamSpec boolParam(std::string name, bool def, std::string doc) {
    return {std::move(name), ParamType::Bool, def ? "true" : "false", 0, 1, {}, std::move(doc)};
}
ParamSpec enumParam(std::string name, std::string def, std::vector<std::string> choices, std::string doc) {
    return {std::move(name), ParamType::Enum, std::move(def), 0, 0, std::move(choices), std::move(doc)};
}
ParamSpec stringParam(std::string name, std::string def, std::string doc,
                      std::function<void(const std::string&)> check) {
    ParamSpec s{std::move(name), ParamType::String, std::move(def), 0, 0, {}, std::move(doc)};
    s.check = std::move(check);
    return s;
}

namespace {

[[noreturn]] void badValue(const std::string& owner, const ParamSpec& spec, const std::string& text,
                           const std::string& why) {
    throw Error(owner + ": bad value '" + text + "' for parameter '" + spec.name + "' (" +
                paramTypeName(spec.type) + ", allowed " + spec.allowedText() + ")" +
                (why.empty() ? "" : ": " + why));
}

bool parseDouble(const std::string& text, double& out) {
    const char* end = text.data() + text.size();
    auto res = std::from_chars(text.data(), end, out);
    return res.ec == std::errc() && res.ptr == end && !text.empty();
}

// Converts and range-checks one value; returns it with canonical text.
std::pair<double, std::string> convert(const std::string& owner, const ParamSpec& spec, const std::string& text) {
    const ParamValue v = checkParamValue(spec, text);
    switch (v.fault) {
        case ParamValue::Fault::None: return {v.number, v.canonical};
        case ParamValue::Fault::NotNumber: badValue(owner, spec, text, "not a number");
        case ParamValue::Fault::NotInteger: badValue(owner, spec, text, "not an integer");
        case ParamValue::Fault::OutOfRange: badValue(owner, spec, text, "out of range");
        case ParamValue::Fault::Check: badValue(owner, spec, text, v.checkMessage);
        default: badValue(owner, spec, text, "");
    }
}

}  // namespace

ParamValue checkParamValue(const ParamSpec& spec, const std::string& text) {
    ParamValue v;
    const auto fail = [&](ParamValue::Fault f) { v.fault = f; return v; };
    switch (spec.type) {
        case ParamType::Bool:
            if (text == "true" || text == "1" || text == "on" || text == "yes") v.number = 1, v.canonical = "true";
            else if (text == "false" || text == "0" || text == "off" || text == "no") v.canonical = "false";
            else return fail(ParamValue::Fault::NotBool);
            return v;
        case ParamType::Enum:
            for (const auto& c : spec.choices)
                if (c == text) return v.canonical = text, v;
            return fail(ParamValue::Fault::NotChoice);
        case ParamType::String:
            if (spec.check) {
                try {
                    spec.check(text);
                } catch (const Error& e) {
                    v.checkMessage = e.what();
                    return fail(ParamValue::Fault::Check);
                }
            }
            return v.canonical = text, v;
        case ParamType::Int:
        case ParamType::Float: {
            if (!parseDouble(text, v.number) || !std::isfinite(v.number)) return fail(ParamValue::Fault::NotNumber);
            if (spec.type == ParamType::Int && v.number != std::floor(v.number)) return fail(ParamValue::Fault::NotInteger);
            if (v.number < spec.min || v.number > spec.max || (spec.type == ParamType::Int && integerOutOfRange(text, spec)))
                return fail(ParamValue::Fault::OutOfRange);
            v.canonical = spec.type == ParamType::Int ? std::to_string(static_cast<long long>(v.number)) : formatNumber(v.number);
            return v;
        }
    }
    return fail(ParamValue::Fault::NotChoice);
}

bool integerOutOfRange(const std::string& text, const ParamSpec& spec) {
    long long v = 0;
    const char* end = text.data() + text.size();
    const auto res = std::from_chars(text.data(), end, v);
    if (res.ptr != end || text.empty()) return false;  // not plain digits: the double path decides
    if (res.ec == std::errc::result_out_of_range) return true;
    constexpr double kInt64 = 9.2e18;  // below 2^63: such bounds convert exactly to long long
    const bool belowMin = std::abs(spec.min) < kInt64 ? v < static_cast<long long>(spec.min) : double(v) < spec.min;
    const bool aboveMax = std::abs(spec.max) < kInt64 ? v > static_cast<long long>(spec.max) : double(v) > spec.max;
    return belowMin || aboveMax;
}

ParamTable::ParamTable(std::string owner, std::vector<ParamSpec> specs)
    : owner_(std::move(owner)), specs_(std::move(specs)) {
    // Defaults must be valid. Checks that consult a registry run at parse time:
    // registries fill up during static initialisation, in no fixed order.
    for (const ParamSpec& spec : specs_)
        if (!spec.check) convert(owner_, spec, spec.defaultValue);
}

ParamSet ParamTable::parse(const std::map<std::string, std::string>& given) const {
    for (const auto& [key, text] : given) {
        bool known = false;
        for (const ParamSpec& spec : specs_) known = known || spec.name == key;
        if (!known) {
            std::string valid;
            for (const ParamSpec& spec : specs_) valid += (valid.empty() ? "" : ", ") + spec.name;
            throw Error(owner_ + ": unknown parameter '" + key + "'; valid parameters: " +
                        (valid.empty() ? "(none)" : valid));
        }
    }
    ParamSet set;
    for (const ParamSpec& spec : specs_) {
        auto it = given.find(spec.name);
        const bool explicitlySet = it != given.end();
        auto [number, canonical] = convert(owner_, spec, explicitlySet ? it->second : spec.defaultValue);
        set.values_[spec.name] = {spec.type, number, canonical, explicitlySet};
        set.ordered_.emplace_back(spec.name, canonical);
    }
    return set;
}

std::string ParamTable::helpText() const {
    std::string out;
    char line[512];
    for (const ParamSpec& s : specs_) {
        std::snprintf(line, sizeof line, "  %-16s %-7s default %-10s %-22s %s\n", s.name.c_str(),
                      paramTypeName(s.type), s.defaultValue.c_str(), s.allowedText().c_str(), s.doc.c_str());
        out += line;
    }
    return out.empty() ? "  (no parameters)\n" : out;
}

// Text for one Markdown table cell: a '|' would end the cell.
static std::string markdownCell(const std::string& text) {
    std::string out;
    for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
    return out;
}

std::string ParamTable::markdownTable() const {
    if (specs_.empty()) return "No parameters.\n";
    std::string out = "| parameter | type | default | allowed | meaning |\n|---|---|---|---|---|\n";
    for (const ParamSpec& s : specs_) {
        const std::string def = s.defaultValue.empty() ? "(empty)" : "`" + markdownCell(s.defaultValue) + "`";
        out += "| `" + s.name + "` | " + paramTypeName(s.type) + " | " + def + " | " +
               markdownCell(s.allowedMarkdown()) + " | " + markdownCell(s.doc) + " |\n";
    }
    return out;
}

const ParamSet::Value& ParamSet::find(const std::string& name, ParamType expected) const {
    auto it = values_.find(name);
    if (it == values_.end()) throw Error("internal: parameter '" + name + "' is not declared");
    const bool numeric = expected == ParamType::Float || expected == ParamType::Int;
    const bool textual = expected == ParamType::String || expected == ParamType::Enum;
    const ParamType t = it->second.type;
    const bool ok = t == expected || (numeric && (t == ParamType::Float || t == ParamType::Int)) ||
                    (textual && (t == ParamType::String || t == ParamType::Enum));
    if (!ok) throw Error("internal: parameter '" + name + "' read as " + paramTypeName(expected));
    return it->second;
}

double ParamSet::getFloat(const std::string& name) const { return find(name, ParamType::Float).number; }
std::int64_t ParamSet::getInt(const std::string& name) const {
    return static_cast<std::int64_t>(find(name, ParamType::Int).number);
}
bool ParamSet::getBool(const std::string& name) const { return find(name, ParamType::Bool).number != 0; }
const std::string& ParamSet::getString(const std::string& name) const { return find(name, ParamType::String).text; }
bool ParamSet::wasSet(const std::string& name) const {
    auto it = values_.find(name);
    return it != values_.end() && it->second.explicitlySet;
}

}  // namespace weft
