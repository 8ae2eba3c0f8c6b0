#include "geometry/mesh/mesh_io.h"

#include <unistd.h>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

namespace fs = std::filesystem;

// A fresh directory per test, removed afterwards.
class MeshIo : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("windplan_mesh_io_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path file(const std::string& name) const { return dir_ / name; }
  fs::path write(const std::string& name, const std::string& bytes) const {
    std::ofstream o(file(name), std::ios::binary);
    o.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return file(name);
  }
  fs::path dir_;
};

// Binary encoders with explicit endianness, independent of the reader's code.
template <class T>
void put(std::string* s, T v, bool big) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  const std::uint16_t one = 1;
  const bool host_little = *reinterpret_cast<const unsigned char*>(&one) == 1;
  if (big == host_little) std::reverse(b, b + sizeof(T));
  s->append(reinterpret_cast<const char*>(b), sizeof(T));
}

void expect_same_soup(const TriangleSoup& a, const TriangleSoup& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i], b.points[i]) << "vertex " << i;
  }
  for (std::size_t i = 0; i < a.triangles.size(); ++i) {
    EXPECT_EQ(a.triangles[i], b.triangles[i]) << "triangle " << i;
  }
}

// Irrational coordinates: a round trip only passes if all 17 digits survive.
TriangleSoup irrational_torus() { return test::torus(3.0 / 7.0, std::sqrt(2.0) / 10.0, 12, 8); }

std::string error_of(const fs::path& p, const MeshReadOptions& o = {}) {
  try {
    read_mesh(p, o);
  } catch (const IoError& e) {
    return e.what();
  }
  return "(no IoError)";
}

// A unit tetrahedron with outward faces: the reference for the hand-written files below.
const std::vector<Vec3> kTetPoints = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
const std::vector<Tri> kTetTris = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

TEST_F(MeshIo, ObjRoundTripIsExact) {
  const TriangleSoup s = irrational_torus();
  write_mesh(file("t.obj"), s);
  expect_same_soup(read_mesh(file("t.obj")), s);
}

TEST_F(MeshIo, BinaryPlyRoundTripIsExact) {
  const TriangleSoup s = irrational_torus();
  write_mesh(file("t.ply"), s);
  std::ifstream in(file("t.ply"), std::ios::binary);
  std::string head(64, '\0');
  in.read(head.data(), 64);
  EXPECT_NE(head.find("binary_little_endian"), std::string::npos);
  expect_same_soup(read_mesh(file("t.ply")), s);
}

TEST_F(MeshIo, AsciiPlyRoundTripIsExact) {
  const TriangleSoup s = irrational_torus();
  MeshWriteOptions o;
  o.ascii_ply = true;
  write_mesh(file("t.ply"), s, o);
  expect_same_soup(read_mesh(file("t.ply")), s);
}

TEST_F(MeshIo, WritesAMeshAndExtensionIsCaseInsensitive) {
  const Mesh m(test::octahedron());
  write_mesh(file("OCTA.OBJ"), m);
  const TriangleSoup r = read_mesh(file("OCTA.OBJ"));
  EXPECT_EQ(r.points, m.points());
  EXPECT_EQ(r.triangles, m.triangles());
}

TEST_F(MeshIo, WriteUnknownExtensionIsIoError) {
  EXPECT_THROW(write_mesh(file("t.stl"), test::octahedron()), IoError);
}

TEST_F(MeshIo, ObjNegativeIndicesQuadsSlashFormsAndIgnoredStatements) {
  const auto p = write("cube_face.obj",
                       "# a comment\n"
                       "mtllib x.mtl\n"
                       "o thing\n"
                       "v 0 0 0\n"
                       "v 1 0 0\n"
                       "v 1 1 0   # trailing comment\n"
                       "v 0 1 0\n"
                       "vt 0 0\nvt 1 0\nvt 1 1\n"
                       "vn 0 0 1\n"
                       "g group\ns 1\nusemtl red\n"
                       "f 1/1/1 2/2/1 3/3/1 4/1/1\n"  // quad -> (0,1,2), (0,2,3)
                       "f -4//1 -2//1 -1//1\n"        // relative: (0,2,3)
                       "f -4/1 -3/2 -2/3\n"           // v/vt: (0,1,2)
                       "v 0.5 0.5 +1e0\n"
                       "f 1 2 5\n");
  const TriangleSoup s = read_mesh(p);
  ASSERT_EQ(s.points.size(), 5u);
  EXPECT_EQ(s.points[4], Vec3(0.5, 0.5, 1.0));
  const std::vector<Tri> expected = {{0, 1, 2}, {0, 2, 3}, {0, 2, 3}, {0, 1, 2}, {0, 1, 4}};
  EXPECT_EQ(s.triangles, expected);
}

