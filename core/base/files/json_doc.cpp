#include "core/base/files/json_doc.hpp"

#include <fstream>
#include <iterator>
#include <sstream>
#include <vector>

#include "core/base/error.hpp"
#include "core/base/quote_value.hpp"

namespace weft {

namespace {

// An input iterator over the text that publishes how far the parser has read,
// so the SAX handler below knows where each event's token ended.
struct CountingIterator {
    using iterator_category = std::input_iterator_tag;
    using value_type = char;
    using difference_type = std::ptrdiff_t;
    using pointer = const char*;
    using reference = const char&;

    const char* p;
    const char* base;
    std::size_t* consumed;

    reference operator*() const { return *p; }
    CountingIterator& operator++() {
        ++p;
        *consumed = static_cast<std::size_t>(p - base);
        return *this;
    }
    CountingIterator operator++(int) { auto old = *this; ++*this; return old; }
    bool operator==(const CountingIterator& o) const { return p == o.p; }
    bool operator!=(const CountingIterator& o) const { return p != o.p; }
};

// A quoted token of the input (a number of 400 digits, a long string) is
// shortened as every quoted value in weft's messages is.
std::string shortenQuoted(const std::string& text) {
    const std::size_t open = text.find('\'');
    const std::size_t close = open == std::string::npos ? open : text.rfind('\'');
    if (open == std::string::npos || close <= open) return text;
    return text.substr(0, open) + quoteValue(std::string_view(text).substr(open + 1, close - open - 1)) + text.substr(close + 1);
}

// nlohmann's "syntax error while parsing CONTEXT - PROBLEM; last read:
// 'TOKEN'; expected WHAT" said as "in CONTEXT: PROBLEM at 'TOKEN'; expected WHAT".
std::string syntaxErrorInOwnWords(const std::string& msg) {
    static const std::pair<const char*, const char*> kContexts[] = {
        {"value", "a value"}, {"object key", "an object key"}, {"object separator", "the ':' after a key"},
        {"object", "an object"}, {"array", "an array"}};
    std::string context, rest = msg;
    if (const std::size_t at = msg.find("while parsing "), dash = msg.find(" - "); at != std::string::npos && dash != std::string::npos && at < dash) {
        context = msg.substr(at + 14, dash - at - 14);
        for (const auto& [theirs, ours] : kContexts)
            if (context == theirs) context = ours;
        rest = msg.substr(dash + 3);
    } else if (const std::size_t dash = msg.find("- "); dash != std::string::npos) {
        rest = msg.substr(dash + 2);
    }
    std::string problem = rest, token, expected;
    if (const std::size_t lr = rest.find("; last read: "); lr != std::string::npos) {
        problem = rest.substr(0, lr);
        token = rest.substr(lr + 13);
        if (const std::size_t ex = token.find("; expected "); ex != std::string::npos) expected = token.substr(ex + 11), token = token.substr(0, ex);
    } else if (const std::size_t ex = rest.find("; expected "); ex != std::string::npos) {
        problem = rest.substr(0, ex), expected = rest.substr(ex + 11);
    }
    std::string out = context.empty() ? problem : "in " + context + ": " + problem;
    if (!token.empty() && token != "''") out += " at " + token;
    if (!expected.empty()) out += "; expected " + expected;
    return out;
}

// nlohmann's message without its "[json.exception.parse_error.101] parse
// error at line 1, column 2: " prefix (the caller gives the position).
std::string jsonErrorInOwnWords(int id, const std::string& what) {
    std::string msg = what;
    if (auto bracket = msg.find("] "); msg.rfind("[json.exception.", 0) == 0 && bracket != std::string::npos)
        msg = msg.substr(bracket + 2);
    if (msg.rfind("parse error", 0) == 0)
        if (auto colon = msg.find(": "); colon != std::string::npos) msg = msg.substr(colon + 2);
    if (msg.rfind("syntax error", 0) == 0) msg = syntaxErrorInOwnWords(msg);
    if (id == 406) {  // out_of_range.406: "number overflow parsing '<digits>'"
        const std::size_t open = msg.find('\'');
        msg = "number too large for a double" + (open == std::string::npos ? std::string() : ": " + msg.substr(open));
    }
    return shortenQuoted(msg);
}

std::string escapePointerToken(const std::string& key) {
    std::string out;
    for (char c : key) out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
    return out;
}

}  // namespace

// Builds the DOM like nlohmann's own SAX DOM parser, and records for each
// value the position of its first character.
class PositionedSax {
public:
    using json = nlohmann::json;
    PositionedSax(const std::string& text, JsonDoc& doc, const std::size_t& consumed)
        : text_(text), doc_(doc), consumed_(consumed) {}

