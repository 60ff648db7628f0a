#pragma once
// The surface model shared by the mesh techniques: Lambertian diffuse plus
// an energy-normalised glossy lobe, either Phong (Lafortune and Willems'
// modified Phong, f = Kd / pi + Ks (e + 2) / (2 pi) cos^e(angle to the
// mirror direction)) or Blinn-Phong (Ks (e + 8) / (8 pi) cos^e(angle between
// normal and half vector)). Kd + Ks is scaled down where it exceeds 1.
#include <algorithm>
#include <cmath>
#include <string>

#include "core/lighting/emitters.hpp"
#include "core/mesh/mesh.hpp"
#include "core/sampling/pixel_sampler.hpp"

namespace weft {

enum class GlossyModel { Phong, Blinn };

struct Brdf {
    Vec3f kd{0, 0, 0}, ks{0, 0, 0};
    float exponent = 1;
    GlossyModel model = GlossyModel::Phong;

    static Brdf of(const Material& m, GlossyModel model = GlossyModel::Phong) {
        Brdf b{m.diffuse, m.glossy, std::max(0.0f, m.exponent), model};
        const float peak = std::max({b.kd.x() + b.ks.x(), b.kd.y() + b.ks.y(), b.kd.z() + b.ks.z()});
        if (peak > 1.0f) b.kd /= peak, b.ks /= peak;
        return b;
    }
    bool glossy() const { return ks.x() > 0 || ks.y() > 0 || ks.z() > 0; }

    static Vec3f reflect(const Vec3f& wo, const Vec3f& n) { return n * (2.0f * n.dot(wo)) - wo; }

    // Glossy lobe value (without Ks) for unit wo, wi on the side of n.
    float lobe(const Vec3f& wo, const Vec3f& wi, const Vec3f& n) const {
        if (model == GlossyModel::Blinn) {
            const Vec3f h = (wo + wi).unitSafe();
            const float c = n.dot(h);
            return c > 0 ? float((exponent + 8) / (8 * M_PI)) * std::pow(c, exponent) : 0.0f;
        }
        const float c = reflect(wo, n).dot(wi);
        return c > 0 ? float((exponent + 2) / (2 * M_PI)) * std::pow(c, exponent) : 0.0f;
    }
    Vec3f eval(const Vec3f& wo, const Vec3f& wi, const Vec3f& n) const {
        Vec3f f = kd * float(1 / M_PI);
        if (glossy()) f += ks * lobe(wo, wi, n);
        return f;
    }
    // Probability of picking the diffuse lobe when sampling.
    float diffuseChance() const {
        const float d = luminance(kd), s = luminance(ks);
        return d + s > 0 ? d / (d + s) : 1.0f;
    }
    float pdf(const Vec3f& wo, const Vec3f& wi, const Vec3f& n) const {
        const float cosI = n.dot(wi);
        if (cosI <= 0) return 0;
        const float pd = diffuseChance();
        float p = pd * cosI * float(1 / M_PI);
        if (pd < 1) p += (1 - pd) * glossyPdf(wo, wi, n);
        return p;
    }
    // Density of the glossy lobe's own sampling: Phong samples around the
    // mirror direction, Blinn samples the half vector around the normal.
    float glossyPdf(const Vec3f& wo, const Vec3f& wi, const Vec3f& n) const {
        if (model == GlossyModel::Blinn) {
            const Vec3f h = (wo + wi).unitSafe();
            const float c = n.dot(h), oh = wo.dot(h);
            return c > 0 && oh > 0 ? float((exponent + 1) / (2 * M_PI)) * std::pow(c, exponent) / (4 * oh) : 0.0f;
        }
        const float c = reflect(wo, n).dot(wi);
        return c > 0 ? float((exponent + 1) / (2 * M_PI)) * std::pow(c, exponent) : 0.0f;
    }
    // A direction for wo (u picks the lobe); below the surface means absorbed.
    Vec3f sample(const Vec3f& wo, const Vec3f& n, float u, float v, float w) const {
        if (u < diffuseChance()) return sampleCosine(n, v, w);
        if (model == GlossyModel::Blinn) return reflect(wo, samplePhongLobe(n, exponent, v, w));
        return samplePhongLobe(reflect(wo, n), exponent, v, w);
    }
    static GlossyModel modelNamed(const std::string& name) { return name == "blinn" ? GlossyModel::Blinn : GlossyModel::Phong; }
};

}  // namespace weft
