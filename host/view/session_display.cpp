// ViewSession's output: the accumulation at the window's size (upsampled from a budgeted
// frame), screenshots, the error against --reference and the tone-mapped display of each
// AOV (docs/viewer.md §1-3).
#include "view/view_session.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "image/atomic_file.h"
#include "image/resample.h"
#include "image/srgb8.h"
#include "metrics/image_metrics.h"
#include "render/interrupt.h"
#include "render/sequence.h"
#include "scene/loader.h"
#include "util/error.h"

namespace tessera::view {

const char* aov_name(Aov aov) {
    static const char* names[] = {"radiance", "albedo",      "normal",  "depth",   "guidance.SS", "guidance.ID",
                                  "guidance.PM", "sets.SS", "sets.ID", "sets.PM", "error"};
    return names[static_cast<int>(aov)];
}

// An image of the accumulation's size at the window's: bilinear when the budget rendered
// fewer pixels (docs/viewer.md §4 says why not a G-buffer-guided filter).
Image ViewSession::to_window(Image image) const {
    if (image.width == width_ && image.height == height_) return image;
    return resize_bilinear(image, width_, height_);
}

Image ViewSession::accumulation() const {
    Image image = acc_->mean_image(settings_.aovs, true);
    if (settings_.aovs) integrator_->add_aov_channels(image, acc_->passes());
    return to_window(std::move(image));
}

bool ViewSession::reserved(const std::filesystem::path& file) const {
    const auto& r = options_.reserved;
    return std::find(r.begin(), r.end(), same_file(file)) != r.end();
}

std::filesystem::path ViewSession::save_screenshot() {
    if (!acc_ || acc_->passes() == 0) throw RuntimeError("screenshot: no pass accumulated yet");
    std::filesystem::path exr, png;
    for (;; ++screenshots_) {
        exr = frame_output_path(options_.screenshot, screenshots_);
        png = std::filesystem::path(exr).replace_extension(".png");
        if (!reserved(exr) && !reserved(png)) break;
        std::fprintf(stderr, "tessera view: screenshot %d skipped: %s is a file this run reads or writes\n",
                     screenshots_, (reserved(exr) ? exr : png).c_str());
    }
    const Image image = accumulation();
    CommitGroup outputs;  // both files or neither, like render
    outputs.write(exr, [&](const std::filesystem::path& t) { write_exr(t, image); });
    outputs.write(png, [&](const std::filesystem::path& t) { write_png(t, image, exposure_); });
    {
        const InterruptDeferral defer;  // a signal meanwhile must not leave one file renamed
        outputs.commit();
    }
    ++screenshots_;
    std::fprintf(stderr, "tessera view: screenshot of %u %s: %s\n", acc_->passes(),
                 acc_->passes() == 1 ? "pass" : "passes", exr.c_str());
    return exr;
}

Image ViewSession::aov_image() const {
    Image image = acc_->mean_image(true, false);
    integrator_->add_aov_channels(image, std::max(acc_->passes(), 1u));
    return to_window(std::move(image));
}

double ViewSession::reference_error() const {
    if (!reference_ || !acc_ || acc_->passes() == 0) return -1.0;
    const Image image = to_window(acc_->mean_image(false, false));
    return metrics::rel_mse(metrics::rgb_for_metrics(*reference_, options_.reference),
                            metrics::rgb_for_metrics(image, "the view"));
}

void ViewSession::display(std::vector<uint8_t>& rgba) const {
    const size_t n = size_t(width_) * height_;
    rgba.assign(n * 4, 255);
    if (!acc_ || acc_->passes() == 0) return;
    const double scale = std::exp2(double(exposure_));
    // The PNG preview's transfer (clamp, exact sRGB OETF, image/srgb8.h).
    if (aov_ == Aov::Radiance && acc_->width() != width_) {  // a budgeted moving frame: upsampled
        const Image image = to_window(acc_->mean_image(false, false));
        for (int c = 0; c < 3; ++c)
            srgb8_encode(image.find(std::string(1, "RGB"[c]))->data.data(), n, scale, &rgba[c], 4);
        return;
    }
    if (aov_ == Aov::Radiance) {  // from the sums directly: the common case, every frame
        const std::vector<double>& s = acc_->sums();
        const double k = scale / acc_->passes();
        for (int c = 0; c < 3; ++c) srgb8_encode(&s[TS_PASS_RADIANCE + c], TS_PASS_FLOATS, n, k, &rgba[c], 4);
        return;
    }
    const Image image = aov_image();
    auto albedo = [&] {  // sRGB-encoded as the radiance is; a missing channel is black
        for (int c = 0; c < 3; ++c) {
            const ImageChannel* ch = image.find(std::string("albedo.") + "RGB"[c]);
            if (ch) srgb8_encode(ch->data.data(), n, 1.0, &rgba[c], 4);
            else for (size_t p = 0; p < n; ++p) rgba[4 * p + c] = 0;
        }
    };
    auto normals = [&] {  // N mapped from [-1, 1] to [0, 1] linearly
        const ImageChannel* ch[3] = {image.find("N.X"), image.find("N.Y"), image.find("N.Z")};
        for (size_t p = 0; p < n; ++p)
            for (int i = 0; i < 3; ++i) {
                const double v = ch[i] ? ch[i]->data[p] * 0.5 + 0.5 : 0.0;
                rgba[4 * p + i] = static_cast<uint8_t>(std::lround(255.0 * std::clamp(v, 0.0, 1.0)));
            }
    };
    auto put1 = [&](const std::vector<float>& v) {  // scaled by the maximum finite value
        float hi = 0.0f;
        for (float x : v)
            if (std::isfinite(x)) hi = std::max(hi, x);
        for (size_t p = 0; p < n; ++p) {
            const float x = std::isfinite(v[p]) && hi > 0 ? v[p] / hi : 1.0f;
            rgba[4 * p] = rgba[4 * p + 1] = rgba[4 * p + 2] = static_cast<uint8_t>(std::lround(255.0f * x));
        }
    };
    switch (aov_) {
        case Aov::Albedo: albedo(); break;
        case Aov::Normal: normals(); break;
        case Aov::Error: {
            const std::vector<double> map = metrics::rel_se_map(metrics::rgb_for_metrics(*reference_, options_.reference),
                                                                metrics::rgb_for_metrics(image, "the view"));
            std::vector<float> v(map.begin(), map.end());
            for (float& x : v) x = std::sqrt(x);  // relative error, not its square: more of the range visible
            put1(v);
            break;
        }
        default: {
            const ImageChannel* ch = image.find(aov_ == Aov::Depth ? "Z" : aov_name(aov_));
            if (ch) put1(ch->data);
            break;
        }
    }
}

}  // namespace tessera::view