TEST_F(MeshIo, WindowsLineEndings) {
  const TriangleSoup o =
      read_mesh(write("crlf.obj", "v 0 0 0\r\nv 1 0 0\r\nv 0 1.5 0\r\nf 1 2 3\r\n"));
  ASSERT_EQ(o.points.size(), 3u);
  EXPECT_EQ(o.points[2], Vec3(0, 1.5, 0));
  const TriangleSoup f =
      read_mesh(write("crlf.off", "OFF\r\n3 1 0\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 2\r\n"));
  EXPECT_EQ(f.triangles.size(), 1u);
  const TriangleSoup p =
      read_mesh(write("crlf.ply",
                      "ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty float x\r\n"
                      "property float y\r\nproperty float z\r\nelement face 1\r\n"
                      "property list uchar int vertex_indices\r\nend_header\r\n"
                      "0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 2\r\n"));
  EXPECT_EQ(p.triangles.size(), 1u);
}

TEST_F(MeshIo, OffWithCommentsAndPolygons) {
  const auto p = write("q.off",
                       "OFF\n"
                       "# a comment line\n"
                       "5 2 0\n"
                       "0 0 0\n1 0 0 # comment after a vertex\n1 1 0\n0 1 0\n"
                       "\n"
                       "0.5 0.5 1\n"
                       "4 0 1 2 3\n"
                       "3 0 1 4 255 0 0\n");  // a face colour is ignored
  const TriangleSoup s = read_mesh(p);
  ASSERT_EQ(s.points.size(), 5u);
  EXPECT_EQ(s.points[4], Vec3(0.5, 0.5, 1.0));
  const std::vector<Tri> expected = {{0, 1, 2}, {0, 2, 3}, {0, 1, 4}};
  EXPECT_EQ(s.triangles, expected);
}

