// One uniform Loop refinement of the same ~1M-triangle lattice as pssurf's bench, with
// OpenSubdiv's Far API (topology refiner + primvar interpolation), timed.
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>
using namespace OpenSubdiv;
struct V { float x, y, z; void Clear(void* = 0) { x = y = z = 0; }
  void AddWithWeight(V const& s, float w) { x += w * s.x; y += w * s.y; z += w * s.z; } };
int main(int argc, char** argv) {
  int n = 707;
  std::vector<V> pos; std::vector<int> idx;
  for (int j = 0; j <= n; ++j) for (int i = 0; i <= n; ++i) {
    double x = i + 0.5 * j, y = 0.866 * j;
    pos.push_back({(float)x, (float)y, (float)(std::sin(0.01 * x) * std::cos(0.02 * y))});
  }
  auto id = [&](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j) for (int i = 0; i < n; ++i) {
    int a[6] = {id(i, j), id(i + 1, j), id(i, j + 1), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)};
    idx.insert(idx.end(), a, a + 6);
  }
  int nf = idx.size() / 3;
  std::vector<int> verts_per_face(nf, 3);
  double best = 1e9;
  for (int rep = 0; rep < 10; ++rep) {
    auto t0 = std::chrono::steady_clock::now();
    Far::TopologyDescriptor desc;
    desc.numVertices = pos.size(); desc.numFaces = nf;
    desc.numVertsPerFace = verts_per_face.data(); desc.vertIndicesPerFace = idx.data();
    Sdc::Options opts; opts.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
    auto* refiner = Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Create(desc,
      Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Options(Sdc::SCHEME_LOOP, opts));
    refiner->RefineUniform(Far::TopologyRefiner::UniformOptions(1));
    std::vector<V> out(refiner->GetLevel(1).GetNumVertices());
    V* src = pos.data(); V* dst = out.data();
    Far::PrimvarRefiner(*refiner).Interpolate(1, src, dst);
    auto t1 = std::chrono::steady_clock::now();
    double s = std::chrono::duration<double>(t1 - t0).count();
    if (s < best) best = s;
    if (rep == 0) printf("faces %d -> %d, vertices %d\n", nf, refiner->GetLevel(1).GetNumFaces(), (int)out.size());
    delete refiner;
  }
  printf("opensubdiv loop one step (topology + refine + interpolate), best of 10: %.3f s\n", best);
}
