#include "plugins/host/render_cli.hpp"

#include <algorithm>
#include <cstdio>
#include <map>

#include "core/base/error.hpp"

namespace weft {

namespace {

// The options whose names are not simply --NAME.
const std::map<std::string, std::string, std::less<>>& ownNames() {
    static const std::map<std::string, std::string, std::less<>> names = {
        {"input", "input"},  // positional
        {"output", "-o,--output"},
        {"resolution", "--res,--resolution"},
        {"pixel_type", "-d,--pixel-type"},
        {"verbose", "-v,--verbose"},
    };
    return names;
}

std::string places(const RenderOption& o) {
    std::string s;
    if (o.places & kOnCommandLine) s += commandLineLabel(o);
    if (o.places & kInBatchJob) s += std::string(s.empty() ? "" : ", ") + "batch";
    if (o.places & kInScene) s += std::string(s.empty() ? "" : ", ") + "scene";
    return s;
}

std::string jsonNames(const RenderOption& o) {
    std::string s = o.spec.name;
    for (const std::string& a : o.aliases) s += " (or " + a + ")";
    return s;
}

}  // namespace

std::string commandLineNames(const RenderOption& option) {
    if (const auto own = ownNames().find(option.spec.name); own != ownNames().end()) return own->second;
    std::string name = option.spec.name;
    std::replace(name.begin(), name.end(), '_', '-');
    return "--" + name;
}

std::string commandLineLabel(const RenderOption& option) {
    const std::string names = commandLineNames(option);
    const auto dashes = names.find("--");
    if (dashes == std::string::npos) return names;  // positional
    return names.substr(dashes, names.find(',', dashes) - dashes);
}

void checkRenderNumber(std::string_view name, double value) {
    const RenderOption* o = findRenderOption(name, kOnCommandLine);
    if (o && !(value >= o->spec.min && value <= o->spec.max))
        throw Error(commandLineLabel(*o) + " " + formatNumber(value) + " is outside " + o->spec.allowedText());
}

std::string renderOptionsHelp() {
    std::string out;
    char line[512];
    for (const RenderOption& o : renderOptions()) {
        std::snprintf(line, sizeof line, "  %-26s %-6s %-9s %-20s %s\n    given as: %s\n", jsonNames(o).c_str(),
                      paramTypeName(o.spec.type), o.spec.defaultValue.empty() ? "-" : o.spec.defaultValue.c_str(),
                      o.spec.type == ParamType::String ? "" : o.spec.allowedText().c_str(), o.spec.doc.c_str(), places(o).c_str());
        out += line;
    }
    return out;
}

std::string renderOptionsMarkdown() {
    std::string out =
        "| key (batch, scene) | command line | batch | scene | type | default | allowed | meaning |\n"
        "|---|---|---|---|---|---|---|---|\n";
    for (const RenderOption& o : renderOptions()) {
        std::string doc = o.spec.doc;
        for (std::size_t p = doc.find('|'); p != std::string::npos; p = doc.find('|', p + 2)) doc.replace(p, 1, "\\|");
        out += "| `" + o.spec.name + "`";
        for (const std::string& a : o.aliases) out += " or `" + a + "`";
        out += " | `" + commandLineNames(o) + "` | " + ((o.places & kInBatchJob) ? "yes" : "no") + " | " +
               ((o.places & kInScene) ? "yes" : "no") + " | " + paramTypeName(o.spec.type) + " | " +
               (o.spec.defaultValue.empty() ? "" : "`" + o.spec.defaultValue + "`") + " | " +
               (o.spec.type == ParamType::String ? "" : o.spec.allowedMarkdown()) + " | " + doc + " |\n";
    }
    return out;
}

}  // namespace weft
