#pragma once
// A JSON document that remembers where every value stands in its source
// text, so that errors found after parsing (an unknown key, a value out of
// range) still point at file:line:column.
#include <map>
#include <string>

#include <nlohmann/json.hpp>

namespace weft {

struct TextPos {
    int line = 1;
    int column = 1;
};

class JsonDoc {
public:
    // Parses text; syntax errors throw weft::Error "file:line:col: ...".
    static JsonDoc parse(const std::string& text, const std::string& fileName);
    static JsonDoc load(const std::string& path);

    const nlohmann::json& root() const { return root_; }
    const std::string& fileName() const { return file_; }
    // "file:line:col" of the value (or key) at a JSON pointer, e.g. "/volumes/0/grid".
    std::string where(const std::string& pointer) const;
    // Position of a value; the key's position for "pointer#key".
    TextPos position(const std::string& pointer) const;

private:
    friend class PositionedSax;
    nlohmann::json root_;
    std::string file_;
    std::map<std::string, TextPos> positions_;
};

}  // namespace weft
