#pragma once
// Slice geometry for slice-based volume rendering (Kraus et al. 2007).
// Slices are shells at equal distance from the eye, t_i = tNear + i *
// spacing along every view ray (in voxels, the volume's index space). For
// an orthographic view they are the paper's view-aligned planes; for a
// perspective view they keep every segment between slices i and j exactly
// (j - i) * spacing long on every ray, so a pre-integration table needs
// only the lengths 1..2^lmax slices.
#include <utility>
#include <vector>

#include "core/base/memory/large_buffer.hpp"
#include "core/scene/camera.hpp"
#include "core/volume/slice/slice_volumes.hpp"
#include "core/volume/volume.hpp"

namespace weft {

struct SliceSetup {
    Vec3d eye;           // index space
    double spacing = 1;  // voxels between slices
    double tNear = 0;    // distance of slice 0 from the eye, voxels
    int imax = 0;        // last slice index, a multiple of 2^lmax
    double t(int i) const { return tNear + spacing * i; }
};

// Slices covering the volume's index box, the last index rounded up to a
// multiple of 2^lmax as the paper requires.
SliceSetup makeSliceSetup(const Camera& camera, const Volume& volume, double spacing, int lmax);
// Slices covering every volume's box, in the reference volume's index space
// (the same setup as above for one volume).
SliceSetup makeSliceSetup(const Camera& camera, const std::vector<SliceVolume>& volumes, double spacing, int lmax);

// One camera ray in index space: its unit direction from the slices' eye
// and, when it crosses the index box, its extent there (distances from the
// eye, voxels).
struct SliceRay {
    Vec3d dir;
    bool inside = false;
    double t0 = 0, t1 = 0;
    // Slices inside the box when every slice moves `offset` spacings further
    // (first > last: none); unclamped to [0, imax].
    std::pair<int, int> slices(const SliceSetup& s, double offset = 0) const;
};
SliceRay sliceRayOf(const Ray& world, const Volume& volume, const SliceSetup& slices);

// The rays of one pyramid level. Pixel (x, y) of level l looks through the
// centre of its 2^l x 2^l block of level-0 pixels.
struct LevelRays {
    int width = 0, height = 0;
    FreshBuffer<Vec3d> dir;         // index space, unit length (all three filled whole in parallel)
    // Slices inside each volume's index box (first > last: none), volume-major:
    // volume k of pixel i at k * pixels + i, so volume 0 is first[i].
    FreshBuffer<int> first, last;
    int index(int x, int y) const { return y * width + x; }
    int firstOf(int k, int i) const { return first[std::size_t(k) * dir.size() + i]; }
    int lastOf(int k, int i) const { return last[std::size_t(k) * dir.size() + i]; }
};

// Level-0 size is padded up to a multiple of 2^lmax; imageWidth/Height
// define the camera's pixel grid.
LevelRays makeLevelRays(const Camera& camera, const Volume& volume, const SliceSetup& slices, int level,
                        int paddedWidth, int paddedHeight, int imageWidth, int imageHeight);
// The same with every volume's slices (volume 0's as above).
LevelRays makeLevelRays(const Camera& camera, const std::vector<SliceVolume>& volumes, const SliceSetup& slices, int level,
                        int paddedWidth, int paddedHeight, int imageWidth, int imageHeight);

}  // namespace weft
