// A single-scattering configuration with a value by quadrature, shared by the path
// tracer's and IGI's media tests: a camera ray along +z through a slab (0 <= z <= 2) of
// medium lit by a small emitter inside it, nothing else in view.
#pragma once
#include <cmath>

#include "scene/scene.h"
#include "support/test_scenes.h"

namespace tessera::test {

constexpr float kSingleScatterSigmaA[3] = {0.05f, 0.2f, 0.6f};
constexpr float kSingleScatterSigmaS = 0.3f, kSingleScatterG = 0.3f;

/// The scene: emitter 0.1 × 0.1 at x = light_x (0.6 unless given) facing -x, radiance 1;
/// camera at z = -1 looking +z with a 0.2° field of view (8 × 8 pixels); medium in the
/// box [-5, 5] × [-5, 5] × [0, 2]. A light near the ray (small light_x) lights a short
/// stretch of it: the case equiangular sampling is for.
inline Scene single_scatter_scene(float light_x = 0.6f) {
    Scene s;
    s.name = "single-scatter";
    const uint32_t light = add_material(s, glm::vec3(0.0f), glm::vec3(1.0f));
    add_quad(s, {light_x, -0.05f, 0.95f}, {0, 0, 0.1f}, {0, 0.1f, 0}, light);  // faces -x
    s.camera.position = {0, 0, -1};
    s.camera.look_at = {0, 0, 0};
    s.camera.vfov_deg = 0.2f;
    s.camera.width = s.camera.height = 8;
    s.has_medium = true;
    s.medium.sigma_a = glm::vec3(kSingleScatterSigmaA[0], kSingleScatterSigmaA[1], kSingleScatterSigmaA[2]);
    s.medium.sigma_s = glm::vec3(kSingleScatterSigmaS);
    s.medium.g = kSingleScatterG;
    s.medium.bounded = true;
    s.medium.box_min = {-5, -5, 0};
    s.medium.box_max = {5, 5, 2};
    return s;
}

/// Single scattering along the camera ray, by quadrature (4000 steps along the ray,
/// 48 × 48 over the emitter; converged to < 0.01%):
///   L = ∫ sigma_s e^{-sigma_t (t - t_in)} ∫_A Le p(cos θ) cos θ_l / r² e^{-sigma_t r} dA dt.
inline double single_scatter_integral(double sigma_s, double sigma_t, double g, double lx = 0.6) {
    const double t_in = 1.0, t_out = 3.0;  // camera at z = -1, slab 0 <= z <= 2 on the axis
    const int nt = 4000, na = 48;
    const double half = 0.05, lz = 1.0;  // light: x = lx, |y| and |z - 1| <= 0.05
    double sum = 0.0;
    for (int i = 0; i < nt; ++i) {
        const double t = t_in + (i + 0.5) * (t_out - t_in) / nt, z = t - 1.0;
        double inner = 0.0;
        for (int a = 0; a < na; ++a)
            for (int b = 0; b < na; ++b) {
                const double y = -half + (a + 0.5) * 2 * half / na, zl = lz - half + (b + 0.5) * 2 * half / na;
                const double dx = lx, dy = y, dz = zl - z, r = std::sqrt(dx * dx + dy * dy + dz * dz);
                const double cos_theta = dz / r;  // between the camera ray (+z) and the light direction
                const double cos_l = dx / r;      // light faces -x
                const double den = 1 + g * g - 2 * g * cos_theta;
                const double phase = (1 - g * g) / (4 * M_PI * den * std::sqrt(den));
                inner += phase * cos_l / (r * r) * std::exp(-sigma_t * r);
            }
        inner *= (2 * half) * (2 * half) / (na * na);
        sum += sigma_s * std::exp(-sigma_t * (t - t_in)) * inner;
    }
    return sum * (t_out - t_in) / nt;
}


/// The value for colour channel c of single_scatter_scene(light_x).
inline double single_scatter_reference(int c, double light_x = 0.6) {
    return single_scatter_integral(kSingleScatterSigmaS, kSingleScatterSigmaA[c] + kSingleScatterSigmaS, kSingleScatterG,
                                   light_x);
}

}  // namespace tessera::test
