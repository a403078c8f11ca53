// OpenEXR output and input: every channel as 32-bit float, planar slices.
#include <ImfChannelList.h>
#include <ImfCompression.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfThreading.h>

#include <algorithm>
#include <exception>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>

#include "image/atomic_file.h"
#include "image/image_check.h"
#include "image/image_io.h"
#include "util/error.h"
#include "util/input_limits.h"

namespace tessera {

namespace fs = std::filesystem;

namespace {

// OpenEXR compresses a file's blocks of 16 rows (ZIP) on its global thread pool, which
// has no threads until set: at 512² with six channels one thread took ~160 ms a file,
// two ~90 ms (bench/results/frame_output.md). Each block is compressed alone and the
// blocks are written in order, so the file's bytes do not depend on the thread count.
void use_every_core() {
    static std::once_flag once;
    std::call_once(once, [] {
        try {
            Imf::setGlobalThreadCount(static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
        } catch (const std::exception&) {  // no threads to be had: OpenEXR compresses on the caller's
        }
    });
}

}  // namespace

void write_exr(const fs::path& path, const Image& image) {
    detail::check_image(path, image);
    use_every_core();
    replace_file_atomic(path, [&](const fs::path& temp) {
        try {
            Imf::Header header(image.width, image.height);
            header.compression() = Imf::ZIP_COMPRESSION;
            const Imath::Box2i dw(Imath::V2i(image.x0, image.y0),
                                  Imath::V2i(image.x0 + image.width - 1, image.y0 + image.height - 1));
            header.dataWindow() = dw;
            Imf::FrameBuffer frame;
            for (const ImageChannel& c : image.channels) {
                header.channels().insert(c.name, Imf::Channel(Imf::FLOAT));
                // OpenEXR only reads through the pointer when writing.
                frame.insert(c.name, Imf::Slice::Make(Imf::FLOAT, c.data.data(), dw));
            }
            Imf::OutputFile file(temp.c_str(), header);
            file.setFrameBuffer(frame);
            file.writePixels(image.height);  // from the data window's first row
        } catch (const std::exception& e) {
            throw RuntimeError("cannot write '" + path.string() + "': " + with_path_shown(e.what(), temp, path));
        }
    });
}

Image read_exr(const fs::path& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
        throw InputError("cannot read '" + path.string() + "': " +
                         (fs::exists(path, ec) ? "not a regular file" : "no such file"));
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        Image image;
        // In 64 bits: a hostile header's window can span the whole int range.
        const long long w = static_cast<long long>(dw.max.x) - dw.min.x + 1;
        const long long h = static_cast<long long>(dw.max.y) - dw.min.y + 1;
        if (w <= 0 || h <= 0) throw InputError("cannot read '" + path.string() + "': empty data window");
        const Imf::ChannelList& list = file.header().channels();
        long long channels = 0;
        for (auto it = list.begin(); it != list.end(); ++it) ++channels;
        limits::check_image_size("EXR image", path.string(), w, h, channels);
        image.width = static_cast<int>(w);
        image.height = static_cast<int>(h);
        image.x0 = dw.min.x;
        image.y0 = dw.min.y;
        const std::size_t pixels =
            static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
        for (auto it = list.begin(); it != list.end(); ++it)
            image.channels.push_back({it.name(), std::vector<float>(pixels, 0.0f)});
        Imf::FrameBuffer frame;
        for (ImageChannel& c : image.channels)
            frame.insert(c.name, Imf::Slice::Make(Imf::FLOAT, c.data.data(), dw));
        file.setFrameBuffer(frame);
        file.readPixels(dw.min.y, dw.max.y);
        return image;
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throw InputError("cannot read '" + path.string() + "': not a readable OpenEXR file (" +
                         e.what() + ")");
    }
}

}  // namespace tessera
