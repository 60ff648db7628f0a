#pragma once
// Self-describing volume files written by the tests themselves: NRRD
// headers, NumPy .npy files and VTK legacy image data around sample bytes.
#include <openvdb/openvdb.h>

#include <cstdint>
#include <string>

namespace weft::test {

inline std::string sizesText(const openvdb::Coord& d, const char* sep = " ") {
    return std::to_string(d.x()) + sep + std::to_string(d.y()) + sep + std::to_string(d.z());
}

// A NRRD0004 header with the given fields (each "name: value\n"), ended by
// the blank line when `attached`.
inline std::string nrrdHeader(const std::string& fields, bool attached = true) {
    return "NRRD0004\n# written by weft's tests\n" + fields + (attached ? "\n" : "");
}

inline std::string nrrdFields(const std::string& type, const openvdb::Coord& dims, const std::string& endian = "little",
                              const std::string& encoding = "raw") {
    return "type: " + type + "\ndimension: 3\nsizes: " + sizesText(dims) + "\nendian: " + endian +
           "\nencoding: " + encoding + "\n";
}

// A .npy file: magic, version, little-endian header length, the dict padded
// with spaces to a multiple of 64 bytes and ended by a newline, then data.
inline std::string npyFile(const std::string& dict, const std::string& data, int major = 1) {
    const std::size_t prefix = major == 1 ? 10 : 12;
    std::string header = dict;
    while ((prefix + header.size() + 1) % 64 != 0) header.push_back(' ');
    header.push_back('\n');
    std::string out("\x93NUMPY", 6);
    out.push_back(char(major));
    out.push_back('\0');
    const std::uint32_t n = std::uint32_t(header.size());
    for (std::size_t i = 0; i < prefix - 8; ++i) out.push_back(char((n >> (8 * i)) & 0xff));
    return out + header + data;
}

inline std::string npyDict(const std::string& descr, bool fortran, const std::string& shape) {
    return "{'descr': '" + descr + "', 'fortran_order': " + (fortran ? "True" : "False") + ", 'shape': " + shape + ", }";
}

// A VTK legacy STRUCTURED_POINTS header up to the line before the samples.
inline std::string vtkHeader(const std::string& format, const openvdb::Coord& dims, const std::string& type,
                             const std::string& geometry = "SPACING 1 1 1\nORIGIN 0 0 0\n") {
    const std::uint64_t n = std::uint64_t(dims.x()) * std::uint64_t(dims.y()) * std::uint64_t(dims.z());
    return "# vtk DataFile Version 3.0\nweft test volume\n" + format + "\nDATASET STRUCTURED_POINTS\nDIMENSIONS " +
           sizesText(dims) + "\n" + geometry + "POINT_DATA " + std::to_string(n) + "\nSCALARS density " + type +
           " 1\nLOOKUP_TABLE default\n";
}

}  // namespace weft::test
