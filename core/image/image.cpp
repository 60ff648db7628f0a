#include "core/image/image.hpp"

#include <algorithm>

namespace weft {

Image::Image(int width, int height, std::vector<std::string> channels)
    : width_(width), height_(height), channels_(std::move(channels)),
      data_(zeroedBuffer<float>(static_cast<std::size_t>(width) * height * channels_.size())) {}

Image Image::rgba(int width, int height) { return Image(width, height, {"R", "G", "B", "A"}); }

int Image::channelIndex(const std::string& name) const {
    auto it = std::find(channels_.begin(), channels_.end(), name);
    return it == channels_.end() ? -1 : static_cast<int>(it - channels_.begin());
}

int Image::addChannel(const std::string& name) {
    if (int existing = channelIndex(name); existing >= 0) return existing;
    const std::size_t oldCount = channels_.size();
    FreshBuffer<float> grown = zeroedBuffer<float>(static_cast<std::size_t>(width_) * height_ * (oldCount + 1));
    for (std::size_t p = 0; p < static_cast<std::size_t>(width_) * height_; ++p)
        std::copy_n(data_.begin() + p * oldCount, oldCount, grown.begin() + p * (oldCount + 1));
    data_ = std::move(grown);
    channels_.push_back(name);
    return static_cast<int>(oldCount);
}

}  // namespace weft
