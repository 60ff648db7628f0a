// Written from NumPy's description of the .npy format (numpy.lib.format).
#include "core/volume/io/npy_header.hpp"

#include <cstring>
#include <map>

#include "core/base/error.hpp"
#include "core/volume/io/header_text.hpp"

namespace weft {

namespace {

// A value of the header dict: a string, a boolean or a tuple of integers.
struct PyValue {
    enum Kind { String, Bool, Tuple } kind = String;
    std::string text;
    bool flag = false;
    std::vector<std::int64_t> items;
};

// A recursive-descent reader for the one dict literal numpy writes.
class DictReader {
public:
    DictReader(std::string_view text, const std::string& file) : s_(text), file_(file) {}

    std::map<std::string, PyValue> read() {
        std::map<std::string, PyValue> dict;
        expect('{');
        for (;;) {
            skipSpace();
            if (peek() == '}') break;
            const std::string key = readString();
            expect(':');
            skipSpace();
            if (!dict.emplace(key, readValue(key)).second) fail("key '" + key + "' is given twice");
            skipSpace();
            if (peek() == ',') ++i_;
            else if (peek() != '}') fail("expected ',' or '}' after '" + key + "'");
        }
        ++i_;
        skipSpace();
        if (i_ != s_.size()) fail("text after the closing '}'");
        return dict;
    }

private:
    [[noreturn]] void fail(const std::string& why) const {
        throw Error(file_ + ": NumPy header dict: " + why + " (at character " + std::to_string(i_) + ")");
    }
    char peek() const { return i_ < s_.size() ? s_[i_] : '\0'; }
    void skipSpace() {
        while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\n' || s_[i_] == '\r')) ++i_;
    }
    void expect(char c) {
        skipSpace();
        if (peek() != c) fail(std::string("expected '") + c + "'");
        ++i_;
    }
    bool accept(std::string_view word) {
        if (s_.substr(i_, word.size()) != word) return false;
        i_ += word.size();
        return true;
    }

    std::string readString() {
        skipSpace();
        const char quote = peek();
        if (quote != '\'' && quote != '"') fail("expected a quoted string");
        const std::size_t end = s_.find(quote, i_ + 1);
        if (end == std::string_view::npos) fail("unterminated string");
        std::string out(s_.substr(i_ + 1, end - i_ - 1));
        if (out.find('\\') != std::string::npos) fail("escapes in strings are not supported");
        i_ = end + 1;
        return out;
    }

    std::int64_t readInteger() {
        skipSpace();
        const std::size_t start = i_;
        while (peek() >= '0' && peek() <= '9') ++i_;
        std::int64_t v;
        if (!parseWhole(s_.substr(start, i_ - start), v)) fail("expected a non-negative integer of at most 18 digits");
        if (peek() == 'L') ++i_;  // Python 2 long
        return v;
    }

    PyValue readTuple() {
        PyValue v;
        v.kind = PyValue::Tuple;
        ++i_;  // '('
        for (;;) {
            skipSpace();
            if (peek() == ')') break;
            if (v.items.size() == 32) fail("a shape of more than 32 axes");
            v.items.push_back(readInteger());
            skipSpace();
            if (peek() == ',') ++i_;
            else if (peek() != ')') fail("expected ',' or ')' in a tuple");
        }
        ++i_;
        return v;
    }

    PyValue readValue(const std::string& key) {
        PyValue v;
        if (peek() == '\'' || peek() == '"') {
            v.text = readString();
        } else if (peek() == '(') {
            v = readTuple();
        } else if (accept("True")) {
            v.kind = PyValue::Bool;
            v.flag = true;
        } else if (accept("False")) {
            v.kind = PyValue::Bool;
        } else if (peek() == '[') {
            throw Error(file_ + ": NumPy header '" + key + "': structured dtypes (a list) are not supported");
        } else {
            fail("the value of '" + key + "' is not a string, True, False or a tuple");
        }
        return v;
    }

