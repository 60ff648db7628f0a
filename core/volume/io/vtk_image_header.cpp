// Written from the VTK file formats document (legacy format, versions 2.0 to 5.1).
#include "core/volume/io/vtk_image_header.hpp"

#include <algorithm>
#include <set>

#include "core/base/error.hpp"
#include "core/volume/io/header_text.hpp"

namespace weft {

namespace {

// The header's lines one at a time, tracking where the next one starts.
class Lines {
public:
    Lines(std::string_view bytes, bool wholeFile, const std::string& file) : s_(bytes), whole_(wholeFile), file_(file) {}

    std::string_view next() {
        if (pos_ >= s_.size()) throw ended();
        return nextHeaderLine(s_, pos_, whole_, file_, "VTK");
    }

    // The next line holding something, split into words.
    std::vector<std::string_view> nextWords() {
        for (;;) {
            auto words = splitWhitespace(next());
            if (!words.empty()) return words;
        }
    }

    // Whether the text from here on starts with `word` (any case), after spaces.
    bool startsWith(std::string_view word, bool skipSpace) const {
        std::size_t p = pos_;
        while (skipSpace && p < s_.size() && (s_[p] == ' ' || s_[p] == '\t' || s_[p] == '\r' || s_[p] == '\n')) ++p;
        return lowerAscii(s_.substr(p, word.size())) == word;
    }