    bool null() { return value(nullptr); }
    bool boolean(bool v) { return value(v); }
    bool number_integer(json::number_integer_t v) { return value(v); }
    bool number_unsigned(json::number_unsigned_t v) { return value(v); }
    bool number_float(json::number_float_t v, const json::string_t&) { return value(v); }
    bool string(json::string_t& v) { return value(v); }
    bool binary(json::binary_t& v) { return value(json(v)); }
    bool start_object(std::size_t) { return open(json::object()); }
    bool start_array(std::size_t) { return open(json::array()); }
    bool end_object() { return close(); }
    bool end_array() { return close(); }
    bool key(json::string_t& k) {
        const std::size_t start = tokenStart();
        doc_.positions_[pointers_.back() + "/" + escapePointerToken(k) + "#key"] = toPos(start);
        key_ = k;
        lastEnd_ = consumed_;
        return true;
    }
    bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& ex) {
        const TextPos pos = toPos(position > 0 ? position - 1 : 0);
        throw Error(doc_.file_ + ":" + std::to_string(pos.line) + ":" + std::to_string(pos.column) +
                    ": JSON syntax error: " + jsonErrorInOwnWords(ex.id, ex.what()));
    }

private:
    // First character of the current token: skip the separators after the
    // previous event's end.
    std::size_t tokenStart() const {
        std::size_t i = lastEnd_;
        while (i < text_.size() && (std::isspace(static_cast<unsigned char>(text_[i])) || text_[i] == ':' || text_[i] == ','))
            ++i;
        return i;
    }
    // Events come in text order, so the line and column are carried forward
    // from the last offset asked: the whole parse scans the text once (from
    // the start each time, a 689 KB scene took 30 s).
    TextPos toPos(std::size_t offset) {
        if (offset < cursorOffset_) cursorOffset_ = 0, cursor_ = TextPos{};
        for (; cursorOffset_ < offset && cursorOffset_ < text_.size(); ++cursorOffset_) {
            if (text_[cursorOffset_] == '\n') ++cursor_.line, cursor_.column = 1;
            else ++cursor_.column;
        }
        return cursor_;
    }
    std::string childPointer() const {
        if (stack_.empty()) return "";
        json& parent = *stack_.back();
        return pointers_.back() + "/" + (parent.is_array() ? std::to_string(parent.size()) : escapePointerToken(key_));
    }
    json* insert(json v) {
        if (stack_.empty()) { doc_.root_ = std::move(v); return &doc_.root_; }
        json& parent = *stack_.back();
        if (parent.is_array()) { parent.push_back(std::move(v)); return &parent.back(); }
        parent[key_] = std::move(v);
        return &parent[key_];
    }
    bool value(json v) {
        doc_.positions_[childPointer()] = toPos(tokenStart());
        insert(std::move(v));
        lastEnd_ = consumed_;
        return true;
    }
    bool open(json container) {
        if (stack_.size() >= kMaxDepth) {
            const TextPos pos = toPos(tokenStart());
            throw Error(doc_.file_ + ":" + std::to_string(pos.line) + ":" + std::to_string(pos.column) +
                        ": JSON nested deeper than " + std::to_string(kMaxDepth) + " levels of arrays and objects");
        }
        const std::string pointer = childPointer();
        doc_.positions_[pointer] = toPos(tokenStart());
        stack_.push_back(insert(std::move(container)));
        pointers_.push_back(pointer);
        lastEnd_ = consumed_;
        return true;
    }
    bool close() {
        stack_.pop_back();
        pointers_.pop_back();
        lastEnd_ = consumed_;
        return true;
    }

    // Scenes nest a few levels; bounded, the pointers to 100,000 nested
    // arrays (twice the depth in characters each) took 17 GB.
    static constexpr std::size_t kMaxDepth = 256;

    const std::string& text_;
    JsonDoc& doc_;
    const std::size_t& consumed_;
    std::size_t cursorOffset_ = 0;
    TextPos cursor_;
    std::size_t lastEnd_ = 0;
    std::vector<json*> stack_;
    std::vector<std::string> pointers_;
    std::string key_;
};

JsonDoc JsonDoc::parse(const std::string& text, const std::string& fileName) {
    JsonDoc doc;
    doc.file_ = fileName;
    std::size_t consumed = 0;
    PositionedSax sax(text, doc, consumed);
    CountingIterator first{text.data(), text.data(), &consumed};
    CountingIterator last{text.data() + text.size(), text.data(), &consumed};
    nlohmann::json::sax_parse(first, last, &sax);
    return doc;
}

JsonDoc JsonDoc::load(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("scene '" + path + "': cannot open file");
    std::stringstream buffer;
    buffer << in.rdbuf();
    return parse(buffer.str(), path);
}

TextPos JsonDoc::position(const std::string& pointer) const {
    auto it = positions_.find(pointer);
    return it == positions_.end() ? TextPos{} : it->second;
}

std::string JsonDoc::where(const std::string& pointer) const {
    const TextPos pos = position(pointer);
    return file_ + ":" + std::to_string(pos.line) + ":" + std::to_string(pos.column);
}

}  // namespace weft
