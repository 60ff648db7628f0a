#pragma once
// A bounds-checked reader over a .vdb file for the preflight walks
// (vdb_preflight.cpp, vdb_float_tree.cpp): every length is checked against
// the bytes left before it is read or skipped.
#include <cstdint>
#include <istream>
#include <string>

#include "core/base/error.hpp"

namespace weft::vdbwalk {

constexpr std::uint32_t kMaxName = 1 << 20;  // names and type names: a megabyte is already absurd

class Walker {
public:
    Walker(std::istream& in, std::uint64_t size, std::string name) : in_(in), size_(size), name_(std::move(name)) {}

    [[noreturn]] void corrupt(const std::string& what) const {
        throw Error("volume '" + name_ + "': corrupt file (" + what + " at byte " + std::to_string(pos_) + ")");
    }
    const std::string& name() const { return name_; }
    std::uint64_t size() const { return size_; }
    std::uint64_t left() const { return size_ - pos_; }
    std::uint64_t pos() const { return pos_; }

    void bytes(void* out, std::uint64_t n, const char* what) {
        if (n > left()) corrupt(std::string(what) + " runs past the end of the file");
        in_.read(static_cast<char*>(out), std::streamsize(n));
        if (!in_) corrupt(std::string(what) + " cannot be read");
        pos_ += n;
    }
    template <typename T> T value(const char* what) {
        T v{};
        bytes(&v, sizeof v, what);
        return v;
    }
    void skip(std::uint64_t n, const char* what) {
        if (n > left()) corrupt(std::string(what) + " of " + std::to_string(n) + " bytes runs past the end of the file");
        in_.seekg(std::streamoff(n), std::ios::cur);
        pos_ += n;
    }
    void seek(std::int64_t at, const char* what) {
        if (at < 0 || std::uint64_t(at) > size_) corrupt(std::string(what) + " " + std::to_string(at) + " lies outside the file");
        in_.clear();
        in_.seekg(at);
        pos_ = std::uint64_t(at);
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
    std::istream& in_;
    std::uint64_t size_, pos_ = 0;
    std::string name_;
};

}  // namespace weft::vdbwalk