    std::size_t offset() const { return pos_; }
    Error ended() const { return Error(file_ + ": VTK header ends before its SCALARS array"); }

private:
    std::string_view s_;
    std::size_t pos_ = 0;
    bool whole_;
    const std::string& file_;
};

struct Parser {
    const std::string& file;
    Error bad(std::string_view keyword, const std::string& why) const {
        return Error(file + ": VTK " + quoteValue(keyword) + ": " + why);
    }
};

RawType vtkType(std::string_view name, const Parser& p) {
    static const struct {
        const char* name;
        RawType type;
    } types[] = {{"unsigned_char", RawType::U8}, {"char", RawType::I8}, {"signed_char", RawType::I8},
                 {"unsigned_short", RawType::U16}, {"short", RawType::I16}, {"unsigned_int", RawType::U32},
                 {"int", RawType::I32}, {"float", RawType::F32}, {"double", RawType::F64},
                 {"vtktypeuint8", RawType::U8}, {"vtktypeint8", RawType::I8}, {"vtktypeuint16", RawType::U16},
                 {"vtktypeint16", RawType::I16}, {"vtktypeuint32", RawType::U32}, {"vtktypeint32", RawType::I32},
                 {"vtktypefloat32", RawType::F32}, {"vtktypefloat64", RawType::F64}};
    const std::string lower = lowerAscii(name);
    for (const auto& t : types)
        if (lower == t.name) return t.type;
    throw p.bad(name, "sample type not supported (weft reads unsigned_char, char, unsigned_short, short, "
                      "unsigned_int, int, float, double)");
}

void readTriple(const std::vector<std::string_view>& words, bool positive, double* out, const Parser& p) {
    if (words.size() != 4) throw p.bad(words[0], "expected 3 numbers");
    for (int i = 0; i < 3; ++i)
        if (!parseFinite(words[std::size_t(i) + 1], out[i]) || (positive && !(out[i] > 0)))
            throw p.bad(words[0], std::string("expected 3 ") + (positive ? "positive " : "") + "finite numbers, not " +
                                      quoteValue(words[std::size_t(i) + 1]));
}

void readDimensions(const std::vector<std::string_view>& words, VolumeHeader& h, const Parser& p) {
    if (words.size() != 4) throw p.bad(words[0], "expected 3 sizes");
    for (int i = 0; i < 3; ++i) {
        std::int64_t n;
        if (!parseWhole(words[std::size_t(i) + 1], n) || n < 1 || n > kMaxRawDim)
            throw p.bad(words[0], "expected 3 sizes from 1 to " + std::to_string(kMaxRawDim) + ", not " +
                                      quoteValue(words[std::size_t(i) + 1]));
        h.spec.dims[i] = int(n);
    }
    h.stated.dims = true;
}

// DIMENSIONS, SPACING and ORIGIN up to and including POINT_DATA.
void readGeometry(Lines& lines, VolumeHeader& h, const Parser& p) {
    std::set<std::string> seen;
    for (;;) {
        const auto words = lines.nextWords();
        std::string key = lowerAscii(words[0]);
        if (key == "aspect_ratio") key = "spacing";
        if (!seen.insert(key).second) throw p.bad(words[0], "given twice");
        if (key == "dimensions") readDimensions(words, h, p);
        else if (key == "spacing") {
            readTriple(words, true, h.spec.spacing.asPointer(), p);
            h.stated.spacing = true;
        } else if (key == "origin") {
            readTriple(words, false, h.spec.origin.asPointer(), p);
            h.stated.origin = true;
        } else if (key == "point_data") {
            if (!h.stated.dims) throw p.bad(words[0], "comes before DIMENSIONS");
            const std::uint64_t count = std::uint64_t(h.spec.dims.x()) * std::uint64_t(h.spec.dims.y()) * std::uint64_t(h.spec.dims.z());
            std::uint64_t n = 0;
            if (words.size() != 2 || !parseWhole(words[1], n) || n != count)
                throw p.bad(words[0], "expected the point count " + std::to_string(count) + " (DIMENSIONS)");
            return;
        } else if (key == "cell_data") throw p.bad(words[0], "cell data is not supported (weft reads POINT_DATA)");
        else if (key == "field") throw p.bad(words[0], "field data is not supported");
        else throw p.bad(words[0], "unknown keyword in STRUCTURED_POINTS");
    }
}

void readScalars(Lines& lines, VolumeHeader& h, const Parser& p) {
    const auto words = lines.nextWords();
    if (lowerAscii(words[0]) != "scalars") throw p.bad(words[0], "attribute not supported (weft reads one SCALARS array)");
    if (words.size() < 3 || words.size() > 4) throw p.bad(words[0], "expected SCALARS name type [components]");
    h.spec.type = vtkType(words[2], p);
    h.stated.type = true;
    if (words.size() == 4 && words[3] != "1") throw p.bad(words[0], "weft reads one component, not " + quoteValue(words[3]));
    if (lines.startsWith("lookup_table", h.encoding == SampleEncoding::Ascii)) {
        const auto table = lines.nextWords();
        if (table.size() != 2) throw p.bad(table[0], "expected LOOKUP_TABLE name");
    }
}

}  // namespace

VolumeHeader parseVtkImageHeader(std::string_view bytes, bool wholeFile, const std::string& file) {
    const Parser p{file};
    Lines lines(bytes, wholeFile, file);
    if (bytes.empty() || lowerAscii(lines.next()).rfind("# vtk datafile version", 0) != 0)
        throw Error(file + ": not a VTK legacy file (its first line is not '# vtk DataFile Version ...')");
    lines.next();  // the title
    VolumeHeader h;
    const std::string_view format = trimSpace(lines.next());
    const std::string lower = lowerAscii(format);
    if (lower == "ascii") h.encoding = SampleEncoding::Ascii;
    else if (lower != "binary") throw p.bad(format, "expected ASCII or BINARY on the third line");
    const auto dataset = lines.nextWords();
    if (lowerAscii(dataset[0]) != "dataset" || dataset.size() != 2)
        throw p.bad(dataset[0], "expected DATASET STRUCTURED_POINTS");
    if (lowerAscii(dataset[1]) != "structured_points")
        throw p.bad(dataset[1], "weft reads DATASET STRUCTURED_POINTS (image data) only");
    readGeometry(lines, h, p);
    readScalars(lines, h, p);
    h.spec.byteOrder = ByteOrder::Big;  // what VTK writes, whatever the machine
    h.stated.byteOrder = true;
    h.dataOffset = lines.offset();
    h.trailingAllowed = true;
    return h;
}

}  // namespace weft