TEST_F(MeshIo, OffCountsOnTheHeaderLine) {
  const auto p = write("h.off", "OFF 3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const TriangleSoup s = read_mesh(p);
  EXPECT_EQ(s.points.size(), 3u);
  EXPECT_EQ(s.triangles.size(), 1u);
}

TEST_F(MeshIo, AsciiPlyWithExtraPropertiesAndQuad) {
  const auto p =
      write("a.ply",
            "ply\nformat ascii 1.0\ncomment hand written\n"
            "element vertex 4\nproperty float x\nproperty uchar red\n"
            "property float y\nproperty float z\nproperty list uchar float junk\n"
            "element face 1\nproperty uchar flags\nproperty list uchar int vertex_indices\n"
            "property float quality\nend_header\n"
            "0 7 0 0 2 0.5 0.5\n1 7 0 0 0\n1 7 1 0 1 9\n0 7 1 0 3 1 2 3\n"
            "3 4 0 1 2 3 0.25\n");
  const TriangleSoup s = read_mesh(p);
  ASSERT_EQ(s.points.size(), 4u);
  EXPECT_EQ(s.points[2], Vec3(1, 1, 0));
  const std::vector<Tri> expected = {{0, 1, 2}, {0, 2, 3}};
  EXPECT_EQ(s.triangles, expected);
}

// The same tetrahedron as binary PLY in both byte orders, with properties of every size before,
// between and after x, y, z, a skipped extra element, and 16-bit list counts with uint indices.
std::string binary_tet_ply(bool big) {
  std::string s = std::string("ply\nformat ") +
                  (big ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\n"
                  "element vertex 4\nproperty int16 id\nproperty double x\nproperty float y\n"
                  "property uchar alpha\nproperty double z\nproperty list uchar int junk\n"
                  "element material 2\nproperty float shine\nproperty int8 k\n"
                  "element face 4\nproperty list ushort uint vertex_indices\nproperty uint32 tag\n"
                  "end_header\n";
  for (std::size_t i = 0; i < kTetPoints.size(); ++i) {
    put<std::int16_t>(&s, static_cast<std::int16_t>(-static_cast<int>(i)), big);
    put<double>(&s, kTetPoints[i].x(), big);
    put<float>(&s, static_cast<float>(kTetPoints[i].y()), big);
    put<std::uint8_t>(&s, 200, big);
    put<double>(&s, kTetPoints[i].z(), big);
    put<std::uint8_t>(&s, static_cast<std::uint8_t>(i % 3), big);
    for (std::size_t j = 0; j < i % 3; ++j) put<std::int32_t>(&s, 77, big);
  }
  for (int m = 0; m < 2; ++m) {
    put<float>(&s, 0.5f, big);
    put<std::int8_t>(&s, -3, big);
  }
  for (const Tri& t : kTetTris) {
    put<std::uint16_t>(&s, 3, big);
    for (int v : t) put<std::uint32_t>(&s, static_cast<std::uint32_t>(v), big);
    put<std::uint32_t>(&s, 0xdeadbeef, big);
  }
  return s;
}

TEST_F(MeshIo, BinaryPlyLittleEndian) {
  const TriangleSoup s = read_mesh(write("le.ply", binary_tet_ply(false)));
  EXPECT_EQ(s.points, kTetPoints);
  EXPECT_EQ(s.triangles, kTetTris);
}

TEST_F(MeshIo, BinaryPlyBigEndian) {
  const TriangleSoup s = read_mesh(write("be.ply", binary_tet_ply(true)));
  EXPECT_EQ(s.points, kTetPoints);
  EXPECT_EQ(s.triangles, kTetTris);
}

std::string ascii_tet_stl() {
  std::string s = "solid tet\n";
  for (const Tri& t : kTetTris) {
    s += "  facet normal 0 0 0\n    outer loop\n";
    for (int v : t) {
      char buf[128];
      std::snprintf(buf, sizeof buf, "      vertex %g %g %g\n", kTetPoints[v].x(),
                    kTetPoints[v].y(), kTetPoints[v].z());
      s += buf;
    }
    s += "    endloop\n  endfacet\n";
  }
  return s + "endsolid tet\n";
}

std::string binary_tet_stl(const std::string& header80, float jitter = 0.0f) {
  std::string s = header80;
  s.resize(80, ' ');
  put<std::uint32_t>(&s, static_cast<std::uint32_t>(kTetTris.size()), false);
  int corner = 0;
  for (const Tri& t : kTetTris) {
    for (int k = 0; k < 3; ++k) put<float>(&s, 0.0f, false);
    for (int v : t) {
      // Corner c is moved by c * jitter: every corner distinct, copies within 11 * jitter.
      const float d = static_cast<float>(corner++) * jitter;
      for (int k = 0; k < 3; ++k) put<float>(&s, static_cast<float>(kTetPoints[v][k]) + d, false);
    }
    put<std::uint16_t>(&s, 0, false);
  }
  return s;
}

TEST_F(MeshIo, AsciiStlIsWelded) {
  const TriangleSoup s = read_mesh(write("a.stl", ascii_tet_stl()));
  // 12 corners welded into the 4 vertices, in order of first appearance: 0, 2, 1, 3.
  ASSERT_EQ(s.points.size(), 4u);
  EXPECT_EQ(s.points[1], kTetPoints[2]);
  EXPECT_EQ(s.triangles.size(), 4u);
  for (int f = 0; f < 4; ++f)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(s.points[s.triangles[f][k]], kTetPoints[kTetTris[f][k]]);
}

TEST_F(MeshIo, BinaryStlWhoseHeaderStartsWithSolid) {
  const TriangleSoup s =
      read_mesh(write("b.stl", binary_tet_stl("solid but binary, facet vertex words inside")));
  ASSERT_EQ(s.points.size(), 4u);
  for (int f = 0; f < 4; ++f)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(s.points[s.triangles[f][k]], kTetPoints[kTetTris[f][k]]);
}

TEST_F(MeshIo, StlWeldToleranceIsRelativeToTheDiagonal) {
  // Copies differ by up to 11 * 2^-23 ~ 1.3e-6 per axis against a diagonal of ~sqrt(3): welded
  // at a relative 1e-5, kept apart at the default 1e-9 (2^-23 is the float spacing at 1).
  const auto p = write("j.stl", binary_tet_stl("jittered", 1.0f / (1 << 23)));
  MeshReadOptions loose;
  loose.weld_tolerance = 1e-5;
  EXPECT_EQ(read_mesh(p, loose).points.size(), 4u);
  EXPECT_EQ(read_mesh(p).points.size(), 12u);
}

TEST_F(MeshIo, WeldVerticesMergesWithinToleranceOnly) {
  TriangleSoup s;
  s.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1e-7, 0, 0), Vec3(1, 0, 2e-6)};
  s.triangles = {{0, 1, 2}, {3, 4, 2}};
  const TriangleSoup w = weld_vertices(s, 1e-6);
  ASSERT_EQ(w.points.size(), 4u);  // 3 -> 0; 4 stays (2e-6 away from 1)
  const std::vector<Tri> expected = {{0, 1, 2}, {0, 3, 2}};
  EXPECT_EQ(w.triangles, expected);
}

