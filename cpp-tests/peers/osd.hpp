// OpenSubdiv set up with loopsurf's rules: Loop, VTX_BOUNDARY_EDGE_ONLY,
// infinitely sharp creases on every hard edge.
#pragma once
#include "mesh.hpp"

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

namespace osd = OpenSubdiv::Far;
namespace sdc = OpenSubdiv::Sdc;

// A refiner over the net (hard edges as infinitely sharp creases; vertices
// with three or more of them are corners in OpenSubdiv as in loopsurf).
inline osd::TopologyRefiner* osd_refiner(const Net& n) {
    static std::vector<int> per_face;
    static std::vector<float> weights;
    per_face.assign(n.ntris(), 3);
    weights.assign(n.hard.size() / 2, sdc::Crease::SHARPNESS_INFINITE);
    osd::TopologyDescriptor desc;
    desc.numVertices = int(n.nverts());
    desc.numFaces = int(n.ntris());
    desc.numVertsPerFace = per_face.data();
    desc.vertIndicesPerFace = n.tris.data();
    desc.numCreases = int(n.hard.size() / 2);
    desc.creaseVertexIndexPairs = n.hard.data();
    desc.creaseWeights = weights.data();
    sdc::Options options;
    options.SetVtxBoundaryInterpolation(sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
    typedef osd::TopologyRefinerFactory<osd::TopologyDescriptor> Factory;
    return Factory::Create(desc, Factory::Options(sdc::SCHEME_LOOP, options));
}

struct Point3 {
    double p[3];
    void Clear() { p[0] = p[1] = p[2] = 0; }
    void AddWithWeight(const Point3& s, double w) {
        p[0] += w * s.p[0], p[1] += w * s.p[1], p[2] += w * s.p[2];
    }
};

// Uniform refinement, all levels' points in one buffer; returns the last
// level's points and triangles.
inline void osd_refine(const Net& n, int levels, std::vector<double>& xyz, std::vector<int>& tris) {
    osd::TopologyRefiner* refiner = osd_refiner(n);
    refiner->RefineUniform(osd::TopologyRefiner::UniformOptions(levels));
    std::vector<Point3> points(size_t(refiner->GetNumVerticesTotal()));
    for (size_t i = 0; i < n.nverts(); i++)
        for (int k = 0; k < 3; k++) points[i].p[k] = n.xyz[3 * i + k];
    osd::PrimvarRefinerReal<double> primvar(*refiner);
    Point3* src = points.data();
    for (int level = 1; level <= levels; level++) {
        Point3* dst = src + refiner->GetLevel(level - 1).GetNumVertices();
        primvar.Interpolate(level, src, dst);
        src = dst;
    }
    const osd::TopologyLevel& last = refiner->GetLevel(levels);
    xyz.clear();
    for (int i = 0; i < last.GetNumVertices(); i++) xyz.insert(xyz.end(), {src[i].p[0], src[i].p[1], src[i].p[2]});
    tris.clear();
    for (int f = 0; f < last.GetNumFaces(); f++) {
        auto fv = last.GetFaceVertices(f);
        for (int k = 0; k < fv.size(); k++) tris.push_back(fv[k]);
    }
    delete refiner;
}
