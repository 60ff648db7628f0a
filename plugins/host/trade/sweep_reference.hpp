#pragma once
// The image a sweep's runs are measured against: one file given by the user
// (--reference REF.exr), or (--reference auto) the converged render each
// run's technique declares (TechniqueInfo::reference), rendered once and
// cached under the sweep's folder by a hash of the scene's content and the
// reference's settings, so a later sweep of the same scene reuses it.
#include <map>
#include <string>

#include "core/image/image.hpp"
#include "plugins/host/render_job.hpp"
#include "plugins/host/trade/sweep_plan.hpp"
#include "plugins/host/trade/trade_metrics.hpp"

namespace weft {

class SweepReferences {
public:
    // `spec` is a path or "auto"; `cacheDir` holds the auto references.
    SweepReferences(std::string spec, std::string cacheDir);
    bool automatic() const { return spec_ == "auto"; }
    // Before anything renders: a reference file is read and must match
    // every run's image size; an automatic reference must exist for every
    // run's technique and pass a render's checks.
    void check(const std::vector<SweepRun>& runs, const Scene& scene);
    // The request that renders the reference of `run` on `scene` (auto
    // only). Throws when the run's technique declares no reference. On a
    // scene with meshes it takes at least the largest spp any technique
    // declares: the surfaces' light sampling converges at the path tracer's
    // count, whatever the volume family needs.
    RenderRequest referenceRequest(const SweepRun& run, const Scene& scene) const;
    // Where the reference of `run` is (or will be) cached: a hash of the
    // request and of the files the scene was loaded from.
    std::string cachePath(const SweepRun& run, const Scene& scene) const;
    // The reference image for `run`: read once, or rendered once on `scene`
    // and cached.
    const Image& imageFor(const SweepRun& run, const LoadedScene& scene);
    // The same reference prepared for measuring renders against it, once.
    const TradeReference& measureFor(const SweepRun& run, const LoadedScene& scene);

private:
    std::string ensurePath(const SweepRun& run, const LoadedScene& scene);
    const Image& readOnce(const std::string& path);
    std::string spec_, cacheDir_;
    std::map<std::string, Image> loaded_;  // by path; read once each
    std::map<std::string, TradeReference> prepared_;  // by path
};

}  // namespace weft
