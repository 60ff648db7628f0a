#pragma once
// A bounds-checked reader over a .vdb file's bytes for the preflight walks
// (vdb_preflight.cpp, vdb_float_tree.cpp): every length is checked against
// the bytes left before it is read or skipped. The bytes lie in memory (the
// file mapped), so skipping a chunk costs no system call.
#include <cstdint>
#include <cstring>
#include <string>

#include "core/base/error.hpp"

namespace weft::vdbwalk {

constexpr std::uint32_t kMaxName = 1 << 20;  // names and type names: a megabyte is already absurd

class Walker {
public:
    Walker(const char* data, std::uint64_t size, std::string name) : data_(data), size_(size), name_(std::move(name)) {}

    [[noreturn]] void corrupt(const std::string& what) const {
        throw Error("volume '" + name_ + "': corrupt file (" + what + " at byte " + std::to_string(pos_) + ")");
    }
    const std::string& name() const { return name_; }
    std::uint64_t size() const { return size_; }
    std::uint64_t left() const { return size_ - pos_; }
    std::uint64_t pos() const { return pos_; }

    void bytes(void* out, std::uint64_t n, const char* what) {
        if (n > left()) corrupt(std::string(what) + " runs past the end of the file");
        if (n > 0) std::memcpy(out, data_ + pos_, n);
        pos_ += n;
    }
    template <typename T> T value(const char* what) {
        T v{};
        bytes(&v, sizeof v, what);
        return v;
    }
    void skip(std::uint64_t n, const char* what) {
        if (n > left()) corrupt(std::string(what) + " of " + std::to_string(n) + " bytes runs past the end of the file");
        pos_ += n;
    }
    void seek(std::int64_t at, const char* what) {
        if (at < 0 || std::uint64_t(at) > size_) corrupt(std::string(what) + " " + std::to_string(at) + " lies outside the file");
        pos_ = std::uint64_t(at);
    }
    // A blosc buffer of `stated` bytes that must decompress to `expected`:
    // its 16-byte header states both sizes (at bytes 12 and 4), and blosc
    // trusts them, reading and writing as far as they say. OpenVDB's
    // compression::bloscCompress pads buffers under 128 bytes to 128
    // (`padded`: that size is accepted too).
    void bloscBuffer(std::uint64_t stated, std::uint64_t expected, const char* what, bool padded = false) {
        if (stated > left()) corrupt(std::string(what) + " of " + std::to_string(stated) + " bytes runs past the end of the file");
        if (stated < 16) corrupt(std::string(what) + " of " + std::to_string(stated) + " bytes, shorter than blosc's header");
        unsigned char header[16];
        bytes(header, sizeof header, what);
        const auto le32 = [&](int at) {
            return std::uint32_t(header[at]) | std::uint32_t(header[at + 1]) << 8 | std::uint32_t(header[at + 2]) << 16 |
                   std::uint32_t(header[at + 3]) << 24;
        };
        const std::uint32_t decompressed = le32(4), compressed = le32(12);
        const bool sized = decompressed == expected || (padded && expected < 128 && decompressed == 128);
        if (!sized || compressed != stated)
            corrupt(std::string(what) + " of " + std::to_string(stated) + " bytes whose header states " + std::to_string(compressed) +
                    " compressed and " + std::to_string(decompressed) + " decompressed where " + std::to_string(expected) +
                    " are expected");
        skip(stated - sizeof header, what);
    }
    // OpenVDB's readString: a 32-bit length, then the characters.
    std::string text(const char* what, std::uint32_t maxLength = kMaxName) {
        const std::uint32_t n = value<std::uint32_t>(what);
        if (n > maxLength || n > left())
            corrupt(std::string(what) + " claims " + std::to_string(n) + " bytes");
        std::string s(n, '\0');
        bytes(s.data(), n, what);
        return s;
    }

private:
    const char* data_;
    std::uint64_t size_, pos_ = 0;
    std::string name_;
};

}  // namespace weft::vdbwalk
