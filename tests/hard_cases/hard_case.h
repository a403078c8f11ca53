// The hard-case suite (tests/README.md, "Hard cases"): each case is a scene builder run on every method in
// kHardCaseMethods (every row of the method table) and every backend in kHardCaseBackends: a
// new method runs every case on both backends with no edit here. tests/README.md lists the
// cases, the methods and backends they run and the checks they make.
#pragma once
#include <algorithm>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace tessera::test {

/// What a method computes, which decides the energy bound a case may assert.
enum class Transport {
    Direct,  ///< emission + one bounce of direct light: L <= Le_max (1 + rho_max)
    Global,  ///< all bounces:                              L <= Le_max / (1 - rho_max)
};

struct HardCaseMethod {
    const char* name;
    Method method;
    Transport transport;
    bool media;  ///< the method renders participating media (else it ignores them)
    /// Media through VPLs and ray lights (the igi family): a phase function peaked near
    /// |g| = 1 puts the light it scatters into a few links' spikes, which they cannot carry
    /// (docs/igi.md §6: 0.59-0.63 of pt's radiance in the foggy Cornell box at g = ±0.999; a
    /// scattering furnace renders 0.64-0.79 of its radiance there, extreme_values_test.cpp).
    /// There the suite asks only the energy bound; at moderate g the furnace value.
    bool peaked_phase_limit = false;
};

/// Every method the hard cases run: every row of the method table (integrators/method.h),
/// so a new method runs every case without an edit here.
inline std::vector<HardCaseMethod> hard_case_methods() {
    std::vector<HardCaseMethod> methods;
    for (const MethodInfo& m : method_table())
        methods.push_back({m.name, m.method, m.global ? Transport::Global : Transport::Direct, m.media,
                           m.igi_family});
    return methods;
}
inline const std::vector<HardCaseMethod> kHardCaseMethods = hard_case_methods();

inline const std::vector<BackendKind> kHardCaseBackends = {BackendKind::Embree, BackendKind::OpenCL};

struct HardCaseParam {
    HardCaseMethod method;
    BackendKind backend;
};

inline void PrintTo(const HardCaseParam& p, std::ostream* os) {
    *os << p.method.name << " on " << (p.backend == BackendKind::Embree ? "embree" : "opencl");
}

inline std::vector<HardCaseParam> hard_case_params() {
    std::vector<HardCaseParam> out;
    for (const auto& m : kHardCaseMethods)
        for (BackendKind b : kHardCaseBackends) out.push_back({m, b});
    return out;
}

inline std::string hard_case_name(const ::testing::TestParamInfo<HardCaseParam>& info) {
    std::string method = info.param.method.name;  // gtest names allow [A-Za-z0-9_] only
    std::replace(method.begin(), method.end(), '-', '_');
    return method + "_" +
           (info.param.backend == BackendKind::Embree ? "Embree" : "OpenCL");
}

/// Upper bound on the radiance anywhere in a scene whose emitters have radiance at most
/// `le` (per channel) and whose surfaces reflect at most `rho` < 1 (Lambertian, so the
/// hemispherical reflectance is the albedo), in vacuum or in a non-emitting medium whose
/// single-scattering albedo is at most 1:
///   Global: L = Le + T L with ||T||_inf <= rho, so ||L||_inf <= Le / (1 - rho)
///           (Neumann series; a medium only attenuates or redistributes, ||T|| <= rho
///           still holds for the surface-to-surface operator including media).
///   Direct: L = Le + (rho / pi) ∫ Le_i cos dω <= Le + rho Le (∫ cos dω = pi).
inline double radiance_bound(Transport t, double le, double rho) {
    return t == Transport::Direct ? le * (1.0 + rho) : le / (1.0 - rho);
}

class HardCase : public ::testing::TestWithParam<HardCaseParam> {
protected:
    const HardCaseMethod& method() const { return GetParam().method; }
    BackendKind backend() const { return GetParam().backend; }

    RenderSettings settings(uint32_t spp, uint32_t seed = 1) const {
        RenderSettings rs;
        rs.method = method().method;
        rs.spp = spp;
        rs.seed = seed;
        rs.aovs = true;
        return rs;
    }

    Image render(const Scene& s, uint32_t spp, uint32_t seed = 1) const {
        return render_with(backend(), s, settings(spp, seed));
    }
};

/// Largest value of a channel.
inline float channel_max(const Image& img, const char* name) {
    float m = -INFINITY;
    for (float v : img.find(name)->data) m = std::fmax(m, v);
    return m;
}

/// Largest value over R, G, B.
inline float radiance_max(const Image& img) {
    return std::fmax(channel_max(img, "R"), std::fmax(channel_max(img, "G"), channel_max(img, "B")));
}

/// Mean over R, G, B and pixels.
inline double radiance_mean(const Image& img) {
    return (channel_mean(img, "R") + channel_mean(img, "G") + channel_mean(img, "B")) / 3.0;
}

/// Standard error of radiance_mean(img), from the per-pixel variance of the mean
/// (variance.R/G/B), treating pixels as independent (they are: per-pixel seeds).
inline double radiance_mean_stderr(const Image& img) {
    double v = 0.0;
    size_t n = 0;
    for (const char* c : {"variance.R", "variance.G", "variance.B"})
        for (float x : img.find(c)->data) {
            v += x;
            ++n;
        }
    return std::sqrt(v) / double(n);
}

/// Scales and translates every position (and the camera) by p -> s p + t.
inline Scene transformed(Scene s, float scale, glm::vec3 t) {
    for (auto& p : s.positions) p = p * scale + t;
    s.camera.position = s.camera.position * scale + t;
    s.camera.look_at = s.camera.look_at * scale + t;
    if (s.medium.bounded) {
        s.medium.box_min = s.medium.box_min * scale + t;
        s.medium.box_max = s.medium.box_max * scale + t;
    }
    s.medium.sigma_a /= scale;  // per scene unit: optical depths stay the same
    s.medium.sigma_s /= scale;
    return s;
}

}  // namespace tessera::test
