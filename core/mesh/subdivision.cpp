// Catmull-Clark subdivision through OpenSubdiv Far: the cage becomes a
// TopologyDescriptor (with crease edges and corner vertices), a
// TopologyRefiner refines it uniformly, and a PrimvarRefiner carries the
// positions down; the last level's quads are triangulated. Material ids
// follow each face's base face.
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <memory>

#include "core/base/error.hpp"
#include "core/mesh/mesh.hpp"

namespace weft {

namespace {

using namespace OpenSubdiv;

// The vertex type PrimvarRefiner interpolates.
struct RefineVertex {
    float p[3] = {0, 0, 0};
    void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0; }
    void AddWithWeight(const RefineVertex& src, float w) {
        p[0] += w * src.p[0], p[1] += w * src.p[1], p[2] += w * src.p[2];
    }
};

std::unique_ptr<Far::TopologyRefiner> makeRefiner(const PolyMesh& mesh, std::vector<int>& creasePairs,
                                                  std::vector<float>& creaseWeights, std::vector<int>& cornerIds,
                                                  std::vector<float>& cornerWeights) {
    for (const Crease& c : mesh.creases) creasePairs.push_back(c.v0), creasePairs.push_back(c.v1), creaseWeights.push_back(c.sharpness);
    for (const auto& [v, s] : mesh.corners) cornerIds.push_back(v), cornerWeights.push_back(s);
    Far::TopologyDescriptor desc;
    desc.numVertices = int(mesh.positions.size());
    desc.numFaces = mesh.faceCount();
    desc.numVertsPerFace = mesh.faceSizes.data();
    desc.vertIndicesPerFace = mesh.faceIndices.data();
    desc.numCreases = int(creaseWeights.size());
    desc.creaseVertexIndexPairs = creasePairs.data();
    desc.creaseWeights = creaseWeights.data();
    desc.numCorners = int(cornerWeights.size());
    desc.cornerVertexIndices = cornerIds.data();
    desc.cornerWeights = cornerWeights.data();
    Sdc::Options options;
    options.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    return std::unique_ptr<Far::TopologyRefiner>(Factory::Create(desc, Factory::Options(Sdc::SCHEME_CATMARK, options)));
}

}  // namespace

TriangleMesh subdivide(const PolyMesh& mesh, int level, const std::string& source) {
    if (level < 0 || level > 8) throw Error("mesh '" + source + "': subdivision level " + std::to_string(level) + " is outside [0, 8]");
    if (level == 0) return triangulate(mesh, source);
    std::vector<int> creasePairs, cornerIds;
    std::vector<float> creaseWeights, cornerWeights;
    auto refiner = makeRefiner(mesh, creasePairs, creaseWeights, cornerIds, cornerWeights);
    if (!refiner) throw Error("mesh '" + source + "': OpenSubdiv cannot build a topology from it (non-manifold?)");
    refiner->RefineUniform(Far::TopologyRefiner::UniformOptions(level));

    std::vector<RefineVertex> verts(std::size_t(refiner->GetNumVerticesTotal()));
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
        verts[i].p[0] = mesh.positions[i].x(), verts[i].p[1] = mesh.positions[i].y(), verts[i].p[2] = mesh.positions[i].z();
    Far::PrimvarRefiner primvars(*refiner);
    RefineVertex* src = verts.data();
    for (int l = 1; l <= level; ++l) {
        RefineVertex* dst = src + refiner->GetLevel(l - 1).GetNumVertices();
        primvars.Interpolate(l, src, dst);
        src = dst;
    }

    // Each level's child faces are numbered after their parents; walk the
    // parent chain once per face to find the base face's material.
    const Far::TopologyLevel& last = refiner->GetLevel(level);
    PolyMesh refined;
    refined.materials = mesh.materials;
    for (int v = 0; v < last.GetNumVertices(); ++v) refined.positions.emplace_back(src[v].p[0], src[v].p[1], src[v].p[2]);
    std::vector<int> material = mesh.faceMaterial;
    for (int l = 1; l <= level; ++l) {
        const Far::TopologyRefiner& r = *refiner;
        std::vector<int> child(std::size_t(r.GetLevel(l).GetNumFaces()));
        const Far::TopologyLevel& parent = r.GetLevel(l - 1);
        for (int f = 0; f < parent.GetNumFaces(); ++f)
            for (int c : parent.GetFaceChildFaces(f)) child[std::size_t(c)] = material[std::size_t(f)];
        material = std::move(child);
    }
    for (int f = 0; f < last.GetNumFaces(); ++f) {
        const Far::ConstIndexArray fv = last.GetFaceVertices(f);
        for (int k = 0; k < fv.size(); ++k) refined.faceIndices.push_back(fv[k]);
        refined.faceSizes.push_back(fv.size());
        refined.faceMaterial.push_back(material[std::size_t(f)]);
    }
    return triangulate(refined, source);
}

}  // namespace weft
