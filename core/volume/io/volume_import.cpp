#include "core/volume/io/volume_import.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/base/error.hpp"
#include "core/base/files/input_file.hpp"
#include "core/volume/io/header_text.hpp"
#include "core/volume/io/npy_header.hpp"
#include "core/volume/io/nrrd_header.hpp"
#include "core/volume/io/vtk_image_header.hpp"

namespace fs = std::filesystem;

namespace weft {

std::string_view nextHeaderLine(std::string_view bytes, std::size_t& pos, bool wholeFile, const std::string& file,
                                const char* format) {
    std::size_t eol = bytes.find('\n', pos);
    if (eol == std::string_view::npos) {
        if (!wholeFile) throw Error(file + ": " + format + " header does not end within " + std::to_string(kMaxHeaderBytes) + " bytes");
        eol = bytes.size();
    }
    std::string_view line = bytes.substr(pos, eol - pos);
    pos = std::min(eol + 1, bytes.size());
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return line;
}

std::string headerDescription(const RawVolumeSpec& spec) {
    return "the header's " + std::to_string(spec.dims.x()) + "x" + std::to_string(spec.dims.y()) + "x" +
           std::to_string(spec.dims.z()) + " " + rawTypeName(spec.type);
}

namespace {

// The options, checked before any file is opened.
struct ParsedOptions {
    std::optional<openvdb::math::Coord> dims;
    std::optional<RawType> type;
    std::optional<ByteOrder> byteOrder;
    std::optional<openvdb::math::Vec3d> spacing, origin;
    std::optional<openvdb::math::Mat3d> direction;
    std::optional<double> background;
};

ParsedOptions parseOptions(const ImportOptions& o) {
    ParsedOptions p;
    if (o.dims) p.dims = parseRawDims(*o.dims);
    if (o.type) p.type = parseRawType(*o.type);
    if (o.endian) p.byteOrder = parseByteOrder(*o.endian);
    if (o.spacing) p.spacing = parseRawSpacing(*o.spacing);
    if (o.origin) p.origin = parseRawOrigin(*o.origin);
    if (o.direction) p.direction = parseRawDirection(*o.direction);
    if (o.background) p.background = parseRawBackground(*o.background);
    if (o.grid.empty()) throw Error("--grid: the grid name must not be empty");
    return p;
}

std::string formatOf(const std::string& path) {
    const std::string ext = lowerAscii(fs::path(path).extension().string());
    if (ext == ".nrrd" || ext == ".nhdr") return "nrrd";
    if (ext == ".npy") return "npy";
    if (ext == ".vtk") return "vtk";
    if (ext == ".vti")
        throw Error(path + ": VTK XML image data (.vti) is not supported; save it as legacy .vtk (BINARY or ASCII) or .nrrd");
    return "raw";
}

// Up to `limit` bytes from the start of the file; whole: that was all of it.
std::string readHead(const std::string& path, std::size_t limit, bool& whole) {
    requireRegularFile(path, "volume");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot open: " + std::strerror(errno));
    std::string head(limit, '\0');
    in.read(head.data(), std::streamsize(limit));
    head.resize(std::size_t(in.gcount()));
    whole = head.size() < limit;
    return head;
}

bool near(double a, double b) { return std::fabs(a - b) <= 1e-9 * std::max(1.0, std::max(std::fabs(a), std::fabs(b))); }

std::string vecText(const double* v, int n) {
    std::string out;
    char buf[32];
    for (int i = 0; i < n; ++i) {
        std::snprintf(buf, sizeof buf, "%s%.10g", i ? "," : "", v[i]);
        out += buf;
    }
    return out;
}

Error contradiction(const std::string& option, const std::string& text, const std::string& path, const std::string& header) {
    return Error(option + " '" + text + "' contradicts the header of " + path + " (" + header + ")");
}

// Fills what the header leaves open with the options; an option that
// disagrees with what the header states is an error.
void mergeOptions(VolumeHeader& h, const ParsedOptions& p, const ImportOptions& o, const std::string& path) {
    RawVolumeSpec& s = h.spec;
    const StatedFields& st = h.stated;
    if (p.dims && st.dims && *p.dims != s.dims)
        throw contradiction("--dims", *o.dims, path, "sizes " + std::to_string(s.dims.x()) + "," + std::to_string(s.dims.y()) + "," + std::to_string(s.dims.z()));
    if (p.type && st.type && *p.type != s.type) throw contradiction("--type", *o.type, path, rawTypeName(s.type));
    if (p.byteOrder && st.byteOrder && rawTypeBytes(s.type) > 1 && *p.byteOrder != s.byteOrder)
        throw contradiction("--endian", *o.endian, path, s.byteOrder == ByteOrder::Big ? "big" : "little");
    if (p.spacing && st.spacing && !(near((*p.spacing)[0], s.spacing[0]) && near((*p.spacing)[1], s.spacing[1]) && near((*p.spacing)[2], s.spacing[2])))
        throw contradiction("--spacing", *o.spacing, path, "spacing " + vecText(s.spacing.asPointer(), 3));
    if (p.origin && st.origin && !(near((*p.origin)[0], s.origin[0]) && near((*p.origin)[1], s.origin[1]) && near((*p.origin)[2], s.origin[2])))
        throw contradiction("--origin", *o.origin, path, "origin " + vecText(s.origin.asPointer(), 3));
    if (p.direction && st.direction) {
        bool same = true;
        for (int i = 0; i < 9; ++i) same = same && near(p.direction->asPointer()[i], s.direction.asPointer()[i]);
        if (!same) throw contradiction("--direction", *o.direction, path, "direction " + vecText(s.direction.asPointer(), 9));
    }
    if (p.dims) s.dims = *p.dims;
    if (p.type) s.type = *p.type;
    if (p.byteOrder) s.byteOrder = *p.byteOrder;
    if (p.spacing) s.spacing = *p.spacing;
    if (p.origin) s.origin = *p.origin;
    if (p.direction) s.direction = *p.direction;
    if (p.background) s.background = *p.background;
    s.gridName = o.grid;
}

// The offset after `count` more lines of the file from `offset` on.
std::uint64_t skipLines(const std::string& path, std::uint64_t offset, std::int64_t count) {
    std::ifstream in(path, std::ios::binary);
    in.seekg(std::streamoff(offset));
    std::streambuf& buf = *in.rdbuf();
    for (std::int64_t n = 0; n < count;) {
        const int c = buf.sbumpc();
        if (c == std::char_traits<char>::eof())
            throw Error(path + ": NRRD 'line skip' " + std::to_string(count) + ": the data file ends after " + std::to_string(n) + " lines");
        ++offset;
        n += c == '\n';
    }
    return offset;
}

VolumeImport planNrrd(const std::string& path, const ParsedOptions& p, const ImportOptions& o) {
    bool whole = false;
    const std::string head = readHead(path, kMaxHeaderBytes + 1, whole);
    NrrdHeader n = parseNrrdHeader(head, whole, path);
    VolumeImport im{"nrrd", {}, {}};
    mergeOptions(n.volume, p, o, path);
    im.spec = n.volume.spec;
    RawDataSource& d = im.data;
    d.path = path;
    if (!n.dataFile.empty()) {
        const fs::path file(n.dataFile);
        d.path = (file.is_absolute() ? file : fs::path(path).parent_path() / file).string();
        requireRegularFile(d.path, path + ": its data file");
    }
    d.encoding = n.volume.encoding;
    d.offset = n.volume.dataOffset;
    if (n.lineSkip > 0) d.offset = skipLines(d.path, d.offset, n.lineSkip);
    if (n.byteSkip == -1) {
        std::error_code ec;
        const std::uint64_t size = fs::file_size(d.path, ec);
        const std::uint64_t needed = rawByteCount(im.spec);
        if (ec || size < d.offset + needed)
            throw Error(d.path + ": holds " + std::to_string(ec ? 0 : size) + " bytes, fewer than " +
                        headerDescription(im.spec) + " needs (" + std::to_string(needed) + ") after " + std::to_string(d.offset));
        d.offset = size - needed;
    } else if (d.encoding == SampleEncoding::Gzip) {
        d.skipDecoded = std::uint64_t(n.byteSkip);
    } else {
        d.offset += std::uint64_t(n.byteSkip);
    }
    d.describedBy = headerDescription(im.spec);
    return im;
}

VolumeImport planHeader(const std::string& format, const std::string& path, const ParsedOptions& p, const ImportOptions& o) {
    bool whole = false;
    const std::string head = readHead(path, kMaxHeaderBytes + 16, whole);
    VolumeHeader h = format == "npy" ? parseNpyHeader(head, path) : parseVtkImageHeader(head, whole, path);
    mergeOptions(h, p, o, path);
    VolumeImport im{format, h.spec, {}};
    im.data.path = path;
    im.data.offset = h.dataOffset;
    im.data.encoding = h.encoding;
    im.data.trailingAllowed = h.trailingAllowed;
    im.data.describedBy = headerDescription(h.spec);
    return im;
}

VolumeImport planRaw(const std::string& path, const ParsedOptions& p, const ImportOptions& o) {
    if (!p.dims || !p.type)
        throw Error(path + ": a headerless volume needs --dims and --type (.nrrd, .nhdr, .npy and .vtk files describe themselves)");
    VolumeHeader h;
    mergeOptions(h, p, o, path);
    VolumeImport im{"raw", h.spec, {}};
    im.data.path = path;
    im.data.encoding = endsWithText(path, ".gz") ? SampleEncoding::Gzip : SampleEncoding::Raw;
    return im;
}

}  // namespace

VolumeImport planImport(const std::string& path, const ImportOptions& options) {
    const ParsedOptions parsed = parseOptions(options);
    const std::string format = formatOf(path);
    VolumeImport im = format == "raw"    ? planRaw(path, parsed, options)
                      : format == "nrrd" ? planNrrd(path, parsed, options)
                                         : planHeader(format, path, parsed, options);
    try {
        rawByteCount(im.spec);  // overflow and absurd sizes
    } catch (const Error& e) {
        if (format == "raw") throw;
        throw Error(path + ": " + e.what());
    }
    return im;
}

}  // namespace weft