// ---- bad input: each an IoError naming the file ----

TEST_F(MeshIo, MissingFile) {
  const std::string e = error_of(file("nope.obj"));
  EXPECT_NE(e.find("nope.obj"), std::string::npos) << e;
  EXPECT_NE(e.find("no such file"), std::string::npos) << e;
}

TEST_F(MeshIo, EmptyFile) {
  for (const char* name : {"e.obj", "e.ply", "e.stl", "e.off"}) {
    const std::string e = error_of(write(name, ""));
    EXPECT_NE(e.find(name), std::string::npos) << e;
    EXPECT_NE(e.find("empty"), std::string::npos) << e;
  }
}

TEST_F(MeshIo, UnknownExtensionNamesItAndTheSupportedOnes) {
  const std::string e = error_of(write("m.xyz", "1 2 3\n"));
  EXPECT_NE(e.find("m.xyz"), std::string::npos) << e;
  EXPECT_NE(e.find("'.xyz'"), std::string::npos) << e;
  EXPECT_NE(e.find(".obj, .off, .ply, .stl"), std::string::npos) << e;
}

TEST_F(MeshIo, TruncatedBinaryPlySaysExpectedAndActualSize) {
  const std::string full = binary_tet_ply(false);
  const std::string cut = full.substr(0, full.size() - 10);
  const std::string e = error_of(write("cut.ply", cut));
  EXPECT_NE(e.find("cut.ply"), std::string::npos) << e;
  EXPECT_NE(e.find("truncated"), std::string::npos) << e;
  EXPECT_NE(e.find("face 3 of 4"), std::string::npos) << e;
  EXPECT_NE(e.find("the file has " + std::to_string(cut.size()) + " bytes"), std::string::npos)
      << e;
}

TEST_F(MeshIo, TruncatedBinaryStlSaysExpectedAndActualSize) {
  const std::string full = binary_tet_stl("solid looks ascii");
  const std::string cut = full.substr(0, full.size() - 7);
  const std::string e = error_of(write("cut.stl", cut));
  EXPECT_NE(e.find("cut.stl"), std::string::npos) << e;
  EXPECT_NE(e.find("84 + 50 * 4 = 284 bytes"), std::string::npos) << e;
  EXPECT_NE(e.find("it has " + std::to_string(cut.size())), std::string::npos) << e;
}

TEST_F(MeshIo, AHeaderClaimingBillionsFailsAsTruncatedWithoutAllocatingThem) {
  const std::string e =
      error_of(write("huge.ply",
                     "ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\n"
                     "property float x\nproperty float y\nproperty float z\nend_header\nabc"));
  EXPECT_NE(e.find("vertex 0 of 2000000000"), std::string::npos) << e;
  const std::string o = error_of(write("huge.off", "OFF\n2000000000 1 0\n0 0 0\n"));
  EXPECT_NE(o.find("expected 2000000000 vertices, found 1"), std::string::npos) << o;
  const std::string t = error_of(
      write("big.ply",
            "ply\nformat ascii 1.0\nelement vertex 9000000000\nproperty float x\nend_header\n"));
  EXPECT_NE(t.find("too large"), std::string::npos) << t;
}

TEST_F(MeshIo, ObjFaceIndexOutOfRangeNamesTheLine) {
  const std::string e = error_of(write("r.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n"));
  EXPECT_NE(e.find("r.obj:5:"), std::string::npos) << e;
  EXPECT_NE(e.find("face index 4 is out of range"), std::string::npos) << e;
  const std::string e0 = error_of(write("z.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"));
  EXPECT_NE(e0.find("z.obj:4:"), std::string::npos) << e0;
  const std::string en = error_of(write("n.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n"));
  EXPECT_NE(en.find("n.obj:4:"), std::string::npos) << en;
}

