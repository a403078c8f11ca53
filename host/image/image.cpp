#include <set>
#include <string>

#include "image/image_check.h"
#include "image/image_io.h"
#include "util/error.h"

namespace tessera {

const ImageChannel* Image::find(const std::string& name) const {
    for (const ImageChannel& c : channels)
        if (c.name == name) return &c;
    return nullptr;
}

namespace detail {

void check_image(const std::filesystem::path& path, const Image& image) {
    auto bad = [&](const std::string& why) {
        throw RuntimeError("cannot write '" + path.string() + "': " + why);
    };
    if (image.width <= 0 || image.height <= 0)
        bad("invalid image size " + std::to_string(image.width) + "x" +
            std::to_string(image.height));
    if (image.channels.empty()) bad("image has no channels");
    const std::size_t pixels =
        static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
    std::set<std::string> names;
    for (const ImageChannel& c : image.channels) {
        if (c.name.empty()) bad("image has a channel with an empty name");
        if (!names.insert(c.name).second) bad("duplicate channel '" + c.name + "'");
        if (c.data.size() != pixels)
            bad("channel '" + c.name + "' has " + std::to_string(c.data.size()) +
                " values, expected " + std::to_string(pixels));
    }
}

}  // namespace detail
}  // namespace tessera
