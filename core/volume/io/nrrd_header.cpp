// Written from the NRRD file format specification (teem, NRRD0005).
#include "core/volume/io/nrrd_header.hpp"

#include <algorithm>
#include <map>

#include "core/base/error.hpp"
#include "core/volume/io/header_text.hpp"

namespace weft {

namespace {

using Fields = std::map<std::string, std::string>;

struct Parser {
    const std::string& file;

    Error bad(const std::string& field, std::string_view value, const std::string& why) const {
        return Error(file + ": NRRD field '" + field + "' " + quoteValue(value) + ": " + why);
    }
    Error missing(const std::string& field, const std::string& why) const {
        return Error(file + ": NRRD header has no '" + field + "' field" + why);
    }
};

// Spellings of one field name in the versions of the format.
std::string canonicalField(const std::string& name) {
    static const std::map<std::string, std::string> aliases = {
        {"datafile", "data file"},   {"lineskip", "line skip"},     {"byteskip", "byte skip"},
        {"oldmin", "old min"},       {"oldmax", "old max"},         {"axismins", "axis mins"},
        {"axismaxs", "axis maxs"},   {"centerings", "centers"},     {"sampleunits", "sample units"},
        {"blocksize", "block size"}, {"spacedimension", "space dimension"}};
    const auto it = aliases.find(name);
    return it == aliases.end() ? name : it->second;
}

bool isKnownField(const std::string& name) {
    static const char* const known[] = {
        "dimension", "type", "encoding", "sizes", "endian", "data file", "line skip", "byte skip", "spacings",
        "space", "space dimension", "space directions", "space origin",
        // Descriptive fields weft does not need.
        "content", "min", "max", "old min", "old max", "sample units", "number", "thicknesses", "axis mins",
        "axis maxs", "centers", "labels", "units", "kinds", "space units", "measurement frame", "block size"};
    for (const char* k : known)
        if (name == k) return true;
    return false;
}

// The first line: NRRD0001 .. NRRD0005. Returns the offset of the next line.
std::size_t checkMagic(std::string_view bytes, const std::string& file) {
    const std::size_t eol = bytes.find('\n');
    std::string_view line = bytes.substr(0, eol == std::string_view::npos ? bytes.size() : eol);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.size() != 8 || line.substr(0, 7) != "NRRD000" || line[7] < '1' || line[7] > '5')
        throw Error(file + ": not a NRRD file (its first line is not NRRD0001 .. NRRD0005)");
    if (eol == std::string_view::npos) throw Error(file + ": NRRD header ends after its first line");
    return eol + 1;
}

// Splits the header into fields; sets `end` to the offset after the blank
// line that ends it, or to bytes.size() when the file ends first.
Fields readFields(std::string_view bytes, bool wholeFile, const std::string& file, std::size_t& end, bool& blankLine) {
    Fields fields;
    std::size_t pos = checkMagic(bytes, file);
    int lineNo = 1;
    blankLine = false;
    while (pos < bytes.size()) {
        ++lineNo;
        const std::string_view line = nextHeaderLine(bytes, pos, wholeFile, file, "NRRD");
        if (line.empty()) {
            blankLine = true;
            break;
        }
        if (line.front() == '#') continue;
        const std::size_t colon = line.find(": ");
        const std::size_t keyValue = line.find(":=");
        if (keyValue != std::string_view::npos && (colon == std::string_view::npos || keyValue < colon)) continue;
        if (colon == std::string_view::npos)
            throw Error(file + ": NRRD header line " + std::to_string(lineNo) + " " + quoteValue(line) +
                        " is not 'field: value'");
        const std::string name = canonicalField(std::string(line.substr(0, colon)));
        if (!isKnownField(name)) throw Error(file + ": " + quoteValue(name) + " is not a NRRD field (line " + std::to_string(lineNo) + ")");
        if (!fields.emplace(name, std::string(trimSpace(line.substr(colon + 2)))).second)
            throw Error(file + ": NRRD field '" + name + "' is given twice");
    }
    end = pos;
    return fields;
}

struct TypeSpelling {
    const char* name;
    RawType type;
};

RawType nrrdType(const std::string& value, const Parser& p) {
    static const TypeSpelling spellings[] = {
        {"signed char", RawType::I8},  {"int8", RawType::I8},  {"int8_t", RawType::I8},
        {"uchar", RawType::U8},  {"unsigned char", RawType::U8},  {"uint8", RawType::U8},  {"uint8_t", RawType::U8},
        {"short", RawType::I16}, {"short int", RawType::I16}, {"signed short", RawType::I16},
        {"signed short int", RawType::I16}, {"int16", RawType::I16}, {"int16_t", RawType::I16},
        {"ushort", RawType::U16}, {"unsigned short", RawType::U16}, {"unsigned short int", RawType::U16},
        {"uint16", RawType::U16}, {"uint16_t", RawType::U16},
        {"int", RawType::I32}, {"signed int", RawType::I32}, {"int32", RawType::I32}, {"int32_t", RawType::I32},
        {"uint", RawType::U32}, {"unsigned int", RawType::U32}, {"uint32", RawType::U32}, {"uint32_t", RawType::U32},
        {"float", RawType::F32}, {"double", RawType::F64}};
    for (const TypeSpelling& s : spellings)
        if (value == s.name) return s.type;
    static const char* const unsupported[] = {
        "longlong", "long long", "long long int", "signed long long", "signed long long int", "int64", "int64_t",
        "ulonglong", "unsigned long long", "unsigned long long int", "uint64", "uint64_t", "block"};
    for (const char* u : unsupported)
        if (value == u) throw p.bad("type", value, "not supported (weft reads 8-, 16- and 32-bit integers, float and double)");
    throw p.bad("type", value, "not a NRRD type");
}

std::int64_t parseCount(const std::string& field, std::string_view text, std::int64_t lo, std::int64_t hi, const Parser& p) {
    std::int64_t v;
    if (!parseWhole(text, v) || v < lo || v > hi)
        throw p.bad(field, text, "expected an integer from " + std::to_string(lo) + " to " + std::to_string(hi));
    return v;
}

openvdb::math::Coord parseSizes(const std::string& value, const Parser& p) {
    const auto parts = splitWhitespace(value);
    if (parts.size() != 3) throw p.bad("sizes", value, "expected 3 sizes");
    openvdb::math::Coord dims;
    for (int i = 0; i < 3; ++i) dims[i] = int(parseCount("sizes", parts[i], 1, kMaxRawDim, p));
    return dims;
}

openvdb::math::Vec3d parseSpacings(const std::string& value, const Parser& p) {
    const auto parts = splitWhitespace(value);
    openvdb::math::Vec3d s;
    if (parts.size() != 3) throw p.bad("spacings", value, "expected 3 spacings");
    for (int i = 0; i < 3; ++i)
        if (!parseFinite(parts[i], s[i]) || !(s[i] > 0)) throw p.bad("spacings", value, "expected 3 positive finite numbers");
    return s;
}

// "(x,y,z)" with optional spaces; false when it is not one.
bool parseVector(std::string_view text, openvdb::math::Vec3d& v) {
    text = trimSpace(text);
    if (text.size() < 2 || text.front() != '(' || text.back() != ')') return false;
    const std::vector<std::string> parts = splitOn(text.substr(1, text.size() - 2), ',');
    if (parts.size() != 3) return false;
    for (int i = 0; i < 3; ++i)
        if (!parseFinite(trimSpace(parts[i]), v[i])) return false;
    return true;
}

// Three vectors, each the world step along one index axis.
openvdb::math::Mat3d parseDirections(const std::string& value, const Parser& p) {
    std::vector<std::string_view> vectors;
    std::size_t pos = 0;
    while (pos < value.size()) {
        const std::size_t open = value.find_first_not_of(" \t", pos);
        if (open == std::string::npos) break;
        const std::size_t close = value[open] == '(' ? value.find(')', open) : value.find_first_of(" \t", open);
        const std::size_t stop = close == std::string::npos ? value.size() : close + (value[open] == '(' ? 1 : 0);
        vectors.push_back(std::string_view(value).substr(open, stop - open));
        pos = stop;
        if (vectors.size() > 3) break;  // too many either way
    }
    if (vectors.size() != 3) throw p.bad("space directions", value, "expected 3 vectors (x,y,z)");
    openvdb::math::Mat3d m;
    for (int c = 0; c < 3; ++c) {
        openvdb::math::Vec3d v;
        if (vectors[c] == "none") throw p.bad("space directions", value, "an axis without a direction ('none') is not a spatial axis");
        if (!parseVector(vectors[c], v)) throw p.bad("space directions", value, "expected 3 vectors (x,y,z) of finite numbers");
        for (int r = 0; r < 3; ++r) m(r, c) = v[r];
    }
    return m;
}

void checkSpace(const Fields& f, const Parser& p) {
    static const char* const spaces[] = {"right-anterior-superior", "ras", "left-anterior-superior", "las",
                                         "left-posterior-superior", "lps", "scanner-xyz", "3d-right-handed",
                                         "3d-left-handed"};
    if (f.count("space") && f.count("space dimension"))
        throw p.bad("space dimension", f.at("space dimension"), "a header gives 'space' or 'space dimension', not both");
    if (f.count("space")) {
        const std::string v = lowerAscii(f.at("space"));
        bool ok = false;
        for (const char* s : spaces) ok = ok || v == s;
        if (!ok) throw p.bad("space", f.at("space"), "weft reads 3-D spaces (RAS, LAS, LPS, scanner-xyz, 3D-right-handed, 3D-left-handed)");
    }
    if (f.count("space dimension") && f.at("space dimension") != "3")
        throw p.bad("space dimension", f.at("space dimension"), "weft reads 3-D spaces");
}

// Spacing and orientation: "space directions" (each axis' world step) or
// "spacings" (axis-aligned), never both.
void readGeometry(const Fields& f, VolumeHeader& h, const Parser& p) {
    checkSpace(f, p);
    if (f.count("spacings") && f.count("space directions"))
        throw p.bad("spacings", f.at("spacings"), "a header gives 'spacings' or 'space directions', not both");
    if (f.count("spacings")) {
        h.spec.spacing = parseSpacings(f.at("spacings"), p);
        h.stated.spacing = true;
    }
    if (f.count("space directions")) {
        const openvdb::math::Mat3d steps = parseDirections(f.at("space directions"), p);
        checkDirection(steps, p.file + ": NRRD field 'space directions' " + quoteValue(f.at("space directions")));
        for (int c = 0; c < 3; ++c) {
            const double length = openvdb::math::Vec3d(steps(0, c), steps(1, c), steps(2, c)).length();
            h.spec.spacing[c] = length;
            for (int r = 0; r < 3; ++r) h.spec.direction(r, c) = steps(r, c) / length;
        }
        h.stated.spacing = h.stated.direction = true;
    }
    if (f.count("space origin")) {
        if (!parseVector(f.at("space origin"), h.spec.origin))
            throw p.bad("space origin", f.at("space origin"), "expected (x,y,z) of finite numbers");
        h.stated.origin = true;
    }
}

void readEncoding(const Fields& f, NrrdHeader& n, const Parser& p) {
    if (!f.count("encoding")) throw p.missing("encoding", "");
    const std::string& e = f.at("encoding");
    if (e == "raw") n.volume.encoding = SampleEncoding::Raw;
    else if (e == "gzip" || e == "gz") n.volume.encoding = SampleEncoding::Gzip;
    else if (e == "bzip2" || e == "bz2" || e == "ascii" || e == "text" || e == "txt" || e == "hex")
        throw p.bad("encoding", e, "not supported (weft reads raw and gzip)");
    else throw p.bad("encoding", e, "not a NRRD encoding");
}

void readByteOrder(const Fields& f, VolumeHeader& h, const Parser& p) {
    if (f.count("endian")) {
        const std::string& e = f.at("endian");
        if (e == "little") h.spec.byteOrder = ByteOrder::Little;
        else if (e == "big") h.spec.byteOrder = ByteOrder::Big;
        else throw p.bad("endian", e, "expected little or big");
        h.stated.byteOrder = true;
    } else if (rawTypeBytes(h.spec.type) > 1) {
        throw p.missing("endian", " (needed for samples of more than one byte)");
    }
    if (rawTypeBytes(h.spec.type) == 1) h.stated.byteOrder = true;  // one byte has no order to contradict
}

void readDataPlacement(const Fields& f, NrrdHeader& n, const Parser& p) {
    if (f.count("data file")) {
        const std::string& d = f.at("data file");
        if (d.empty()) throw p.bad("data file", d, "names no file");
        if (d.rfind("LIST", 0) == 0 || d.find('%') != std::string::npos)
            throw p.bad("data file", d, "several data files are not supported");
        n.dataFile = d;
    }
    if (f.count("line skip")) n.lineSkip = parseCount("line skip", f.at("line skip"), 0, 1 << 20, p);
    if (f.count("byte skip")) n.byteSkip = parseCount("byte skip", f.at("byte skip"), -1, std::int64_t(kMaxRawBytes), p);
    if (n.byteSkip == -1 && n.volume.encoding != SampleEncoding::Raw)
        throw p.bad("byte skip", "-1", "only with raw encoding (the samples end the file)");
}

}  // namespace

NrrdHeader parseNrrdHeader(std::string_view bytes, bool wholeFile, const std::string& file) {
    const Parser p{file};
    std::size_t end = 0;
    bool blankLine = false;
    const Fields f = readFields(bytes, wholeFile, file, end, blankLine);
    NrrdHeader n;
    VolumeHeader& h = n.volume;
    if (!f.count("dimension")) throw p.missing("dimension", "");
    if (f.at("dimension") != "3")
        throw p.bad("dimension", f.at("dimension"), "weft reads 3-dimensional scalar volumes only");
    if (!f.count("type")) throw p.missing("type", "");
    h.spec.type = nrrdType(f.at("type"), p);
    if (!f.count("sizes")) throw p.missing("sizes", "");
    h.spec.dims = parseSizes(f.at("sizes"), p);
    h.stated.dims = h.stated.type = true;
    readEncoding(f, n, p);
    readByteOrder(f, h, p);
    readGeometry(f, h, p);
    readDataPlacement(f, n, p);
    if (n.dataFile.empty() && !blankLine)
        throw Error(file + ": NRRD header names no 'data file' and is not ended by a blank line before its samples");
    h.dataOffset = n.dataFile.empty() ? end : 0;
    return n;
}

}  // namespace weft
