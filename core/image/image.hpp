#pragma once
// Image: a float image with named channels, stored interleaved. The first
// four channels of a render are R, G, B, A (premultiplied, scene-linear);
// AOVs follow with conventional EXR names (Z, N.X, N.Y, N.Z, sampleCount...).
#include <cstddef>
#include <string>
#include <vector>

#include "core/base/memory/large_buffer.hpp"

namespace weft {

class Image {
public:
    Image() = default;
    Image(int width, int height, std::vector<std::string> channels);
    static Image rgba(int width, int height);

    int width() const { return width_; }
    int height() const { return height_; }
    int channelCount() const { return static_cast<int>(channels_.size()); }
    const std::vector<std::string>& channelNames() const { return channels_; }
    // Index of a channel, or -1 when the image has no such channel.
    int channelIndex(const std::string& name) const;
    // Adds a channel (zero-filled) and returns its index; existing data is kept.
    int addChannel(const std::string& name);

    float* pixel(int x, int y) { return data_.data() + offset(x, y); }
    const float* pixel(int x, int y) const { return data_.data() + offset(x, y); }
    float& at(int x, int y, int c) { return data_[offset(x, y) + c]; }
    float at(int x, int y, int c) const { return data_[offset(x, y) + c]; }

    FreshBuffer<float>& data() { return data_; }
    const FreshBuffer<float>& data() const { return data_; }

private:
    std::size_t offset(int x, int y) const {
        return (static_cast<std::size_t>(y) * width_ + x) * channels_.size();
    }
    int width_ = 0;
    int height_ = 0;
    std::vector<std::string> channels_;
    FreshBuffer<float> data_;  // zero where nothing was written
};

}  // namespace weft