    std::string_view s_;
    std::size_t i_ = 0;
    const std::string& file_;
};

// descr: byte order ('<' little, '>' big, '|' not applicable) then kind and size.
void readDescr(const std::string& descr, VolumeHeader& h, const std::string& file) {
    static const struct {
        const char* code;
        RawType type;
    } codes[] = {{"i1", RawType::I8},  {"u1", RawType::U8},  {"i2", RawType::I16}, {"u2", RawType::U16},
                 {"i4", RawType::I32}, {"u4", RawType::U32}, {"f4", RawType::F32}, {"f8", RawType::F64}};
    const Error bad(file + ": NumPy header 'descr' " + quoteValue(descr) +
                    ": weft reads <i1 <u1 <i2 <u2 <i4 <u4 <f4 <f8 (or '>' for big-endian, '|' for one byte)");
    if (descr.size() != 3) throw bad;
    const char order = descr[0];
    bool found = false;
    for (const auto& c : codes)
        if (descr.compare(1, 2, c.code) == 0) {
            h.spec.type = c.type;
            found = true;
        }
    if (!found) throw bad;
    const bool oneByte = rawTypeBytes(h.spec.type) == 1;
    if (order == '<') h.spec.byteOrder = ByteOrder::Little;
    else if (order == '>') h.spec.byteOrder = ByteOrder::Big;
    else if (order != '|' || !oneByte) throw bad;
}

void readShape(const PyValue& shape, bool fortran, VolumeHeader& h, const std::string& file) {
    if (shape.kind != PyValue::Tuple || shape.items.size() != 3)
        throw Error(file + ": NumPy header 'shape': weft reads 3-D arrays (shape (Z, Y, X) in C order)");
    for (int i = 0; i < 3; ++i) {
        const std::int64_t n = shape.items[std::size_t(i)];
        if (n <= 0 || n > kMaxRawDim)
            throw Error(file + ": NumPy header 'shape': axis " + std::to_string(i) + " of " + std::to_string(n) +
                        " elements (expected 1 to " + std::to_string(kMaxRawDim) + ")");
        // C order: the last axis is fastest, and weft's x is fastest.
        h.spec.dims[fortran ? i : 2 - i] = int(n);
    }
}

std::uint64_t readLittle(std::string_view bytes, std::size_t at, std::size_t n) {
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < n; ++i) v |= std::uint64_t(static_cast<unsigned char>(bytes[at + i])) << (8 * i);
    return v;
}

}  // namespace

VolumeHeader parseNpyHeader(std::string_view bytes, const std::string& file) {
    if (bytes.size() < 10 || bytes.substr(0, 6) != std::string_view("\x93NUMPY", 6))
        throw Error(file + ": not a NumPy .npy file (no \\x93NUMPY magic)");
    const int major = static_cast<unsigned char>(bytes[6]), minor = static_cast<unsigned char>(bytes[7]);
    if (major < 1 || major > 3 || minor != 0)
        throw Error(file + ": NumPy format version " + std::to_string(major) + "." + std::to_string(minor) +
                    " is not supported (weft reads 1.0, 2.0 and 3.0)");
    const std::size_t lengthBytes = major == 1 ? 2 : 4;
    if (bytes.size() < 8 + lengthBytes) throw Error(file + ": NumPy header is cut short");
    const std::uint64_t length = readLittle(bytes, 8, lengthBytes);
    const std::size_t start = 8 + lengthBytes;
    if (length > kMaxHeaderBytes)
        throw Error(file + ": NumPy header length " + std::to_string(length) + " is more than weft accepts (" +
                    std::to_string(kMaxHeaderBytes) + ")");
    if (bytes.size() < start + length)
        throw Error(file + ": NumPy header of " + std::to_string(length) + " bytes is cut short (the file ends first)");

    const auto dict = DictReader(bytes.substr(start, std::size_t(length)), file).read();
    for (const auto& [key, value] : dict)
        if (key != "descr" && key != "fortran_order" && key != "shape")
            throw Error(file + ": NumPy header key " + quoteValue(key) + " is not one of descr, fortran_order, shape");
    for (const char* key : {"descr", "fortran_order", "shape"})
        if (!dict.count(key)) throw Error(file + ": NumPy header has no '" + std::string(key) + "'");
    const PyValue& descr = dict.at("descr");
    const PyValue& fortran = dict.at("fortran_order");
    if (descr.kind != PyValue::String) throw Error(file + ": NumPy header 'descr' is not a string");
    if (fortran.kind != PyValue::Bool) throw Error(file + ": NumPy header 'fortran_order' is not True or False");

    VolumeHeader h;
    readDescr(descr.text, h, file);
    readShape(dict.at("shape"), fortran.flag, h, file);
    h.stated.dims = h.stated.type = h.stated.byteOrder = true;
    h.dataOffset = start + length;
    return h;
}

}  // namespace weft