TEST_F(MeshIo, NanCoordinatesNameTheVertex) {
  const std::string e = error_of(write("nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n"));
  EXPECT_NE(e.find("nan.obj:2:"), std::string::npos) << e;
  EXPECT_NE(e.find("vertex 1 has a NaN or infinite coordinate"), std::string::npos) << e;
  const std::string eo = error_of(write("inf.off", "OFF\n3 1 0\n0 0 0\n1 0 inf\n0 1 0\n3 0 1 2\n"));
  EXPECT_NE(eo.find("inf.off:4:"), std::string::npos) << eo;
  std::string ply = binary_tet_ply(false);
  // Overwrite vertex 2's x (after the header and 2 vertex records) with a NaN.
  const std::size_t body = ply.find("end_header\n") + 11;
  const std::size_t rec0 = 2 + 8 + 4 + 1 + 8 + 1, rec1 = rec0 + 4;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::memcpy(&ply[body + rec0 + rec1 + 2], &nan, 8);
  const std::string ep = error_of(write("nan.ply", ply));
  EXPECT_NE(ep.find("vertex 2 has a NaN"), std::string::npos) << ep;
  std::string stl = binary_tet_stl("x");
  const float fnan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&stl[84 + 50 + 12 + 12 + 4], &fnan, 4);  // triangle 1, corner 1, y
  const std::string es = error_of(write("nan.stl", stl));
  EXPECT_NE(es.find("triangle 1 corner 1 has a NaN"), std::string::npos) << es;
}

// Issue 28: a 'v' line with many numbers was read as one vertex (every index after it shifted).
TEST_F(MeshIo, ObjVertexLinesHoldThreeFourOrSixNumbers) {
  std::string many = "v 0 0 0\nv 1 0 0";
  for (int i = 0; i < 1000; ++i) many += " 0 1 0";
  many += "\nv 0 1 0\nf 1 2 3\n";
  const std::string e = error_of(write("many.obj", many));
  EXPECT_NE(e.find("many.obj:2: a 'v' line with more than 6 numbers"), std::string::npos) << e;
  const std::string e5 = error_of(write("five.obj", "v 0 0 0 1 1\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  EXPECT_NE(e5.find("five.obj:1: a 'v' line with 5 numbers"), std::string::npos) << e5;
  // w, and r g b vertex colours, as other programs write them; a trailing comment.
  const TriangleSoup ok =
      read_mesh(write("ok.obj", "v 0 0 0 1\nv 1 0 0 0.5 0.5 0.5\nv 0 1 0 # top\nf 1 2 3\n"));
  ASSERT_EQ(ok.points.size(), 3u);
  EXPECT_EQ(ok.points[1], Vec3(1, 0, 0));
}

TEST_F(MeshIo, MalformedNumbersNameTheLine) {
  const std::string e = error_of(write("m.obj", "v 0 0 0\nv 1 0x 0\n"));
  EXPECT_NE(e.find("m.obj:2:"), std::string::npos) << e;
  EXPECT_NE(e.find("'0x'"), std::string::npos) << e;
  const std::string ef = error_of(write("f.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 two 3\n"));
  EXPECT_NE(ef.find("f.obj:4:"), std::string::npos) << ef;
  const std::string eo = error_of(write("m.off", "OFF\n3 1 0\n0 0 0\n1 0 zero\n0 1 0\n3 0 1 2\n"));
  EXPECT_NE(eo.find("m.off:4:"), std::string::npos) << eo;
  const std::string ep =
      error_of(write("m.ply",
                     "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                     "property float z\nend_header\n0 1,5 0\n"));
  EXPECT_NE(ep.find("m.ply:8:"), std::string::npos) << ep;
}

TEST_F(MeshIo, TruncatedTextFiles) {
  const std::string eo =
      error_of(write("t.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n"));
  EXPECT_NE(eo.find("expected 2 faces, found 1"), std::string::npos) << eo;
  const std::string ep =
      error_of(write("t.ply",
                     "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                     "property float z\nend_header\n0 0 0\n1 0\n"));
  EXPECT_NE(ep.find("truncated ascii PLY"), std::string::npos) << ep;
  EXPECT_NE(
      error_of(write("h.ply", "ply\nformat ascii 1.0\nelement vertex 2\n")).find("end_header"),
      std::string::npos);
}

}  // namespace
}  // namespace windplan
