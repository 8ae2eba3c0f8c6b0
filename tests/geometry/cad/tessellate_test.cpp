// Welding through the B-rep topology: closed solids give closed, manifold, outward meshes; poles
// collapse; edges are shared; invalid deflections are refused.
#include <cmath>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "geometry/cad/parametric_mandrel.h"
#include "geometry/cad/tessellate.h"
#include "geometry/mesh/mesh.h"
#include "geometry/mesh/mesh_validation.h"

namespace windplan {
namespace {

double signed_volume(const Mesh& m) {
  double v = 0.0;
  for (const Tri& t : m.triangles()) {
    v += m.position(t[0]).dot(m.position(t[1]).cross(m.position(t[2])));
  }
  return v / 6.0;
}

void expect_closed_outward(const Tessellation& t, double exact_volume) {
  const MeshHealth h = check_mesh(t.soup);
  EXPECT_TRUE(h.closed);
  EXPECT_TRUE(h.manifold);
  EXPECT_TRUE(h.oriented);
  EXPECT_EQ(h.num_components, 1);
  EXPECT_EQ(h.genus, 0);
  EXPECT_EQ(h.num_duplicate_vertices, 0) << "welding through the topology leaves no duplicates";
  EXPECT_EQ(h.num_unreferenced_vertices, 0);
  const Mesh m(t.soup);  // throws on non-manifold or inconsistent input
  EXPECT_TRUE(m.is_closed());
  EXPECT_EQ(m.genus(), 0);
  const double v = signed_volume(m);
  EXPECT_GT(v, 0.0) << "normals must point outward";
  EXPECT_NEAR(v, exact_volume, 0.02 * exact_volume);
}

TEST(Tessellate, PipeIsClosedManifoldOutward) {
  const Tessellation t = tessellate(make_pipe({50, 500}));
  EXPECT_EQ(t.faces.size(), 3u);
  int planes = 0;
  for (const CadFaceInfo& f : t.faces) {
    if (f.kind != CadSurfaceKind::Plane) continue;
    ++planes;
    EXPECT_NEAR(std::abs(f.plane_normal.z()), 1.0, 1e-12);
  }
  EXPECT_EQ(planes, 2);
  EXPECT_EQ(t.triangle_face.size(), t.soup.triangles.size());
  expect_closed_outward(t, M_PI * 50 * 50 * 500);
}

TEST(Tessellate, PlaneNormalsPointOutOfTheSolid) {
  const Tessellation t = tessellate(make_pipe({50, 500}));
  for (std::size_t k = 0; k < t.soup.triangles.size(); ++k) {
    const CadFaceInfo& f = t.faces[t.triangle_face[k]];
    if (f.kind != CadSurfaceKind::Plane) continue;
    const Tri& tri = t.soup.triangles[k];
    const Vec3 c = (t.soup.points[tri[0]] + t.soup.points[tri[1]] + t.soup.points[tri[2]]) / 3;
    // The cap at z = 0 faces -z, the one at z = 500 faces +z.
    EXPECT_GT(f.plane_normal.z() * (c.z() - 250.0), 0.0);
  }
}

TEST(Tessellate, SpherePolesCollapse) {
  const Tessellation t = tessellate(make_sphere(100));
  EXPECT_GT(t.dropped_triangles, 0) << "the triangles at the two poles collapse and are dropped";
  expect_closed_outward(t, 4.0 / 3.0 * M_PI * 1e6);
}

TEST(Tessellate, VesselsAndBentTubeAreClosed) {
  for (DomeType type : {DomeType::Hemispherical, DomeType::Elliptical, DomeType::Isotensoid}) {
    VesselParams v;
    v.dome_start.type = v.dome_end.type = type;
    const Tessellation t = tessellate(make_vessel(v));
    const MeshHealth h = check_mesh(t.soup);
    EXPECT_TRUE(h.closed && h.manifold && h.oriented) << to_string(type);
    EXPECT_EQ(h.genus, 0);
    EXPECT_GT(signed_volume(Mesh(t.soup)), 0.0);
  }
  const double len = 400 + 100 * M_PI / 2;
  expect_closed_outward(tessellate(make_bent_tube({})), M_PI * 25 * 25 * len);
}

TEST(Tessellate, FinerDeflectionGivesMoreTriangles) {
  TessellateOptions coarse, fine;
  coarse.linear_deflection = 1.0;
  fine.linear_deflection = 0.1;
  const CadShape s = make_vessel({});
  EXPECT_GT(tessellate(s, fine).soup.triangles.size(),
            2 * tessellate(s, coarse).soup.triangles.size());
}

TEST(Tessellate, DeflectionMustBePositive) {
  TessellateOptions o;
  o.linear_deflection = 0.0;
  std::string why;
  EXPECT_FALSE(o.is_valid(&why));
  EXPECT_NE(why.find("linear_deflection"), std::string::npos);
  EXPECT_THROW(tessellate(make_pipe({}), o), ConfigError);
  o.linear_deflection = -1.0;
  EXPECT_THROW(tessellate(make_pipe({}), o), ConfigError);
  o.linear_deflection = 0.5;
  o.angular_deflection = 0.0;
  EXPECT_FALSE(o.is_valid(&why));
  EXPECT_NE(why.find("angular_deflection"), std::string::npos);
  EXPECT_NO_THROW(tessellate(make_pipe({}), TessellateOptions{}));
}

}  // namespace
}  // namespace windplan
