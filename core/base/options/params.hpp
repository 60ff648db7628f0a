#pragma once
// Parameters are declared once, as a table of ParamSpec. That one table
// validates user input (a bad value names the key, the value and the allowed
// range), documents the plugin (`weft help NAME`), and records every value
// used in the output metadata.
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace weft {

enum class ParamType { Int, Float, Bool, String, Enum };

const char* paramTypeName(ParamType type);

struct ParamSpec {
    std::string name;
    ParamType type = ParamType::Float;
    std::string defaultValue;  // in the same text form a user types
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    std::vector<std::string> choices;  // for Enum
    std::string doc;                   // one line of meaning
    // Optional extra check for String values; throws a message (without the key).
    std::function<void(const std::string&)> check = nullptr;

    // The allowed values as a user reads them: "[0.001, 64]", "one of a|b".
    std::string allowedText() const;
    // The same for a Markdown table cell: "[0.001, 64]", "`a`, `b`".
    std::string allowedMarkdown() const;
};

// Builders that keep plugin tables short and readable.
ParamSpec floatParam(std::string name, double def, double min, double max, std::string doc);
ParamSpec intParam(std::string name, std::int64_t def, std::int64_t min, std::int64_t max, std::string doc);
ParamSpec boolParam(std::string name, bool def, std::string doc);
ParamSpec enumParam(std::string name, std::string def, std::vector<std::string> choices, std::string doc);
ParamSpec stringParam(std::string name, std::string def, std::string doc,
                      std::function<void(const std::string&)> check = nullptr);

// Validated values of one plugin, every declared parameter present.
class ParamSet {
public:
    double getFloat(const std::string& name) const;
    std::int64_t getInt(const std::string& name) const;
    bool getBool(const std::string& name) const;
    const std::string& getString(const std::string& name) const;
    bool wasSet(const std::string& name) const;
    // Every parameter in table order with its value in canonical text form.
    const std::vector<std::pair<std::string, std::string>>& values() const { return ordered_; }

private:
    friend class ParamTable;
    struct Value {
        ParamType type;
        double number = 0;
        std::string text;
        bool explicitlySet = false;
    };
    const Value& find(const std::string& name, ParamType expected) const;
    std::map<std::string, Value> values_;
    std::vector<std::pair<std::string, std::string>> ordered_;
};

class ParamTable {
public:
    ParamTable(std::string owner, std::vector<ParamSpec> specs);

    // Validates user-given key=value text against the table. Unknown keys and
    // bad values throw weft::Error naming owner, key, value and allowed range.
    ParamSet parse(const std::map<std::string, std::string>& given) const;
    const std::vector<ParamSpec>& specs() const { return specs_; }
    const std::string& owner() const { return owner_; }
    // Human-readable documentation, one parameter per line.
    std::string helpText() const;
    // The same as a Markdown table: name, type, default, allowed values, meaning.
    std::string markdownTable() const;

private:
    std::string owner_;
    std::vector<ParamSpec> specs_;
};

// Canonical shortest round-trip text of a double.
std::string formatNumber(double v);

// Whether text, written as plain digits, lies outside spec's range, compared
// exactly: through a double, 2^53 + 1 read as 2^53 and passed a range ending
// there. False for any other text (a double's check decides).
bool integerOutOfRange(const std::string& text, const ParamSpec& spec);

}  // namespace weft
